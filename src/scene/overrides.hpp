// Command-line overrides of scene keys (overrides.cpp).
#pragma once

#include "checker.hpp"

#include <toml.hpp>

#include <string>

namespace narrows::scene::detail {

// Applies one "--set a.b=value" (`text`) to the scene's table `root`, and tells the checker
// that the key came from it (its messages then name the override).
void apply_override(Checker &c, toml::value &root, const std::string &text);

} // namespace narrows::scene::detail
