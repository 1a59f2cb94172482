#pragma once
// TOML text shared by the tests that parse a scene written inline.
#include <string>

namespace testing_support {

// The [model] section of a Timoshenko blade in 8 Legendre terms with the axial field and Coriolis.
inline const std::string legendre_model_section = R"([model]
basis = "legendre"
terms = 8
theory = "timoshenko"
axial = true
coriolis = true
)";

}  // namespace testing_support
