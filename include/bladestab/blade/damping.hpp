#pragma once
// Structural damping matrix C_D for the [damping] section of a scene.
#include <Eigen/Dense>

#include "bladestab/blade/model.hpp"
#include "bladestab/scene/scene.hpp"

namespace bladestab {

// none:     0
// modal:    M Φ diag(2ζω_k) Φᵀ M, Φ the mass-normalized undamped, non-gyroscopic modes at Ω
// rayleigh: αM + βK_S with ζ met exactly at the two given frequencies (K_S: the elastic stiffness,
//           without a static tip compression)
// paper:    (2ζ/Ω) K_S, the paper's (37); undefined at Ω = 0
Eigen::MatrixXd damping_matrix(const BladeModel& model, const DampingSpec& spec, double speed_rad_s);

}  // namespace bladestab
