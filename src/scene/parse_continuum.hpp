// Validation of the [continuum] section (engine "continuum"), called by scene/parse.cpp.
#pragma once

#include "narrows/scene/scene.hpp"

#include "section_checker.hpp"

#include <toml.hpp>

namespace narrows::scene::detail {

// `section` may be null (missing [continuum]); fail(key, message) throws.
Continuum parse_continuum(const toml::value *section, const SectionFail &fail);

} // namespace narrows::scene::detail
