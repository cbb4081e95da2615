// The canonical form of a scene and the one comparison a restart makes with it: a checkpoint
// continues only the scene it was written by (docs/architecture.md, "Scenes").
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace narrows::scene {

// The scene's TOML table (after --set) as one line per leaf, "a.b.c = value", sorted by key:
// integers and integral floats print alike (10 and 10.0 are the same number), other floats as
// the shortest text that reads back to the same double, strings quoted; arrays and empty
// tables are leaves. It is valid TOML with the same meaning, and two scenes that differ only in
// comments, layout, key order or number spelling have the same canonical text.
std::string canonical_text(const std::string &toml_text, const std::string &file);

// The first key (run.engine, run.dimensions, then in sorted order) whose value differs between the
// scene given now and the checkpoint's stored scene (canonical or original text, either works),
// skipping run.steps, output.* and the keys listed in `may_change` (exact keys, e.g.
// "kmc.replicas"). A missing value is "(not set)"; a whole top-level table present on one side only
// is named as the table ("[walls]"). Throws input_error if the stored text does not parse.
struct SceneDifference {
  std::string key, given, stored;
};
std::optional<SceneDifference> first_difference(const std::string &given_text,
                                                const std::string &stored_text,
                                                const std::string &stored_name,
                                                const std::vector<std::string> &may_change = {});

} // namespace narrows::scene
