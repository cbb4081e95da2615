// Validation of [run] and [output], the sections of every engine (parse_common.cpp).
#pragma once

#include "checker.hpp"
#include "narrows/scene/scene.hpp"

#include <toml.hpp>

namespace narrows::scene::detail {

// run.engine (default mpcd); `run` is the [run] table or null.
Engine parse_engine(const Checker &c, const toml::value *run);
// The other keys of [run]; out.engine is set.
void parse_run(const Checker &c, const toml::value *run, Run &out);
// [output] (may be null); out.observables holds the engine's defaults unless the scene lists
// them.
void parse_output(const Checker &c, const toml::value *o, Engine engine, Output &out);

} // namespace narrows::scene::detail
