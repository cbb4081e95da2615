// Command-line overrides: "--set section.key=value" applied to the scene's TOML table before it
// is validated, the key checked against the schema, the value read as TOML (or a bare word as a
// string).
#include "overrides.hpp"

#include "narrows/core/error.hpp"
#include "narrows/scene/schema.hpp"
#include "toml_errors.hpp"
#include "unknown_names.hpp"

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

namespace narrows::scene::detail {

using toml::value;

void apply_override(Checker &c, value &root, const std::string &text) {
  const auto eq = text.find('=');
  std::vector<std::string> parts;
  if (eq != std::string::npos) {
    const std::string path = trim(std::string_view(text).substr(0, eq));
    std::size_t start = 0;
    while (true) {
      const auto dot = path.find('.', start);
      parts.push_back(trim(path.substr(start, dot == std::string::npos ? dot : dot - start)));
      if (dot == std::string::npos)
        break;
      start = dot + 1;
    }
  }
  if (eq == std::string::npos || parts.size() < 2 ||
      std::any_of(parts.begin(), parts.end(), [](const std::string &p) { return p.empty(); }))
    c.fail_set(text, "expected key.path=value (e.g. --set fluid.dt=0.05)");

  const std::string key = parts[0] + "." + parts[1];
  const SectionSpec *sec = find_section(parts[0]);
  if (sec == nullptr)
    c.fail_set(text, "unknown key '" + join(parts, ".") +
                         "'; allowed sections: " + join(section_names()) +
                         (closest(parts[0], section_names()).empty()
                              ? std::string()
                              : "; did you mean [" + closest(parts[0], section_names()) + "]?"));
  if (find_key(sec->keys, parts[1]) == nullptr)
    c.fail_set(text, unknown_key_message(parts[0], parts[1]));

  // The value: a TOML value if it parses as one, else the raw text as a string.
  const std::string raw = trim(std::string_view(text).substr(eq + 1));
  value parsed = raw;
  try {
    try {
      check_raw_text("v = " + raw, "--set '" + one_line(text) + "'");
    } catch (const Error &e) {
      throw input_error(std::string(e.what()) + " (overriding " + c.file() + ")");
    }
    std::istringstream in("v = " + raw);
    const value t = toml::parse(in, "--set");
    if (t.is_table() && t.as_table().size() == 1 && t.contains("v"))
      parsed = t.at("v");
  } catch (const Error &) {
    throw; // too long or too deep for the parser
  } catch (const std::exception &) {
    // not a TOML value: keep the bare word as a string
  }

  auto &table = root.as_table();
  auto it = table.find(parts[0]);
  if (it == table.end())
    it = table.emplace(parts[0], toml::table{}).first;
  if (!it->second.is_table())
    c.fail_set(text, parts[0] + ": found " + repr(it->second) + " (" + type_name(it->second) +
                         ") in the scene; allowed: a table [" + parts[0] + "]");
  // Deeper paths (kmc.initial.site, kmc.parameters.h3) set one entry of a table-valued key;
  // its section's parser validates the entry like any other.
  value *slot = &it->second.as_table()[parts[1]];
  for (std::size_t i = 2; i < parts.size(); ++i) {
    if (slot->is_uninitialized())
      *slot = toml::table{};
    if (!slot->is_table())
      c.fail_set(text, "unknown key '" + join(parts, ".") + "'; " +
                           join(std::vector<std::string>(parts.begin(), parts.begin() + i), ".") +
                           " is a " + type_name(*slot) + ", not a table, so it has no sub-keys");
    slot = &slot->as_table()[parts[i]];
  }
  *slot = std::move(parsed);
  c.from_override(key, text);
}

} // namespace narrows::scene::detail
