// Validation of the lattice-gas engine's sections [lattice], [tagged] and [colloid] (engine
// "lgca"), called by parse_scene.
#pragma once

#include "narrows/scene/scene.hpp"

#include "checker.hpp"

#include <toml.hpp>

namespace narrows::scene::detail {

// The sections of an lgca scene from its table `root`, into `s`.
void parse_lgca_scene(const Checker &c, const toml::value &root, Scene &s);

// `section` may be null (missing [lattice]).
Lgca parse_lgca(const toml::value *section, const Checker &c);

// `section` is the [tagged] ([colloid]) table (not null).
Tagged parse_tagged(const toml::value &section, const Lgca &lattice, const Checker &c);
LgcaColloid parse_colloid(const toml::value &section, const Lgca &lattice, const Checker &c);

} // namespace narrows::scene::detail
