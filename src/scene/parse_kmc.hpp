// Validation of the [kmc] section (engine "kmc"), called by scene/parse.cpp.
#pragma once

#include "narrows/scene/scene.hpp"

#include <toml.hpp>

#include <functional>
#include <string>

namespace narrows::scene::detail {

// fail(key, message) throws the one-line input error (it never returns); the caller adds the
// source (file or --set). `section` may be null (missing [kmc]).
using KmcFail = std::function<void(const std::string &key, const std::string &message)>;

Kmc parse_kmc(const toml::value *section, const KmcFail &fail);

} // namespace narrows::scene::detail
