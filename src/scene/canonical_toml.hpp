// The canonical text of a parsed TOML table (scene/canonical.hpp), for parse.cpp.
#pragma once

#include <toml.hpp>

#include <string>

namespace narrows::scene::detail {

std::string canonical_text(const toml::value &root);

} // namespace narrows::scene::detail
