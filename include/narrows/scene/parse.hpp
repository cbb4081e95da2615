// Reading a scene: TOML text -> validated scene::Scene, with --set overrides applied first.
#pragma once

#include "narrows/scene/scene.hpp"

#include <string>
#include <vector>

namespace narrows::scene {

// Reads and validates the scene file. Each override is "key.path=value" where value is a
// TOML value (3, 0.05, true, [32.0, 64.0], "srd") or a bare word taken as a string.
// Any problem throws narrows::Error with ExitCode::bad_input and one line naming the file,
// the key, what was found and what is allowed.
Scene load_scene(const std::string &path, const std::vector<std::string> &overrides = {});

// The keys the validator accepts with an engine ("section.key", in the order of
// its sections) and the names output.observables accepts with it. docs/scenes.md is checked against
// these both ways (tests/unit/test_scene_docs.cpp).
struct AcceptedKeys {
  std::vector<std::string> keys;
  std::vector<std::string> observables;
};
AcceptedKeys accepted_keys(Engine engine);

// Same, from text already in memory; `file` is only used in messages.
Scene parse_scene(const std::string &text, const std::string &file,
                  const std::vector<std::string> &overrides = {});

} // namespace narrows::scene
