// The words of the scene's one-line messages: values rendered, lists joined, suggestions.
#include "message_text.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

namespace narrows::scene::detail {

namespace {

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

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      const char ca = static_cast<char>(std::tolower(static_cast<unsigned char>(a[i - 1])));
      const char cb = static_cast<char>(std::tolower(static_cast<unsigned char>(b[j - 1])));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (ca == cb ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
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

std::string join(const std::vector<std::string> &items, const char *sep) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i)
      out += sep;
    out += items[i];
  }
  return out;
}

std::string trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos)
    return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(first, last - first + 1));
}

std::string one_line(std::string s) {
  for (char &ch : s)
    if (ch == '\n' || ch == '\r')
      ch = ' ';
  return s;
}

std::string closest(const std::string &word, const std::vector<std::string> &candidates) {
  std::string best;
  std::size_t best_d = std::max<std::size_t>(1, std::min<std::size_t>(2, word.size() / 3)) + 1;
  for (const auto &c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

} // namespace narrows::scene::detail
