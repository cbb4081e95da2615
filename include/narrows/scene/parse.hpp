// Reading a scene: TOML text -> validated scene::Scene, with --set overrides applied first.
#pragma once

#include "narrows/scene/scene.hpp"

#include <string>
#include <vector>

namespace narrows::scene {

// Reads and validates the scene file. Each override is "key.path=value" where value is a
// TOML value (3, 0.05, true, [32.0, 64.0], "srd") or a bare word taken as a string.
// Any problem throws narrows::Error with ExitCode::bad_input and one line naming the file,
// the key, what was found and what is allowed. The sections, keys and observables a scene may
// have are those of scene/schema.hpp.
Scene load_scene(const std::string &path, const std::vector<std::string> &overrides = {});

// Same, from text already in memory; `file` is only used in messages.
Scene parse_scene(const std::string &text, const std::string &file,
                  const std::vector<std::string> &overrides = {});

} // namespace narrows::scene
