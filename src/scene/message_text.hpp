// The words of the scene's one-line messages: TOML values rendered short, lists joined, and the
// "did you mean" suggestion for a misspelt name.
#pragma once

#include <toml.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace narrows::scene::detail {

// Shortest round-trip text of a number, always with a '.' or exponent (nan, inf as such).
std::string float_text(double x);
// A short one-line rendering of a value for messages (nested arrays and tables abridged).
std::string repr(const toml::value &v, int depth = 0);
const char *type_name(const toml::value &v);

std::string join(const std::vector<std::string> &items, const char *sep = ", ");
std::string trim(std::string_view s);
// Messages are one line whatever the input contains: newlines become spaces.
std::string one_line(std::string s);
// The closest candidate within a small edit distance (case-insensitive), or "".
std::string closest(const std::string &word, const std::vector<std::string> &candidates);

} // namespace narrows::scene::detail
