#pragma once
// The paper's example blade (docs/theory.md §7) as a scene, with overrides, for tests.
#include <string>
#include <vector>

#include "bladestab/scene/scene.hpp"

namespace testing_support {

inline std::string paper_scene_path() { return std::string(BLADESTAB_SOURCE_DIR) + "/stability_maps/sinha2005/blade.toml"; }

inline bladestab::Scene paper_scene(const std::vector<std::string>& overrides = {}) {
  return bladestab::load_scene(paper_scene_path(), overrides);
}

// The overrides that make the paper blade Mathieu's equation, y'' + ω0²(1 − F̄/2 + (F̄/2) cos θt) y = 0:
// one Euler–Bernoulli sine term, no axial field, at rest, under the cosine load of peak F̄.
inline std::vector<std::string> mathieu_overrides(double fbar) {
  return {"model.theory=euler-bernoulli", "model.terms=1", "model.axial=false", "model.basis=sine",
          "operation.speed_rad_s=0", "load.approximation=cosine", "load.fmax_over_fcr=" + std::to_string(fbar)};
}

inline bladestab::Scene mathieu_scene(double fbar, const std::vector<std::string>& more = {}) {
  std::vector<std::string> o = mathieu_overrides(fbar);
  o.insert(o.end(), more.begin(), more.end());
  return paper_scene(o);
}

}  // namespace testing_support
