// Helpers of the section parsers: value renderings for messages, look-ups.
#include "section_checker.hpp"

#include <charconv>

namespace narrows::scene::detail {

std::string number_text(double x) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  std::string s(buf, res.ptr);
  if (s.find_first_of(".en") == std::string::npos)
    s += ".0";
  return s;
}

// A short one-line rendering of a value for messages.
std::string repr(const toml::value &v) {
  if (v.is_integer())
    return std::to_string(v.as_integer());
  if (v.is_floating())
    return number_text(v.as_floating());
  if (v.is_string())
    return "\"" + v.as_string().str + "\"";
  std::string s = toml::format(v);
  for (char &c : s)
    if (c == '\n' || c == '\r')
      c = ' ';
  if (s.size() > 70)
    s = s.substr(0, 67) + "...";
  return s;
}

const char *type_name(const toml::value &v) {
  switch (v.type()) {
  case toml::value_t::boolean:
    return "boolean";
  case toml::value_t::integer:
    return "integer";
  case toml::value_t::floating:
    return "float";
  case toml::value_t::string:
    return "string";
  case toml::value_t::array:
    return "array";
  case toml::value_t::table:
    return "table";
  default:
    return "other";
  }
}

const toml::value *find(const toml::value *table, const char *key) {
  if (table == nullptr)
    return nullptr;
  const auto &t = table->as_table();
  const auto it = t.find(key);
  return it == t.end() ? nullptr : &it->second;
}

std::map<std::string, const toml::value *> sorted(const toml::value &table) {
  std::map<std::string, const toml::value *> out;
  for (const auto &[k, v] : table.as_table())
    out.emplace(k, &v);
  return out;
}

} // namespace narrows::scene::detail
