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

}  // namespace testing_support
