// Validation of the [kmc] section (engine "kmc"), called by scene/parse.cpp.
#pragma once

#include "narrows/scene/scene.hpp"

#include "section_checker.hpp"

#include <toml.hpp>

#include <functional>
#include <string>

namespace narrows::scene::detail {

// `section` may be null (missing [kmc]); fail(key, message) throws (section_checker.hpp).
using KmcFail = SectionFail;

Kmc parse_kmc(const toml::value *section, const KmcFail &fail);

} // namespace narrows::scene::detail
