// Helpers of the section parsers: value renderings for messages, look-ups.
#include "section_checker.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

namespace narrows::scene::detail {

namespace {

std::string join(const std::vector<std::string> &items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i)
    out += (i ? ", " : "") + items[i];
  return out;
}

} // namespace

const char *type_name(const toml::value &v) {
  switch (v.type()) {
  case toml::value_t::empty:
    return "empty";
  case toml::value_t::boolean:
    return "boolean";
  case toml::value_t::integer:
    return "integer";
  case toml::value_t::floating:
    return "float";
  case toml::value_t::string:
    return "string";
  case toml::value_t::offset_datetime:
    return "offset date-time";
  case toml::value_t::local_datetime:
    return "local date-time";
  case toml::value_t::local_date:
    return "local date";
  case toml::value_t::local_time:
    return "local time";
  case toml::value_t::array:
    return "array";
  case toml::value_t::table:
    return "table";
  }
  return "unknown";
}

std::string float_text(double x) {
  if (std::isnan(x))
    return "nan";
  if (std::isinf(x))
    return x > 0 ? "inf" : "-inf";
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  std::string s(buf, res.ptr);
  if (s.find_first_of(".e") == std::string::npos)
    s += ".0";
  return s;
}

std::string quote_string(const std::string &s) {
  std::string out = "\"";
  for (const char ch : s) {
    switch (ch) {
    case '"':
      out += "\\\"";
      break;
    case '\\':
      out += "\\\\";
      break;
    case '\n':
      out += "\\n";
      break;
    case '\r':
      out += "\\r";
      break;
    case '\t':
      out += "\\t";
      break;
    default:
      if (static_cast<unsigned char>(ch) < 0x20) {
        char buf[8];
        std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(ch));
        out += buf;
      } else {
        out += ch;
      }
    }
  }
  return out + "\"";
}

// A short one-line rendering of a TOML value for messages.
std::string repr(const toml::value &v, int depth) {
  constexpr std::size_t max_items = 6;
  switch (v.type()) {
  case toml::value_t::boolean:
    return v.as_boolean() ? "true" : "false";
  case toml::value_t::integer:
    return std::to_string(v.as_integer());
  case toml::value_t::floating:
    return float_text(v.as_floating());
  case toml::value_t::string: {
    std::string s = v.as_string().str;
    if (s.size() > 60)
      s = s.substr(0, 57) + "...";
    return quote_string(s);
  }
  case toml::value_t::array: {
    if (depth > 1)
      return "[...]";
    const auto &a = v.as_array();
    std::vector<std::string> parts;
    for (std::size_t i = 0; i < a.size() && i < max_items; ++i)
      parts.push_back(repr(a[i], depth + 1));
    if (a.size() > max_items)
      parts.push_back("... (" + std::to_string(a.size()) + " entries)");
    return "[" + join(parts) + "]";
  }
  case toml::value_t::table: {
    if (depth > 1)
      return "{...}";
    std::map<std::string, const toml::value *> keys;
    for (const auto &[k, x] : v.as_table())
      keys.emplace(k, &x);
    std::vector<std::string> parts;
    for (const auto &[k, x] : keys) {
      if (parts.size() == max_items) {
        parts.push_back("...");
        break;
      }
      parts.push_back(k + " = " + repr(*x, depth + 1));
    }
    return parts.empty() ? "{}" : "{ " + join(parts) + " }";
  }
  case toml::value_t::empty:
    return "(empty)";
  default: {
    std::ostringstream os;
    switch (v.type()) {
    case toml::value_t::offset_datetime:
      os << v.as_offset_datetime();
      break;
    case toml::value_t::local_datetime:
      os << v.as_local_datetime();
      break;
    case toml::value_t::local_date:
      os << v.as_local_date();
      break;
    default:
      os << v.as_local_time();
      break;
    }
    std::string text = os.str();
    for (char &ch : text)
      if (ch == '\n' || ch == '\r')
        ch = ' ';
    return text;
  }
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
