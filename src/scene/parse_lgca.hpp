// Validation of the [lattice] and [tagged] sections (engine "lgca"), called by scene/parse.cpp.
#pragma once

#include "narrows/scene/scene.hpp"

#include "section_checker.hpp"

#include <toml.hpp>

namespace narrows::scene::detail {

// `section` may be null (missing [lattice]).
Lgca parse_lgca(const toml::value *section, const SectionFail &fail);

// `section` is the [tagged] table (not null).
Tagged parse_tagged(const toml::value &section, const Lgca &lattice, const SectionFail &fail);
LgcaColloid parse_colloid(const toml::value &section, const Lgca &lattice, const SectionFail &fail);

} // namespace narrows::scene::detail
