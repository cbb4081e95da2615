// The canonical text of a scene (sorted "key = value" lines) and the first difference between
// two scenes, for restarts.
#include "narrows/scene/canonical.hpp"

#include "canonical_toml.hpp"
#include "narrows/core/error.hpp"
#include "narrows/scene/schema.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>

namespace narrows::scene {

namespace {

bool bare_key(const std::string &k) {
  if (k.empty())
    return false;
  for (const char ch : k)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-'))
      return false;
  return true;
}

std::string quoted(const std::string &s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto u = static_cast<unsigned char>(ch);
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (u < 0x20 || u == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", u);
      out += buf;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

std::string key_text(const std::string &k) { return bare_key(k) ? k : quoted(k); }

// Integral values print as integers whatever their TOML type; other floats as the shortest
// text that reads back to the same double.
std::string number_text(double x) {
  if (std::isnan(x))
    return "nan";
  if (std::isinf(x))
    return x > 0 ? "inf" : "-inf";
  if (x == std::floor(x) && std::fabs(x) < 9007199254740992.0) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f", x == 0.0 ? 0.0 : x);
    return buf;
  }
  char buf[40];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, x);
    if (std::strtod(buf, nullptr) == x)
      break;
  }
  return buf; // "%g" writes e.g. "1.5e-07", which TOML reads as a float
}

std::string value_text(const toml::value &v);

std::string inline_table(const toml::value &v) {
  std::map<std::string, std::string> items;
  for (const auto &[k, x] : v.as_table())
    items[key_text(k)] = value_text(x);
  std::string out = "{";
  for (const auto &[k, x] : items)
    out += (out.size() > 1 ? ", " : " ") + k + " = " + x;
  return out + (items.empty() ? "}" : " }");
}

std::string value_text(const toml::value &v) {
  if (v.is_integer())
    return std::to_string(v.as_integer());
  if (v.is_floating())
    return number_text(v.as_floating());
  if (v.is_boolean())
    return v.as_boolean() ? "true" : "false";
  if (v.is_string())
    return quoted(v.as_string().str);
  if (v.is_array()) {
    std::string out = "[";
    for (const auto &x : v.as_array())
      out += (out.size() > 1 ? ", " : "") + value_text(x);
    return out + "]";
  }
  if (v.is_table())
    return inline_table(v);
  std::ostringstream s;
  s << v; // dates and times: toml11's own text
  return s.str();
}

// Every leaf of `table` under `prefix`: canonical key -> canonical value.
void flatten(const toml::value &table, const std::string &prefix,
             std::map<std::string, std::string> &out) {
  for (const auto &[k, v] : table.as_table()) {
    const std::string key = prefix.empty() ? key_text(k) : prefix + "." + key_text(k);
    if (v.is_table() && !v.as_table().empty())
      flatten(v, key, out);
    else
      out[key] = value_text(v);
  }
}

std::map<std::string, std::string> leaves(const std::string &text, const std::string &name) {
  toml::value root;
  try {
    std::istringstream in(text);
    root = toml::parse(in, name);
  } catch (const std::exception &) {
    throw input_error(name + ": the stored scene is not valid TOML; allowed: a checkpoint "
                             "written by narrows run");
  }
  std::map<std::string, std::string> out;
  flatten(root, "", out);
  return out;
}

std::string section_of(const std::string &key) {
  if (!key.empty() && key[0] == '"')
    return key.substr(0, key.find('"', 1) + 1);
  return key.substr(0, key.find('.'));
}

// The canonical value of a key's documented default (its cell in the schema, e.g. "2500" or
// `"none"`) when that is one TOML value; "(not set)" otherwise ("the defaults below", "2 r_a").
std::string default_of(const std::string &key) {
  std::vector<std::string> parts;
  for (std::size_t at = 0;;) {
    const std::size_t dot = key.find('.', at);
    parts.push_back(key.substr(at, dot - at));
    if (dot == std::string::npos)
      break;
    at = dot + 1;
  }
  const SectionSpec *section = parts.size() >= 2 ? find_section(parts[0]) : nullptr;
  if (section == nullptr)
    return "(not set)";
  const std::vector<KeySpec> *keys = &section->keys;
  const KeySpec *spec = nullptr;
  for (std::size_t i = 1; i < parts.size(); ++i) {
    spec = find_key(*keys, parts[i]);
    if (spec == nullptr)
      return "(not set)";
    keys = &spec->sub_keys;
  }
  std::string text(spec->default_value);
  if (text.size() >= 2 && text.front() == '`' && text.back() == '`')
    text = text.substr(1, text.size() - 2);
  if (text.find('`') != std::string::npos)
    return "(not set)";
  try {
    std::istringstream in("v = " + text);
    const toml::value root = toml::parse(in, "default");
    const toml::value &v = root.as_table().at("v");
    if (v.is_table())
      return "(not set)";
    return value_text(v);
  } catch (const std::exception &) {
    return "(not set)";
  }
}

// Two canonical values of `key` that mean the same: a key not set has its documented default
// (issue 35: --set colloids.spring.kn=2500 was refused as "(not set)"), and "inf" is the float
// inf (mu_cw = inf against a checkpoint's "inf").
bool same_value(const std::string &key, const std::string &a, const std::string &b) {
  const auto value = [&](const std::string &x) {
    const std::string v = x == "(not set)" ? default_of(key) : x;
    if (v == "\"inf\"")
      return std::string("inf");
    if (v == "\"-inf\"")
      return std::string("-inf");
    return v;
  };
  return value(a) == value(b);
}

} // namespace

namespace detail {

std::string canonical_text(const toml::value &root) {
  std::map<std::string, std::string> all;
  flatten(root, "", all);
  std::string out;
  for (const auto &[k, v] : all)
    out += k + " = " + v + "\n";
  return out;
}

} // namespace detail

std::string canonical_text(const std::string &toml_text, const std::string &file) {
  std::string out;
  for (const auto &[k, v] : leaves(toml_text, file))
    out += k + " = " + v + "\n";
  return out;
}

std::optional<SceneDifference> first_difference(const std::string &given_text,
                                                const std::string &stored_text,
                                                const std::string &stored_name,
                                                const std::vector<std::string> &may_change) {
  const auto given = leaves(given_text, "the given scene");
  const auto stored = leaves(stored_text, stored_name);
  const auto exempt = [&](const std::string &k) {
    if (k == "run.steps" || k.rfind("output.", 0) == 0)
      return true;
    for (const auto &m : may_change)
      if (k == m)
        return true;
    return false;
  };
  const auto has_section = [](const std::map<std::string, std::string> &m, const std::string &s) {
    for (auto it = m.lower_bound(s); it != m.end() && it->first.rfind(s, 0) == 0; ++it)
      if (section_of(it->first) == s)
        return true;
    return false;
  };
  // The engine and the dimension first: with them differs everything else.
  for (const char *key : {"run.engine", "run.dimensions"}) {
    const auto a = given.find(key), b = stored.find(key);
    const std::string x = a == given.end() ? "(not set)" : a->second;
    const std::string y = b == stored.end() ? "(not set)" : b->second;
    if (!same_value(key, x, y))
      return SceneDifference{key, x, y};
  }
  auto g = given.begin(), s = stored.begin();
  while (g != given.end() || s != stored.end()) {
    const bool take_g = s == stored.end() || (g != given.end() && g->first <= s->first);
    const bool take_s = g == given.end() || (s != stored.end() && s->first <= g->first);
    const std::string &key = take_g ? g->first : s->first;
    const std::string a = take_g ? g->second : "(not set)";
    const std::string b = take_s ? s->second : "(not set)";
    if (take_g)
      ++g;
    if (take_s)
      ++s;
    if (a == b || exempt(key))
      continue;
    const std::string sec = section_of(key);
    const bool in_given = has_section(given, sec), in_stored = has_section(stored, sec);
    // A section on one side only differs whatever its keys' values ([walls] with its defaults
    // is not the same scene as no walls).
    if (in_given != in_stored && sec != "output")
      return SceneDifference{"[" + sec + "]", in_given ? "present" : "absent",
                             in_stored ? "present" : "absent"};
    if (same_value(key, a, b))
      continue;
    const auto shown = [&](const std::string &x) {
      const std::string d = x == "(not set)" ? default_of(key) : x;
      return d == x ? x : "(not set: the default " + d + ")";
    };
    return SceneDifference{key, shown(a), shown(b)};
  }
  return std::nullopt;
}

} // namespace narrows::scene
