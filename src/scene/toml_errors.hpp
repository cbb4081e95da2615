// Reading TOML text with one-line errors (toml_errors.cpp).
#pragma once

#include <toml.hpp>

#include <string>

namespace narrows::scene::detail {

// Refuses (input_error naming `file`) a text toml11 must not parse: too long, binary (a NUL
// byte), empty, nested deeper than toml11's recursion allows, or with an integer beyond 64 bits.
void check_raw_text(const std::string &text, const std::string &file);

// The TOML table of `text`; a syntax error becomes one line "file: line N: TOML syntax error:
// ..." (the line of `text`).
toml::value parse_toml(const std::string &text, const std::string &file);

} // namespace narrows::scene::detail
