// The messages for names the schema does not know (scene/schema.hpp): a misspelt section or key
// is named with the allowed ones and the likeliest meant one.
#pragma once

#include <toml.hpp>

#include <string>
#include <vector>

namespace narrows::scene::detail {

// Every section's name, in the schema's order.
std::vector<std::string> section_names();
// "unknown key 'section.key'; allowed keys in [section]: ...; did you mean ...?"
std::string unknown_key_message(const std::string &section, const std::string &key);
// The message for a top-level name that is no section (`v`: its value, a table or not).
std::string unknown_section_message(const std::string &name, const toml::value &v);

} // namespace narrows::scene::detail
