// Reading a scene: TOML text -> validated scene::Scene.
//
// All validation lives here. Every problem becomes one narrows::input_error line of the form
//   <source>: <key> ... found ...; allowed: ...
// where <source> is the scene file, or "--set '<override>'" when the offending value came from
// the command line.
#include "narrows/scene/parse.hpp"

#include "canonical_toml.hpp"
#include "narrows/core/error.hpp"
#include "parse_continuum.hpp"
#include "parse_kmc.hpp"
#include "parse_lgca.hpp"

#include <toml.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace narrows::scene {
namespace {

using detail::find;
using detail::float_text;
using detail::repr;
using detail::type_name;
using toml::value;

// ---- the schema -------------------------------------------------------------------------------

struct Section {
  const char *name;
  std::vector<const char *> keys; // in the order shown in messages
};

const std::vector<Section> &schema() {
  static const std::vector<Section> s{
      {"run", {"engine", "dimensions", "seed", "steps"}},
      {"domain", {"size"}},
      {"fluid", {"collision", "density", "dt", "angle", "kT", "sort_every"}},
      {"body_force", {"kind", "value", "amplitude"}},
      {"walls", {"slip", "virtual_particles", "virtual_flow"}},
      {"thermostat", {"kind", "gamma"}},
      {"colloids", {"radius",          "radius_sd",         "mass",           "count",
                    "placement",       "positions",         "positions_file", "gravity",
                    "md_substeps",     "epsilon",           "wall_sigma",     "wall_q",
                    "coupling",        "contacts",          "kind",           "spring",
                    "max_lag",         "correlation_every", "kde_width",      "statistics_from",
                    "packing_fraction"}},
      {"kmc",
       {"length", "boundary", "rates", "left", "right", "initial", "time", "warmup", "replicas",
        "charge", "samples", "preset", "parameters", "fugacity", "boundary_rates",
        "boundary_coupling", "max_tries"}},
      {"lattice",
       {"model", "size", "density", "initial", "amplitude", "walls", "body_force", "obstacles",
        "block"}},
      {"tagged", {"max_lag", "replicas"}},
      {"continuum",
       {"model",   "flux",       "rates",       "parameters",   "c",        "c_prime",
        "v_cm",    "length",     "cells",       "diffusion",    "boundary", "reservoirs",
        "initial", "time",       "samples",     "cfl",          "limiter",  "mu",
        "drive",   "dimensions", "half_width",  "centre_speed", "shear",    "k_c",
        "k_eta",   "k_d",        "max_packing", "kind"}},
      {"colloid",
       {"position", "radius", "mass", "velocity", "held", "max_lag", "displacement_lag",
        "displacement_every"}},
      {"output",
       {"dir", "every", "observables", "checkpoint_every", "checkpoint_keep", "progress",
        "trajectory_every", "trajectory_subsample"}},
  };
  return s;
}

const Section *find_section(const std::string &name) {
  for (const auto &sec : schema())
    if (name == sec.name)
      return &sec;
  return nullptr;
}

constexpr std::int64_t max_cells_per_axis = std::int64_t{1} << 20;
constexpr double max_particles = 1099511627776.0; // 2^40

const char *const all_observables[] = {
    "temperature",       "momentum",          "velocity_profile",
    "density_profile",   "viscosity",         "energy",
    "settling_velocity", "colloid_positions", "colloid_vacf",
    "colloid_diffusion", "colloid_msd",       "colloid_angular_vacf",
    "density_kde"};

// The names output.observables accepts with each engine.
std::vector<std::string> engine_observables(Engine engine) {
  if (engine == Engine::kmc)
    return {"current", "density_profile", "pair_correlation", "shock_position", "charge_profile"};
  if (engine == Engine::lgca)
    return {"shear_wave", "density", "velocity", "vacf", "colloid_vacf", "colloid_diffusion"};
  if (engine == Engine::continuum)
    return {"density", "shock_position", "velocity", "evolution", "steady_density"};
  return std::vector<std::string>(std::begin(all_observables), std::end(all_observables));
}

// The sections each engine reads (parse_scene refuses the others, naming their engine).
std::vector<std::string> engine_sections(Engine engine) {
  if (engine == Engine::kmc)
    return {"run", "kmc", "output"};
  if (engine == Engine::lgca)
    return {"run", "lattice", "tagged", "colloid", "output"};
  if (engine == Engine::continuum)
    return {"run", "continuum", "output"};
  return {"run", "domain", "fluid", "body_force", "walls", "thermostat", "colloids", "output"};
}

// ---- small text helpers -----------------------------------------------------------------------

std::string join(const std::vector<std::string> &items, const char *sep = ", ") {
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

// Messages are one line whatever the input contains.
std::string one_line(std::string s) {
  for (char &ch : s)
    if (ch == '\n' || ch == '\r')
      ch = ' ';
  return s;
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

// The closest candidate within a small edit distance (case-insensitive), or "".
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

// ---- TOML syntax errors -------------------------------------------------------------------------

// toml11's syntax_error what() is a multi-line annotated excerpt. Condense it to
//   file: line N: TOML syntax error: <what>; found '<source line>' (<note>)
std::string condense_syntax_error(const std::string &what, const std::string &file,
                                  std::size_t fallback_line,
                                  const std::vector<std::size_t> &line_map = {}) {
  std::istringstream in(what);
  std::string line, headline, src_text, note;
  std::size_t src_line = 0;
  bool first = true;
  while (std::getline(in, line)) {
    // strip ANSI colour sequences, in case toml11 was built to colourise
    std::string clean;
    for (std::size_t i = 0; i < line.size(); ++i) {
      if (line[i] == '\x1b') {
        while (i < line.size() && line[i] != 'm')
          ++i;
        continue;
      }
      clean += line[i];
    }
    if (first) {
      headline = clean;
      first = false;
      continue;
    }
    const auto bar = clean.find(" | ");
    const auto bar_end = clean.find(" |");
    if (bar_end == std::string::npos)
      continue;
    const std::string lhs = trim(clean.substr(0, bar_end));
    const std::string rhs = bar == std::string::npos ? "" : clean.substr(bar + 3);
    if (!lhs.empty() &&
        std::all_of(lhs.begin(), lhs.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      src_line = std::stoul(lhs);
      src_text = trim(rhs);
      note.clear();
    } else if (lhs.empty() && src_line != 0) {
      // the marker line under the source line: "^--- note" or "~~~~ note"
      const auto mark = rhs.find_first_not_of(" ^~-");
      if (mark != std::string::npos)
        note = trim(rhs.substr(mark));
    }
  }
  // "[error] toml::parse_array: missing ..." -> "missing ..."
  std::string msg = trim(headline);
  if (msg.rfind("[error]", 0) == 0)
    msg = trim(msg.substr(7));
  while (msg.rfind("toml::", 0) == 0) {
    const auto colon = msg.find(": ");
    if (colon == std::string::npos)
      break;
    msg = trim(msg.substr(colon + 2));
  }
  while (!msg.empty() && (msg.back() == '.' || msg.back() == ' '))
    msg.pop_back();
  if (msg.empty())
    msg = "invalid TOML";
  if (src_line == 0)
    src_line = fallback_line;
  if (src_line >= 1 && src_line <= line_map.size())
    src_line = line_map[src_line - 1]; // the line of the scene file, not of the parsed text
  std::string out = file + ": line " + std::to_string(src_line) + ": TOML syntax error: " + msg;
  if (!src_text.empty()) {
    if (src_text.size() > 60)
      src_text = src_text.substr(0, 57) + "...";
    out += "; found '" + src_text + "'";
    if (!note.empty() && note != "here")
      out += " (" + note + ")";
  }
  return one_line(out);
}

// The index of the last character of the TOML string that starts at text[i] (a quote): its
// closing quote, the newline that ends an unterminated one-line string, or the text's end.
// Basic strings ("...", """...""") have backslash escapes; literal ones ('...') do not.
std::size_t string_end(const std::string &text, std::size_t i) {
  const char quote = text[i];
  const std::string triple(3, quote);
  const bool multi = text.compare(i, 3, triple) == 0;
  const std::size_t n = text.size();
  for (i += multi ? 3 : 1; i < n; ++i) {
    if (quote == '"' && text[i] == '\\') {
      ++i;
      continue;
    }
    if (text[i] == quote && (!multi || text.compare(i, 3, triple) == 0))
      return multi ? i + 2 : i;
    if (!multi && text[i] == '\n')
      return i;
  }
  return n - 1;
}

// Limits checked on the raw text before toml11 sees it: toml11 recurses once per nesting level
// (bracket or dotted-key component), so a deep enough text overflows the stack.
constexpr std::size_t max_scene_bytes = std::size_t{16} << 20;
constexpr int max_scene_nesting = 64;

// Refuses a text toml11 must not parse: too long, binary (a NUL byte), or nested deeper than
// max_scene_nesting brackets or dotted-key components. Strings and comments are skipped.
void check_raw_text(const std::string &text, const std::string &file) {
  if (text.size() > max_scene_bytes)
    throw input_error(file + ": scene file of " + std::to_string(text.size()) +
                      " bytes; allowed: at most " + std::to_string(max_scene_bytes) + " bytes");
  if (const auto nul = text.find('\0'); nul != std::string::npos)
    throw input_error(file + ": byte " + std::to_string(nul) +
                      " is NUL (binary content); allowed: a TOML text file");
  if (text.find_first_not_of(" \t\r\n") == std::string::npos)
    throw input_error(file + ": the scene file is empty; allowed: a TOML scene with at least "
                             "[run] (see docs/scenes.md)");
  int depth = 0, dots = 0, line = 1;
  const std::size_t n = text.size();
  const auto deep = [&](const char *what) {
    throw input_error(file + ": line " + std::to_string(line) + ": " + what +
                      " nested deeper than " + std::to_string(max_scene_nesting) +
                      " levels; allowed: at most " + std::to_string(max_scene_nesting));
  };
  for (std::size_t i = 0; i < n; ++i) {
    const char ch = text[i];
    if (ch == '#') { // comment to the end of the line
      while (i + 1 < n && text[i + 1] != '\n')
        ++i;
    } else if (ch == '"' || ch == '\'') {
      const std::size_t end = string_end(text, i);
      line +=
          static_cast<int>(std::count(text.begin() + static_cast<std::ptrdiff_t>(i),
                                      text.begin() + static_cast<std::ptrdiff_t>(end) + 1, '\n'));
      i = end;
    } else if ((std::isdigit(static_cast<unsigned char>(ch)) || ch == '+' || ch == '-') &&
               (i == 0 || std::strchr(" \t\r\n=,[{", text[i - 1]) != nullptr)) {
      // A number (or a bare key starting with a digit): toml11 clamps decimal integers beyond
      // 64 bits to the largest one, so they are refused here.
      std::size_t j = i;
      while (j < n && std::strchr(" \t\r\n,]}#=", text[j]) == nullptr)
        ++j;
      const std::string token = text.substr(i, j - i);
      if (std::count(token.begin(), token.end(), '.') > max_scene_nesting)
        deep("dotted keys");
      std::string digits;
      for (const char d : token.substr(token[0] == '+' || token[0] == '-' ? 1 : 0))
        if (d != '_')
          digits += d;
      if (!digits.empty() && digits.size() < 1000 &&
          std::all_of(digits.begin(), digits.end(), [](char d) { return d >= '0' && d <= '9'; })) {
        digits.erase(0, std::min(digits.find_first_not_of('0'), digits.size() - 1));
        const std::string most = token[0] == '-' ? "9223372036854775808" : "9223372036854775807";
        if (digits.size() > most.size() || (digits.size() == most.size() && digits > most))
          throw input_error(file + ": line " + std::to_string(line) + ": integer " + token +
                            " is beyond 64 bits; allowed: -9223372036854775808 to "
                            "9223372036854775807");
      } else if (digits.size() >= 1000) {
        throw input_error(file + ": line " + std::to_string(line) + ": a number of " +
                          std::to_string(digits.size()) + " characters; allowed: a TOML number");
      }
      i = j - 1;
    } else if (ch == '[' || ch == '{') {
      if (++depth > max_scene_nesting)
        deep("brackets");
      dots = 0;
    } else if (ch == ']' || ch == '}') {
      depth = std::max(depth - 1, 0);
      dots = 0;
    } else if (ch == '.') {
      if (++dots > max_scene_nesting)
        deep("dotted keys");
    } else if (ch == '\n' || ch == '=' || ch == ',') {
      line += ch == '\n';
      dots = 0;
    }
  }
}

// toml11 scans a value's whole line for comments (region::comments) after parsing each value,
// so an array of n values on one line takes O(n^2). Long lines of arrays are broken after
// their commas (newlines are allowed between array elements; not inside inline tables, whose
// lines are left alone). Returns the text toml11 reads; line_map[k] is the scene file's line
// of its line k + 1 (empty when nothing was broken).
std::string break_long_arrays(const std::string &text, std::vector<std::size_t> &line_map) {
  constexpr std::size_t long_line = 1024;
  bool any_long = false;
  for (std::size_t at = 0, nl; at < text.size(); at = nl + 1) {
    nl = text.find('\n', at);
    if (nl == std::string::npos)
      nl = text.size();
    any_long = any_long || nl - at > long_line;
  }
  if (!any_long)
    return text;
  std::string out;
  out.reserve(text.size() + text.size() / 8);
  std::vector<char> open; // the brackets around the current position
  std::size_t line = 1, column = 0;
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n; ++i) {
    const char ch = text[i];
    const auto newline = [&] {
      line_map.push_back(line);
      column = 0;
    };
    if (ch == '#') {
      while (i < n && text[i] != '\n')
        out += text[i++];
      --i;
    } else if (ch == '"' || ch == '\'') { // copy a string verbatim
      const std::size_t end = string_end(text, i);
      for (std::size_t k = i; k <= end; ++k)
        if (text[k] == '\n') {
          newline();
          ++line;
        }
      out.append(text, i, end - i + 1);
      column += 2;
      i = end;
      continue;
    } else if (ch == '[' || ch == '{') {
      open.push_back(ch);
    } else if ((ch == ']' || ch == '}') && !open.empty()) {
      open.pop_back();
    }
    if (ch == '#')
      continue;
    out += ch;
    ++column;
    if (ch == '\n') {
      newline();
      ++line;
    } else if (ch == ',' && column > 80 && !open.empty() &&
               std::all_of(open.begin(), open.end(), [](char b) { return b == '['; })) {
      out += '\n';
      newline();
    }
  }
  line_map.push_back(line);
  return out;
}

value parse_toml(const std::string &text, const std::string &file) {
  check_raw_text(text, file);
  std::vector<std::size_t> line_map;
  std::istringstream in(break_long_arrays(text, line_map));
  try {
    return toml::parse(in, file);
  } catch (const toml::syntax_error &e) {
    throw input_error(condense_syntax_error(e.what(), file, e.location().line(), line_map));
  } catch (const toml::exception &e) {
    throw input_error(condense_syntax_error(e.what(), file, e.location().line(), line_map));
  } catch (const std::exception &e) {
    throw input_error(one_line(file + ": TOML syntax error: " + e.what()));
  }
}

// ---- validation context -------------------------------------------------------------------------

class Ctx {
public:
  explicit Ctx(std::string file) : file_(std::move(file)) {}

  // Remember that the value at `key` (section.key) came from `--set '<text>'`.
  void from_override(const std::string &key, const std::string &text) { set_[key] = text; }

  [[noreturn]] void fail(const std::string &key, const std::string &message) const {
    // array entries ("domain.size[1]") come from where their array came from
    const auto it = set_.find(key.substr(0, key.find('[')));
    if (it != set_.end())
      throw input_error(
          one_line(set_source(it->second) + ": " + message + " (overriding " + file_ + ")"));
    throw input_error(one_line(file_ + ": " + message));
  }

  [[noreturn]] void fail_set(const std::string &text, const std::string &message) const {
    throw input_error(one_line(set_source(text) + ": " + message + " (overriding " + file_ + ")"));
  }

  [[noreturn]] void wrong_type(const std::string &key, const value &v,
                               const std::string &allowed) const {
    fail(key, key + ": found " + repr(v) + " (" + type_name(v) + "); allowed: " + allowed);
  }

  [[noreturn]] void out_of_range(const std::string &key, const value &v,
                                 const std::string &allowed) const {
    fail(key, key + " = " + repr(v) + " is out of range; allowed: " + allowed);
  }

  [[noreturn]] void missing(const std::string &key, const std::string &allowed) const {
    fail(key, "missing required key '" + key + "'; allowed: " + allowed);
  }

  const std::string &file() const { return file_; }

private:
  static std::string set_source(const std::string &text) { return "--set '" + text + "'"; }

  std::string file_;
  std::map<std::string, std::string> set_;
};

// The unknown-key message for `key` in section `sec` (sec == nullptr: a top-level name).
std::string unknown_key_message(const std::string &section, const std::string &key) {
  const Section *sec = find_section(section);
  std::vector<std::string> allowed(sec->keys.begin(), sec->keys.end());
  std::string msg = "unknown key '" + section + "." + key + "'; allowed keys in [" + section +
                    "]: " + join(allowed);
  std::string hint = closest(key, allowed);
  if (!hint.empty()) {
    msg += "; did you mean '" + section + "." + hint + "'?";
  } else {
    for (const auto &other : schema())
      for (const char *k : other.keys)
        if (key == k && section != other.name) {
          msg += "; did you mean '" + std::string(other.name) + "." + key + "' (in [" + other.name +
                 "])?";
          return msg;
        }
  }
  return msg;
}

std::vector<std::string> section_names() {
  std::vector<std::string> names;
  for (const auto &sec : schema())
    names.emplace_back(sec.name);
  return names;
}

std::string unknown_section_message(const std::string &name, const value &v) {
  std::string msg = v.is_table() ? "unknown section [" + name + "]"
                                 : "unknown key '" + name + "' at the top level";
  msg += "; allowed sections: " + join(section_names());
  const std::string hint = closest(name, section_names());
  if (!hint.empty())
    msg += "; did you mean [" + hint + "]?";
  else
    for (const auto &sec : schema())
      for (const char *k : sec.keys)
        if (name == k) {
          msg += "; did you mean '" + std::string(sec.name) + "." + name + "' (in [" + sec.name +
                 "])?";
          return msg;
        }
  return msg;
}

// Keys of a table in the order they appear in the file (ties: by name).
std::vector<std::pair<std::string, const value *>> in_file_order(const value &table) {
  std::vector<std::pair<std::string, const value *>> items;
  for (const auto &[k, v] : table.as_table())
    items.emplace_back(k, &v);
  std::sort(items.begin(), items.end(), [](const auto &a, const auto &b) {
    const auto la = a.second->location().line(), lb = b.second->location().line();
    return la != lb ? la < lb : a.first < b.first;
  });
  return items;
}

// ---- typed getters ------------------------------------------------------------------------------

// A number (integers accepted) that must be finite and satisfy ok(x).
template <class Pred>
double as_number(const Ctx &c, const value &v, const std::string &key, const std::string &allowed,
                 Pred ok) {
  double x = 0.0;
  if (v.is_integer())
    x = static_cast<double>(v.as_integer());
  else if (v.is_floating())
    x = v.as_floating();
  else
    c.wrong_type(key, v, allowed);
  if (!std::isfinite(x) || !ok(x))
    c.out_of_range(key, v, allowed);
  return x;
}

template <class Pred>
std::int64_t as_integer(const Ctx &c, const value &v, const std::string &key,
                        const std::string &allowed, Pred ok) {
  if (!v.is_integer())
    c.wrong_type(key, v, allowed);
  const std::int64_t n = v.as_integer();
  if (!ok(n))
    c.out_of_range(key, v, allowed);
  return n;
}

std::string as_string(const Ctx &c, const value &v, const std::string &key,
                      const std::string &allowed) {
  if (!v.is_string())
    c.wrong_type(key, v, allowed);
  return v.as_string().str;
}

// A string naming one of `names`; returns its index.
std::size_t as_choice(const Ctx &c, const value &v, const std::string &key, const char *what,
                      const std::vector<std::string> &names) {
  const std::string allowed = join(names);
  const std::string s = as_string(c, v, key, "one of " + allowed);
  for (std::size_t i = 0; i < names.size(); ++i)
    if (s == names[i])
      return i;
  std::string msg = key + " = " + repr(v) + " is not " + what + "; allowed: " + allowed;
  const std::string hint = closest(s, names);
  if (!hint.empty())
    msg += "; did you mean \"" + hint + "\"?";
  c.fail(key, msg);
}

// ---- sections -----------------------------------------------------------------------------------

const value *section(const Ctx &c, const value &root, const char *name) {
  const value *sec = find(&root, name);
  if (sec != nullptr && !sec->is_table())
    c.wrong_type(name, *sec, std::string("a table [") + name + "]");
  return sec;
}

void check_keys(const Ctx &c, const value *sec, const char *name) {
  if (sec == nullptr)
    return;
  const Section *schema_sec = find_section(name);
  for (const auto &[k, v] : in_file_order(*sec)) {
    (void)v;
    if (std::none_of(schema_sec->keys.begin(), schema_sec->keys.end(),
                     [&k = k](const char *allowed) { return k == allowed; }))
      c.fail(std::string(name) + "." + k, unknown_key_message(name, k));
  }
}

// The engine a section belongs to, for messages.
const char *engine_of(const std::string &section) {
  if (section == "kmc")
    return "kmc";
  if (section == "continuum")
    return "continuum";
  if (section == "lattice" || section == "tagged" || section == "colloid")
    return "lgca";
  return "mpcd";
}

Engine parse_engine(const Ctx &c, const value *run) {
  const value *v = find(run, "engine");
  if (v == nullptr)
    return Engine::mpcd;
  const std::vector<std::string> names{"mpcd", "lgca", "kmc", "continuum"};
  const std::string s = as_string(c, *v, "run.engine", "one of " + join(names));
  if (s == "mpcd")
    return Engine::mpcd;
  if (s == "kmc")
    return Engine::kmc;
  if (s == "lgca")
    return Engine::lgca;
  if (s == "continuum")
    return Engine::continuum;
  std::string msg =
      "run.engine = " + repr(*v) + " is not a known engine; allowed: mpcd, lgca, kmc, continuum";
  const std::string hint = closest(s, names);
  if (!hint.empty())
    msg += "; did you mean \"" + hint + "\"?";
  c.fail("run.engine", msg);
}

void parse_run(const Ctx &c, const value *run, Run &out) {
  check_keys(c, run, "run");

  const std::string dims_allowed = "2 or 3";
  if (const value *v = find(run, "dimensions"))
    out.dimensions =
        static_cast<int>(as_integer(c, *v, "run.dimensions", "an integer, " + dims_allowed,
                                    [](std::int64_t n) { return n == 2 || n == 3; }));
  else if (out.engine == Engine::mpcd)
    c.missing("run.dimensions", dims_allowed);

  const std::string seed_allowed = "an integer >= 0";
  if (const value *v = find(run, "seed"))
    out.seed = static_cast<std::uint64_t>(
        as_integer(c, *v, "run.seed", seed_allowed, [](std::int64_t n) { return n >= 0; }));

  // kmc runs kmc.time per replica and has no steps: there run.steps is optional (and unused).
  // Checkpoint names hold the step in 10 digits (io/checkpoint.hpp, max_checkpoint_step).
  const std::string steps_allowed =
      "an integer from 0 to 9999999999 (the step at which the run ends)";
  if (const value *v = find(run, "steps"))
    out.steps = as_integer(c, *v, "run.steps", steps_allowed,
                           [](std::int64_t n) { return n >= 0 && n <= 9999999999; });
  else if (out.engine != Engine::kmc && out.engine != Engine::continuum)
    c.missing("run.steps", steps_allowed);
}

void parse_domain(const Ctx &c, const value *domain, int dims, Domain &out) {
  check_keys(c, domain, "domain");
  const std::string per_axis = "whole numbers of cells from 2 to " +
                               std::to_string(max_cells_per_axis) +
                               " (the collision cells have size 1)";
  const std::string allowed = "an array of " + std::to_string(dims) + " " + per_axis;
  const value *v = find(domain, "size");
  if (v == nullptr)
    c.missing("domain.size", allowed);
  if (!v->is_array())
    c.wrong_type("domain.size", *v, allowed);
  const auto &a = v->as_array();
  if (static_cast<int>(a.size()) != dims)
    c.fail("domain.size", "domain.size = " + repr(*v) + " has " + std::to_string(a.size()) +
                              (a.size() == 1 ? " entry" : " entries") +
                              "; allowed: " + std::to_string(dims) +
                              " entries (run.dimensions = " + std::to_string(dims) + ")");
  out.size = {0.0, 0.0, 0.0};
  for (int d = 0; d < dims; ++d) {
    const std::string key = "domain.size[" + std::to_string(d) + "]";
    const double x = as_number(c, a[d], key, per_axis, [](double) { return true; });
    if (x != std::floor(x))
      c.fail(key,
             key + " = " + repr(a[d]) + " is not a whole number of cells; allowed: " + per_axis);
    if (x < 2.0 || x > static_cast<double>(max_cells_per_axis))
      c.out_of_range(key, a[d], per_axis);
    out.size[d] = x;
  }
}

void parse_fluid(const Ctx &c, const value *fluid, const Domain &domain, int dims, Fluid &out) {
  const std::vector<std::string> rules{"srd", "at", "at+a", "random-permute", "random-maxwell"};
  if (fluid == nullptr)
    c.fail("fluid", "missing required section [fluid]; allowed keys in [fluid]: " +
                        join(std::vector<std::string>(find_section("fluid")->keys.begin(),
                                                      find_section("fluid")->keys.end())) +
                        " (collision and dt are required)");
  check_keys(c, fluid, "fluid");

  if (const value *v = find(fluid, "collision")) {
    const std::size_t i = as_choice(c, *v, "fluid.collision", "a known collision rule", rules);
    constexpr std::array<Collision, 5> values{Collision::srd, Collision::at, Collision::at_a,
                                              Collision::random_permute, Collision::random_maxwell};
    out.collision = values[i];
  } else {
    c.missing("fluid.collision", join(rules));
  }

  const std::string density_allowed = "a number > 0 (mean particles per cell)";
  if (const value *v = find(fluid, "density")) {
    out.density =
        as_number(c, *v, "fluid.density", density_allowed, [](double x) { return x > 0.0; });
    double cells = 1.0;
    for (int d = 0; d < dims; ++d)
      cells *= domain.size[d];
    const double total = out.density * cells;
    if (!(total < max_particles)) {
      std::ostringstream os;
      os << "fluid.density = " << repr(*v) << " gives " << total << " particles in " << cells
         << " cells; allowed: fewer than 2^40 (1099511627776) particles in total";
      c.fail("fluid.density", os.str());
    }
  } else {
    double cells = 1.0;
    for (int d = 0; d < dims; ++d)
      cells *= domain.size[d];
    if (!(out.density * cells < max_particles))
      c.fail("domain.size", "domain.size with the default fluid.density = 10 gives more than "
                            "2^40 particles; allowed: fewer than 2^40 (1099511627776) in total");
  }

  const std::string dt_allowed = "a number > 0 (the collision time step)";
  if (const value *v = find(fluid, "dt"))
    out.dt = as_number(c, *v, "fluid.dt", dt_allowed, [](double x) { return x > 0.0; });
  else
    c.missing("fluid.dt", dt_allowed);

  // The rotation angle only matters for srd; with the other rules it is accepted and ignored, so
  // a sweep over collision rules can keep one scene.
  if (const value *v = find(fluid, "angle"))
    out.angle_deg = as_number(c, *v, "fluid.angle", "0 < angle < 360 (degrees)",
                              [](double x) { return x > 0.0 && x < 360.0; });

  if (const value *v = find(fluid, "kT"))
    out.kT = as_number(c, *v, "fluid.kT", "a number > 0", [](double x) { return x > 0.0; });

  if (const value *v = find(fluid, "sort_every"))
    out.sort_every = static_cast<int>(
        as_integer(c, *v, "fluid.sort_every", "an integer from 0 (never sort) to 2147483647",
                   [](std::int64_t n) { return n >= 0 && n <= std::numeric_limits<int>::max(); }));
}

std::optional<BodyForce> parse_body_force(const Ctx &c, const value *bf, int dims) {
  if (bf == nullptr)
    return std::nullopt;
  check_keys(c, bf, "body_force");
  BodyForce out;
  const value *kind = find(bf, "kind");
  const value *val = find(bf, "value");
  const value *amp = find(bf, "amplitude");
  if (kind != nullptr) {
    const std::size_t i =
        as_choice(c, *kind, "body_force.kind", "a known body force kind", {"constant", "sine"});
    out.kind = i == 0 ? ForceKind::constant : ForceKind::sine;
  }
  const std::string vec_allowed =
      "an array of " + std::to_string(dims) + " finite numbers (the acceleration vector)";
  if (out.kind == ForceKind::constant) {
    if (amp != nullptr)
      c.fail("body_force.amplitude",
             "body_force.amplitude = " + repr(*amp) +
                 " needs body_force.kind = \"sine\"; allowed: either value = [ax, ay" +
                 (dims == 3 ? ", az" : "") + "] (constant) or kind = \"sine\", amplitude = A");
    if (val == nullptr)
      c.missing("body_force.value", vec_allowed + ", or kind = \"sine\" with amplitude");
    if (!val->is_array())
      c.wrong_type("body_force.value", *val, vec_allowed);
    const auto &a = val->as_array();
    if (static_cast<int>(a.size()) != dims)
      c.fail("body_force.value",
             "body_force.value = " + repr(*val) + " has " + std::to_string(a.size()) +
                 (a.size() == 1 ? " entry" : " entries") + "; allowed: " + std::to_string(dims) +
                 " entries (run.dimensions = " + std::to_string(dims) + ")");
    for (int d = 0; d < dims; ++d)
      out.value[d] = as_number(c, a[d], "body_force.value[" + std::to_string(d) + "]",
                               "a finite number", [](double) { return true; });
  } else {
    if (val != nullptr)
      c.fail("body_force.value", "body_force.value = " + repr(*val) +
                                     " cannot be mixed with body_force.kind = \"sine\"; allowed: "
                                     "either value = [...] (constant) or kind = \"sine\", "
                                     "amplitude = A");
    const std::string amp_allowed = "a finite number (a_x = amplitude * sin(2 pi y / L_y))";
    if (amp == nullptr)
      c.missing("body_force.amplitude", amp_allowed);
    out.amplitude =
        as_number(c, *amp, "body_force.amplitude", amp_allowed, [](double) { return true; });
  }
  return out;
}

// A vector of `dims` finite numbers at `key`.
std::array<double, 3> as_vector(const Ctx &c, const value &v, const std::string &key, int dims,
                                const std::string &what) {
  const std::string allowed =
      "an array of " + std::to_string(dims) + " finite numbers (" + what + ")";
  if (!v.is_array())
    c.wrong_type(key, v, allowed);
  const auto &a = v.as_array();
  if (static_cast<int>(a.size()) != dims)
    c.fail(key, key + " = " + repr(v) + " has " + std::to_string(a.size()) +
                    (a.size() == 1 ? " entry" : " entries") + "; allowed: " + std::to_string(dims) +
                    " entries (run.dimensions = " + std::to_string(dims) + ")");
  std::array<double, 3> out{0.0, 0.0, 0.0};
  for (int d = 0; d < dims; ++d)
    out[d] = as_number(c, a[d], key + "[" + std::to_string(d) + "]", "a finite number",
                       [](double) { return true; });
  return out;
}

// [[colloids.kind]]: an array of tables {radius, count, mass}. The one-kind keys radius,
// radius_sd, mass and count cannot be given beside it.
std::vector<ColloidKind> parse_colloid_kinds(const Ctx &c, const value *sec, const value &kinds) {
  for (const char *key : {"radius", "radius_sd", "mass", "count"})
    if (const value *v = find(sec, key))
      c.fail(std::string("colloids.") + key,
             std::string("colloids.") + key + " = " + repr(*v) +
                 " cannot be mixed with [[colloids.kind]]; allowed: either the one-kind keys "
                 "radius, radius_sd, mass, count or one [[colloids.kind]] table per kind with "
                 "its radius, count and mass");
  const std::string allowed = "an array of tables [[colloids.kind]], each with radius (> 0), "
                              "count (>= 1) and optional mass (> 0)";
  if (!kinds.is_array() || kinds.as_array().empty())
    c.wrong_type("colloids.kind", kinds, allowed);
  const auto positive = [](double x) { return x > 0.0; };
  std::vector<ColloidKind> out;
  const auto &a = kinds.as_array();
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string key = "colloids.kind[" + std::to_string(i) + "]";
    if (!a[i].is_table())
      c.wrong_type(key, a[i], allowed);
    for (const auto &[k, v] : in_file_order(a[i])) {
      (void)v;
      if (k != "radius" && k != "count" && k != "mass")
        c.fail(key + "." + k, "unknown key '" + key + "." + k +
                                  "'; allowed keys in [[colloids.kind]]: radius, count, mass");
    }
    ColloidKind kind;
    if (const value *v = find(&a[i], "radius"))
      kind.radius = as_number(c, *v, key + ".radius", "a number > 0 (cell units)", positive);
    else
      c.missing(key + ".radius", "a number > 0 (cell units)");
    if (const value *v = find(&a[i], "count"))
      kind.count = as_integer(c, *v, key + ".count", "an integer from 1 to 1000000",
                              [](std::int64_t n) { return n >= 1 && n <= 1000000; });
    else
      c.missing(key + ".count", "an integer from 1 to 1000000");
    if (const value *v = find(&a[i], "mass"))
      kind.mass = as_number(c, *v, key + ".mass",
                            "a number > 0 (default: fluid mass density times the colloid volume)",
                            positive);
    out.push_back(kind);
  }
  return out;
}

// [colloids.spring]: kn, kt, mu_cc, mu_cw (a number >= 0 or inf) and substeps.
ColloidSprings parse_colloid_springs(const Ctx &c, const value &sec) {
  if (!sec.is_table())
    c.wrong_type("colloids.spring", sec, "a table [colloids.spring]");
  for (const auto &[k, v] : in_file_order(sec)) {
    (void)v;
    if (k != "kn" && k != "kt" && k != "mu_cc" && k != "mu_cw" && k != "substeps")
      c.fail("colloids.spring." + k, "unknown key 'colloids.spring." + k +
                                         "'; allowed keys in [colloids.spring]: kn, kt, mu_cc, "
                                         "mu_cw, substeps");
  }
  ColloidSprings out;
  if (const value *v = find(&sec, "kn"))
    out.kn = as_number(c, *v, "colloids.spring.kn", "a number > 0 (kT / a^2)",
                       [](double x) { return x > 0.0; });
  if (const value *v = find(&sec, "kt"))
    out.kt = as_number(c, *v, "colloids.spring.kt", "a number >= 0 (kT / a^2)",
                       [](double x) { return x >= 0.0; });
  // A friction coefficient: a number >= 0, or infinity (the TOML float inf or the string "inf").
  const auto mu = [&](const char *name, double &x) {
    const value *v = find(&sec, name);
    if (v == nullptr)
      return;
    const std::string key = std::string("colloids.spring.") + name;
    const std::string allowed = "a number >= 0, or \"inf\" (never slides)";
    if ((v->is_string() && v->as_string() == "inf") ||
        (v->is_floating() && std::isinf(v->as_floating()) && v->as_floating() > 0.0)) {
      x = std::numeric_limits<double>::infinity();
      return;
    }
    if (v->is_string())
      c.out_of_range(key, *v, allowed);
    x = as_number(c, *v, key, allowed, [](double y) { return y >= 0.0; });
  };
  mu("mu_cc", out.mu_cc);
  mu("mu_cw", out.mu_cw);
  if (const value *v = find(&sec, "substeps"))
    out.substeps =
        static_cast<int>(as_integer(c, *v, "colloids.spring.substeps", "an integer from 1 to 10000",
                                    [](std::int64_t n) { return n >= 1 && n <= 10000; }));
  return out;
}

// The keys of the colloid statistics (observables colloid_vacf ... density_kde).
void parse_colloid_statistics(const Ctx &c, const value *sec, Colloids &out) {
  if (const value *v = find(sec, "correlation_every"))
    out.correlation_every =
        as_integer(c, *v, "colloids.correlation_every", "an integer from 1 to 1000000 (steps)",
                   [](std::int64_t n) { return n >= 1 && n <= 1000000; });
  const std::int64_t every = out.correlation_every;
  if (const value *v = find(sec, "max_lag"))
    out.max_lag = as_integer(
        c, *v, "colloids.max_lag",
        "a multiple of colloids.correlation_every = " + std::to_string(every) +
            ", at most 100000 times it (steps)",
        [every](std::int64_t n) { return n >= 0 && n % every == 0 && n / every <= 100000; });
  else if (out.max_lag % every != 0)
    c.fail("colloids.max_lag", "colloids.max_lag defaults to 1000, not a multiple of "
                               "colloids.correlation_every = " +
                                   std::to_string(every) +
                                   "; allowed: an explicit max_lag, a multiple of it");
  if (const value *v = find(sec, "kde_width"))
    out.kde_width = as_number(c, *v, "colloids.kde_width", "a number > 0 (cell units)",
                              [](double x) { return x > 0.0; });
  if (const value *v = find(sec, "statistics_from"))
    out.statistics_from = as_integer(c, *v, "colloids.statistics_from", "an integer >= 0 (step)",
                                     [](std::int64_t n) { return n >= 0; });
}

// The densest fraction placement = "packing" takes: random close packing of bidisperse disks
// (about 0.84, PHYSICS.md) and of spheres (about 0.64); beyond it the overlaps cannot go.
double packing_limit(int dims) { return dims == 2 ? 0.84 : 0.64; }

std::string packing_allowed(int dims) {
  return "a number > 0 and at most " + float_text(packing_limit(dims)) +
         " (random close packing of " + (dims == 2 ? "disks" : "spheres") + ")";
}

const value *fraction_or_missing(const Ctx &c, const value *fraction, int dims) {
  if (fraction == nullptr)
    c.missing("colloids.packing_fraction", packing_allowed(dims));
  return fraction;
}

// placement = "packing": the target fraction, and the counts that realise it: one kind
// round(phi V / v); several kinds their counts (the number ratio) times one factor, each rounded.
void parse_packing(const Ctx &c, const value *sec, const value &fraction, const Domain &domain,
                   int dims, bool walls, bool no_slip, Colloids &out) {
  if (!no_slip)
    c.fail("colloids.placement", "colloids.placement = \"packing\" grows the colloids with the "
                                 "spring contacts of no-slip colloids; allowed with coupling = "
                                 "\"no-slip\"");
  out.packing_fraction = as_number(c, fraction, "colloids.packing_fraction", packing_allowed(dims),
                                   [&](double x) { return x > 0.0 && x <= packing_limit(dims); });
  for (const char *key : {"count", "radius_sd"})
    if (const value *v = find(sec, key))
      c.fail(std::string("colloids.") + key,
             std::string("colloids.") + key + " = " + repr(*v) +
                 " cannot be mixed with placement = \"packing\"; allowed: one radius, the "
                 "number follows from colloids.packing_fraction (several kinds: "
                 "[[colloids.kind]] with counts in the number ratio)");
  const auto volume_of = [dims](double r) {
    return dims == 2 ? 3.14159265358979 * r * r : 4.18879020478639 * r * r * r;
  };
  double box_volume = 1.0;
  for (int d = 0; d < dims; ++d)
    box_volume *= domain.size[d];
  const double phi = out.packing_fraction;
  if (walls && 2.0 * out.radius > domain.size[1])
    c.fail("colloids.placement",
           "colloids.placement = \"packing\": the largest colloid (radius " +
               float_text(out.radius) + ") does not fit across the channel (" +
               float_text(domain.size[1]) + "); allowed: a diameter up to domain.size[1]");
  if (out.kinds.empty()) {
    out.count = std::llround(phi * box_volume / volume_of(out.radius));
  } else {
    double ratio_volume = 0.0;
    for (const auto &k : out.kinds)
      ratio_volume += static_cast<double>(k.count) * volume_of(k.radius);
    const double factor = phi * box_volume / ratio_volume;
    out.count = 0;
    for (auto &k : out.kinds) {
      k.count = std::llround(static_cast<double>(k.count) * factor);
      out.count += k.count;
    }
  }
  bool none = out.count < 1;
  for (const auto &k : out.kinds)
    none = none || k.count < 1;
  if (none || out.count > 1000000)
    c.fail("colloids.packing_fraction",
           "colloids.packing_fraction = " + repr(fraction) + " makes " + std::to_string(out.count) +
               " colloids" + (none ? " (a kind with none)" : "") +
               " in this box; allowed: 1 to 1000000 colloids, at least one of each kind");
}

std::optional<Colloids> parse_colloids(const Ctx &c, const value *sec, const Domain &domain,
                                       int dims, bool walls) {
  if (sec == nullptr)
    return std::nullopt;
  check_keys(c, sec, "colloids");
  Colloids out;
  const auto positive = [](double x) { return x > 0.0; };
  const value *kinds = find(sec, "kind");
  if (kinds != nullptr) {
    out.kinds = parse_colloid_kinds(c, sec, *kinds);
    for (const auto &k : out.kinds) {
      out.radius = std::max(out.radius, k.radius);
      out.count += k.count;
    }
  } else if (const value *v = find(sec, "radius")) {
    out.radius = as_number(c, *v, "colloids.radius", "a number > 0 (cell units)", positive);
  } else {
    c.missing("colloids.radius", "a number > 0 (cell units; seed 000 uses 2)");
  }
  const double r = out.radius;
  if (const value *v = find(sec, "radius_sd"))
    // Radii are drawn within +-3 sd of the mean: at most 0.2 r keeps every one >= 0.4 r.
    out.radius_sd =
        as_number(c, *v, "colloids.radius_sd",
                  "a number from 0 (all radii equal) to 0.2 radius = " + float_text(0.2 * r) +
                      " (radii are drawn within +-3 radius_sd of radius)",
                  [&](double x) { return x >= 0.0 && x <= 0.2 * r; });
  // Checks that depend on the size use the largest radius a colloid can draw.
  const double r_max = out.max_radius();
  const std::string largest =
      out.radius_sd > 0.0
          ? " (the largest radius, radius + 3 radius_sd = " + float_text(r_max) + ")"
          : "";
  if (const value *v = find(sec, "coupling"))
    out.coupling = static_cast<ColloidCoupling>(
        as_choice(c, *v, "colloids.coupling", "a known coupling", {"md", "no-slip"}));
  const bool no_slip = out.coupling == ColloidCoupling::no_slip;
  if (const value *v = find(sec, "contacts")) {
    out.contacts = static_cast<ColloidContacts>(
        as_choice(c, *v, "colloids.contacts", "a known contact model", {"none", "hard", "spring"}));
    if (out.contacts != ColloidContacts::none && !no_slip)
      c.fail("colloids.contacts",
             "colloids.contacts = " + repr(*v) +
                 " resolves contacts of no-slip colloids; allowed with coupling = \"md\": "
                 "\"none\" (the 48-24 potential keeps MD colloids apart)");
  }
  if (const value *v = find(sec, "spring")) {
    if (out.contacts != ColloidContacts::spring)
      c.fail("colloids.spring", "[colloids.spring] sets the spring contacts; allowed only with "
                                "colloids.contacts = \"spring\"");
    out.spring = parse_colloid_springs(c, *v);
  }
  if (no_slip) // these set the MD potentials, which no-slip colloids do not have
    for (const char *key : {"md_substeps", "epsilon", "wall_sigma", "wall_q"})
      if (const value *v = find(sec, key))
        c.fail(std::string("colloids.") + key,
               std::string("colloids.") + key + " = " + repr(*v) +
                   " sets the MD coupling; allowed only with coupling = \"md\"");
  if (const value *v = find(sec, "mass"))
    out.mass =
        as_number(c, *v, "colloids.mass",
                  "a number > 0 (default: fluid mass density times the colloid volume)", positive);
  if (const value *v = find(sec, "epsilon"))
    out.epsilon = as_number(c, *v, "colloids.epsilon", "a number > 0 (kT units)", positive);
  if (const value *v = find(sec, "wall_q"))
    out.wall_q = as_number(c, *v, "colloids.wall_q", "a number > 0", positive);
  if (const value *v = find(sec, "md_substeps"))
    out.md_substeps =
        static_cast<int>(as_integer(c, *v, "colloids.md_substeps", "an integer from 1 to 10000",
                                    [](std::int64_t n) { return n >= 1 && n <= 10000; }));
  if (const value *v = find(sec, "gravity"))
    out.gravity = as_vector(c, *v, "colloids.gravity", dims,
                            "the gravitational acceleration g (force: mass times g)");
  const double half_width = domain.size[1] / 2.0;
  if (const value *v = find(sec, "wall_sigma")) {
    if (!walls)
      c.fail("colloids.wall_sigma", "colloids.wall_sigma = " + repr(*v) +
                                        " sets the colloid-wall potential; allowed only with "
                                        "[walls]");
    out.wall_sigma =
        as_number(c, *v, "colloids.wall_sigma",
                  "a number > 0 whose cut-off 1.0631 wall_sigma is below half the channel width (" +
                      float_text(half_width) + ")",
                  [&](double x) { return x > 0.0 && 1.0631 * x < half_width; });
  } else if (walls && !no_slip && 1.0631 * out.wall_sigma_of(r_max) >= half_width) {
    c.fail(
        "colloids.wall_sigma",
        std::string("colloids.wall_sigma defaults to ") +
            (out.radius_sd > 0.0 ? "2 r_a, at most 2 (radius + 3 radius_sd) = " : "2 radius = ") +
            float_text(2.0 * r_max) +
            ", whose cut-off 1.0631 wall_sigma does not fit in half the channel width (" +
            float_text(half_width) + "); allowed: a smaller radius" +
            (out.radius_sd > 0.0 ? " or radius_sd" : "") + " or an explicit wall_sigma");
  }
  parse_colloid_statistics(c, sec, out);
  const value *count = find(sec, "count");
  const value *placement = find(sec, "placement");
  const value *positions = find(sec, "positions");
  const value *positions_file = find(sec, "positions_file");
  bool from_file = false;
  if (placement != nullptr) {
    const std::size_t i = as_choice(c, *placement, "colloids.placement", "a known placement",
                                    {"lattice", "list", "random", "file", "packing"});
    from_file = i == 3;
    out.placement = from_file ? ColloidPlacement::list
                    : i == 4  ? ColloidPlacement::packing
                              : static_cast<ColloidPlacement>(i);
  }
  const bool packing = out.placement == ColloidPlacement::packing;
  const value *fraction = find(sec, "packing_fraction");
  if (fraction != nullptr && !packing)
    c.fail("colloids.packing_fraction",
           "colloids.packing_fraction = " + repr(*fraction) +
               " is the target of placement = \"packing\"; allowed only with it");
  if (packing)
    parse_packing(c, sec, *fraction_or_missing(c, fraction, dims), domain, dims, walls, no_slip,
                  out);
  // A position inside the box (and off the walls), or one line naming `key` and what was found.
  auto check_position = [&](const std::string &key, const std::array<double, 3> &p,
                            const std::string &found) {
    for (int d = 0; d < dims; ++d)
      if (!(p[d] >= 0.0 && p[d] < domain.size[d]))
        c.fail(key, key + " = " + found +
                        " lies outside the box; allowed: 0 <= x_k < "
                        "domain.size[k]");
    if (walls && !(p[1] > 0.0 && p[1] < domain.size[1]))
      c.fail(key, key + " = " + found + " lies on a wall; allowed: 0 < y < L_y");
  };
  const std::string coords = std::string(dims == 3 ? "x y z" : "x y");
  if (out.placement == ColloidPlacement::list && !out.kinds.empty())
    c.fail("colloids.placement", "colloids.placement = " + repr(*placement) +
                                     " cannot be mixed with [[colloids.kind]]; allowed with "
                                     "several kinds: \"lattice\" or \"random\"");
  if (out.placement == ColloidPlacement::list) {
    const std::string source = from_file ? "colloids.positions_file" : "colloids.positions";
    if (count != nullptr)
      c.fail(
          "colloids.count",
          "colloids.count = " + repr(*count) + " cannot be mixed with placement = \"" +
              (from_file ? "file" : "list") +
              "\"; allowed: the number of colloids is the number of " +
              (from_file ? "lines in colloids.positions_file" : "entries of colloids.positions"));
    if (from_file) {
      if (positions != nullptr)
        c.fail("colloids.positions",
               "colloids.positions cannot be mixed with placement = \"file\"; "
               "allowed: the positions in colloids.positions_file");
      const std::string allowed = "the path of a text file (relative to the scene file) with one "
                                  "colloid per line: " +
                                  coords + " inside the box; # comments";
      if (positions_file == nullptr)
        c.missing("colloids.positions_file", allowed);
      const std::string name = as_string(c, *positions_file, "colloids.positions_file", allowed);
      std::filesystem::path path(name);
      if (path.is_relative())
        path = std::filesystem::path(c.file()).parent_path() / path;
      std::error_code ec;
      if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
        c.fail("colloids.positions_file", "colloids.positions_file = \"" + name +
                                              "\": " + path.string() +
                                              " is not a regular file; allowed: " + allowed);
      std::ifstream in(path);
      if (!in)
        c.fail("colloids.positions_file", "colloids.positions_file = \"" + name +
                                              "\": cannot open " + path.string() +
                                              "; allowed: " + allowed);
      std::string line;
      for (int number = 1; std::getline(in, line); ++number) {
        const std::string text = line.substr(0, line.find('#'));
        std::istringstream fields(text);
        std::array<double, 3> p{0.0, 0.0, 0.0};
        int n = 0;
        std::string word;
        while (fields >> word) {
          double x = 0.0;
          const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), x);
          if (ec != std::errc() || end != word.data() + word.size() || n == dims) {
            n = -1;
            break;
          }
          p[static_cast<std::size_t>(n++)] = x;
        }
        if (n == 0)
          continue; // blank or comment
        const std::string key =
            "colloids.positions_file (" + path.string() + ":" + std::to_string(number) + ")";
        if (n != dims)
          c.fail("colloids.positions_file", key + ": found \"" + text + "\"; allowed: " +
                                                std::to_string(dims) + " numbers " + coords);
        check_position(key, p, "\"" + text + "\"");
        out.positions.push_back(p);
        out.position_keys.push_back(key);
      }
      if (out.positions.empty())
        c.fail("colloids.positions_file", "colloids.positions_file = \"" + name +
                                              "\": " + path.string() +
                                              " holds no position; allowed: " + allowed);
    } else {
      const std::string allowed =
          "an array of [x, y" + std::string(dims == 3 ? ", z" : "") + "] positions inside the box";
      if (positions_file != nullptr)
        c.fail("colloids.positions_file", "colloids.positions_file needs placement = \"file\"");
      if (positions == nullptr)
        c.missing("colloids.positions", allowed);
      if (!positions->is_array() || positions->as_array().empty())
        c.wrong_type("colloids.positions", *positions, allowed);
      const auto &a = positions->as_array();
      for (std::size_t i = 0; i < a.size(); ++i) {
        const std::string key = "colloids.positions[" + std::to_string(i) + "]";
        const auto p = as_vector(c, a[i], key, dims, "a position inside the box");
        check_position(key, p, repr(a[i]));
        out.positions.push_back(p);
        out.position_keys.push_back(key);
      }
    }
    out.count = static_cast<std::int64_t>(out.positions.size());
  } else {
    if (positions != nullptr)
      c.fail("colloids.positions", "colloids.positions needs placement = \"list\"; allowed with "
                                   "placement = \"lattice\" or \"random\": count");
    if (positions_file != nullptr)
      c.fail("colloids.positions_file",
             "colloids.positions_file needs placement = \"file\"; "
             "allowed with placement = \"lattice\" or \"random\": count");
    if (packing) {
      // the counts came from colloids.packing_fraction (parse_packing)
    } else if (out.kinds.empty()) {
      if (count == nullptr)
        c.missing("colloids.count", "an integer >= 1");
      out.count = as_integer(c, *count, "colloids.count", "an integer from 1 to 1000000",
                             [](std::int64_t n) { return n >= 1 && n <= 1000000; });
    } else if (out.count > 1000000) {
      c.fail("colloids.kind", "colloids.kind: the kinds hold " + std::to_string(out.count) +
                                  " colloids; allowed: 1 to 1000000 in all");
    }
    const double sigma_cc = 2.0 * r_max;
    if (out.placement == ColloidPlacement::lattice &&
        static_cast<double>(out.count) * sigma_cc > domain.size[0])
      c.fail(out.kinds.empty() ? "colloids.count" : "colloids.kind",
             (out.kinds.empty() ? "colloids.count = " + repr(*count)
                                : "colloids.kind: " + std::to_string(out.count)) +
                 " colloids of diameter " + float_text(sigma_cc) + largest +
                 " do not fit in a row along x of length " + float_text(domain.size[0]) +
                 "; allowed: at most " +
                 std::to_string(static_cast<std::int64_t>(domain.size[0] / sigma_cc)) +
                 " (placement = \"lattice\")");
  }
  const auto volume_of = [dims](double r) {
    return dims == 2 ? 3.14159265358979 * r * r : 4.18879020478639 * r * r * r;
  };
  double box_volume = 1.0, colloids_volume = static_cast<double>(out.count) * volume_of(r_max);
  for (int d = 0; d < dims; ++d)
    box_volume *= domain.size[d];
  if (!out.kinds.empty()) {
    colloids_volume = 0.0;
    for (const auto &k : out.kinds)
      colloids_volume += static_cast<double>(k.count) * volume_of(k.radius);
  }
  if (colloids_volume > 0.9 * box_volume)
    c.fail(out.kinds.empty() ? "colloids.count" : "colloids.kind",
           (out.kinds.empty()
                ? "colloids.count = " + std::to_string(out.count) + " colloids" + largest
                : "colloids.kind: the " + std::to_string(out.count) + " colloids of all kinds") +
               " fill more than 90 % of the box; allowed: fewer or smaller colloids");
  return out;
}

// No-slip colloids need the cells of a collision rule (their ghost particles take part in it);
// with walls or more than one colloid they need contacts that keep them apart and off the
// walls (the bounce-back assumes a surface point lies in the fluid).
void check_no_slip(const Ctx &c, const Scene &s) {
  const auto &col = *s.colloids;
  const auto rule = s.fluid.collision;
  if (rule != Collision::srd && rule != Collision::at && rule != Collision::at_a)
    c.fail("colloids.coupling", std::string("colloids.coupling = \"no-slip\" with "
                                            "fluid.collision = \"") +
                                    to_string(rule) +
                                    "\"; allowed with srd, at or at+a (the ghost particles "
                                    "inside the colloids take part in the cell collision)");
  if (s.fluid.density > 255.0)
    c.fail("colloids.coupling",
           "colloids.coupling = \"no-slip\" with fluid.density = " + float_text(s.fluid.density) +
               "; allowed: a density up to 255 (ghost particles per cell)");
  // The impulses of one step change a colloid's spin explicitly: a particle bounced at the
  // surface takes 2 (U + Omega x r - v), so K hits per step turn Omega by a factor
  // 1 - f, f = 4 K / M (2D, I = M R^2 / 2) or 10 K / (3 M) (3D, I = 2 M R^2 / 5, tangential
  // share 2/3), with K = n S sqrt(kT / 2 pi) dt the particles that cross the surface S in a
  // step. Runs with f near 1 grew without bound (2D r 1 dt 0.3: f 0.96; 3D r 2 dt 0.5: f 1.0),
  // f <= 0.67 stayed stable (tests/cli/no_slip_scenes.sh): half of that is allowed.
  // With several kinds, each kind's radius and mass.
  std::vector<std::pair<double, double>> sizes; // (radius, mass) of the smallest of each kind
  const int d = s.run.dimensions;
  if (col.kinds.empty()) {
    const double r_min = col.radius - 3.0 * col.radius_sd;
    sizes.emplace_back(r_min, col.mass_of(d, s.fluid.density, r_min));
  }
  std::uint64_t first_id = 0;
  for (const auto &kind : col.kinds) {
    sizes.emplace_back(kind.radius, col.mass_of_id(d, s.fluid.density, first_id, kind.radius));
    first_id += static_cast<std::uint64_t>(kind.count);
  }
  for (const auto &[r_min, mass] : sizes) {
    const double pi = 3.14159265358979;
    const double surface = d == 2 ? 2.0 * pi * r_min : 4.0 * pi * r_min * r_min;
    const double hits = s.fluid.density * surface * std::sqrt(s.fluid.kT / (2.0 * pi)) * s.fluid.dt;
    const double f = (d == 2 ? 4.0 : 10.0 / 3.0) * hits / mass;
    if (f > 0.5)
      c.fail("colloids.coupling",
             "colloids.coupling = \"no-slip\": the bounce-back of one step would change the "
             "spin of the smallest colloid (r " +
                 float_text(r_min) + ", M " + float_text(mass) +
                 ") by a factor f = " + float_text(f) +
                 " (explicit coupling, unstable near 1); allowed: f <= 0.5, i.e. a smaller "
                 "fluid.dt, larger or heavier colloids");
  }
  if (col.contacts == ColloidContacts::spring) {
    // The fastest spring oscillation, a tangential one of the lightest pair (the tangential
    // spring acts through 1/m_t = 3/m_red for disks, 3.5/m_red for spheres; a wall contact has
    // m_red = M), times the sub-step: velocity Verlet is stable below 2 and accurate to
    // (omega h)^2 / 24 in the contact time; beyond 0.25 the several contacts of a packed colloid
    // (frequencies up to about sqrt(2 z) higher) come near the limit.
    double m_min = std::numeric_limits<double>::infinity();
    for (const auto &[r_min, mass] : sizes)
      m_min = std::min(m_min, mass);
    const auto &k = col.spring;
    const double stiff = std::max(k.kn, (d == 2 ? 3.0 : 3.5) * k.kt);
    const double omega_h = std::sqrt(stiff / (0.5 * m_min)) * s.fluid.dt / k.substeps;
    if (omega_h > 0.25)
      c.fail("colloids.spring.substeps",
             "colloids.spring.substeps = " + std::to_string(k.substeps) +
                 ": the stiffest contact of the lightest colloids (M " + float_text(m_min) +
                 ") oscillates " + float_text(omega_h) +
                 " radians per sub-step; allowed: at most 0.25, i.e. substeps >= " +
                 std::to_string(static_cast<int>(std::ceil(k.substeps * omega_h / 0.25))) +
                 ", or softer springs");
  }
  if (col.contacts == ColloidContacts::none && (s.walls || col.count > 1))
    c.fail("colloids.contacts",
           std::string("colloids.contacts = \"none\" with no-slip colloids and ") +
               (s.walls ? "[walls]" : "colloids.count = " + std::to_string(col.count)) +
               ": they could overlap each other or a wall; allowed: contacts = \"hard\" or "
               "\"spring\", or "
               "one colloid in a periodic box");
}

std::optional<Thermostat> parse_thermostat(const Ctx &c, const value *sec, Collision rule) {
  if (sec == nullptr)
    return std::nullopt;
  check_keys(c, sec, "thermostat");
  Thermostat out;
  const value *kind = find(sec, "kind");
  if (kind == nullptr)
    c.missing("thermostat.kind", "\"layers\" (seed 000 eq 3.53-3.54) or \"monte-carlo\" (eq "
                                 "3.55-3.57)");
  out.kind = static_cast<ThermostatKind>(
      as_choice(c, *kind, "thermostat.kind", "a known thermostat", {"layers", "monte-carlo"}));
  if (const value *g = find(sec, "gamma")) {
    if (out.kind != ThermostatKind::monte_carlo)
      c.fail("thermostat.gamma", "thermostat.gamma = " + repr(*g) +
                                     " is the step of the Monte Carlo thermostat; allowed only "
                                     "with kind = \"monte-carlo\"");
    out.gamma = as_number(c, *g, "thermostat.gamma", "a number in (0, 1]",
                          [](double x) { return x > 0.0 && x <= 1.0; });
  }
  if (rule != Collision::srd && rule != Collision::random_permute)
    c.fail("thermostat", std::string("[thermostat] with fluid.collision = \"") + to_string(rule) +
                             "\"; allowed with srd or random-permute (MPC-AT thermostats "
                             "itself, random-maxwell draws at kT)");
  return out;
}

std::optional<Walls> parse_walls(const Ctx &c, const value *w,
                                 const std::optional<BodyForce> &force) {
  if (w == nullptr)
    return std::nullopt;
  check_keys(c, w, "walls");
  Walls out;
  for (const auto &[key, field] :
       {std::pair{"slip", &out.slip}, std::pair{"virtual_particles", &out.virtual_particles}}) {
    if (const value *v = find(w, key)) {
      if (!v->is_boolean())
        c.wrong_type(std::string("walls.") + key, *v, "true or false");
      *field = v->as_boolean();
    }
  }
  if (const value *v = find(w, "virtual_flow")) {
    const std::size_t i =
        as_choice(c, *v, "walls.virtual_flow", "a known virtual-particle flow", {"rest", "mirror"});
    out.virtual_flow = i == 0 ? VirtualFlow::rest : VirtualFlow::mirror;
    if (out.virtual_flow == VirtualFlow::mirror && out.slip)
      c.fail("walls.virtual_flow", "walls.virtual_flow = \"mirror\" continues the flow of a "
                                   "no-slip wall; allowed with walls.slip = true: \"rest\"");
  }
  if (force && force->kind == ForceKind::sine)
    c.fail("walls", "[walls] cannot be combined with body_force.kind = \"sine\" (the Kolmogorov "
                    "flow needs a periodic y axis); allowed: a constant body_force.value with "
                    "walls, or the sine force without [walls]");
  return out;
}

void parse_output(const Ctx &c, const value *o, Engine engine, Output &out) {
  check_keys(c, o, "output");
  if (const value *v = find(o, "dir")) {
    out.dir = as_string(c, *v, "output.dir", "a non-empty directory path");
    if (out.dir.empty())
      c.out_of_range("output.dir", *v, "a non-empty directory path");
  }
  if (const value *v = find(o, "every"))
    out.every = as_integer(c, *v, "output.every", "an integer >= 1 (steps)",
                           [](std::int64_t n) { return n >= 1; });
  if (const value *v = find(o, "observables")) {
    const std::vector<std::string> names = engine_observables(engine);
    const std::string allowed = "an array of strings from: " + join(names);
    if (!v->is_array())
      c.wrong_type("output.observables", *v, allowed);
    out.observables.clear();
    const auto &a = v->as_array();
    for (std::size_t i = 0; i < a.size(); ++i) {
      const std::string key = "output.observables[" + std::to_string(i) + "]";
      const std::string s = names[as_choice(c, a[i], key, "a known observable", names)];
      if (std::find(out.observables.begin(), out.observables.end(), s) != out.observables.end())
        c.fail(key, key + " = " + repr(a[i]) +
                        " is listed twice; allowed: each observable at most once");
      out.observables.push_back(s);
    }
  }
  if (const value *v = find(o, "checkpoint_every"))
    out.checkpoint_every =
        as_integer(c, *v, "output.checkpoint_every", "an integer >= 0 (0 = only at the end)",
                   [](std::int64_t n) { return n >= 0; });
  if (const value *v = find(o, "checkpoint_keep"))
    out.checkpoint_keep = static_cast<int>(
        as_integer(c, *v, "output.checkpoint_keep", "an integer from 1 to 1000 (checkpoints kept)",
                   [](std::int64_t n) { return n >= 1 && n <= 1000; }));
  if (const value *v = find(o, "trajectory_every"))
    out.trajectory_every =
        as_integer(c, *v, "output.trajectory_every", "an integer >= 0 (steps; 0 = no trajectory)",
                   [](std::int64_t n) { return n >= 0; });
  if (const value *v = find(o, "trajectory_subsample"))
    out.trajectory_subsample =
        as_integer(c, *v, "output.trajectory_subsample",
                   "an integer >= 1 (frames hold the fluid particles whose id is a multiple of it)",
                   [](std::int64_t n) { return n >= 1; });
  if ((engine == Engine::kmc || engine == Engine::lgca || engine == Engine::continuum) &&
      out.trajectory_every > 0)
    c.fail("output.trajectory_every",
           "output.trajectory_every = " + std::to_string(out.trajectory_every) +
               " is for particle engines; allowed with run.engine = \"" + to_string(engine) +
               "\": 0 (the lattice engines write no trajectory)");
  if (const value *v = find(o, "progress")) {
    if (!v->is_boolean())
      c.wrong_type("output.progress", *v, "true or false");
    out.progress = v->as_boolean();
  }
}

// ---- overrides ----------------------------------------------------------------------------------

// Applies one "--set a.b=value" to the parsed scene.
void apply_override(Ctx &c, value &root, const std::string &text) {
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
  const Section *sec = find_section(parts[0]);
  if (sec == nullptr)
    c.fail_set(text, "unknown key '" + join(parts, ".") +
                         "'; allowed sections: " + join(section_names()) +
                         (closest(parts[0], section_names()).empty()
                              ? std::string()
                              : "; did you mean [" + closest(parts[0], section_names()) + "]?"));
  if (std::none_of(sec->keys.begin(), sec->keys.end(),
                   [&](const char *k) { return parts[1] == k; }))
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

// ---- reading files ------------------------------------------------------------------------------

std::string read_file(const std::string &path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw input_error(one_line(path + ": cannot open scene file (" + std::strerror(EISDIR) + ")"));
  // A FIFO or device would block or never end: only regular files are read.
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw input_error(one_line(path + ": not a regular file (a FIFO, socket or device); allowed: "
                                      "a scene file"));
  errno = 0;
  std::FILE *f = std::fopen(path.c_str(), "rb");
  if (f == nullptr)
    throw input_error(one_line(path + ": cannot open scene file (" +
                               std::strerror(errno ? errno : ENOENT) + ")"));
  std::string text;
  char buf[65536];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
    text.append(buf, n);
  const bool failed = std::ferror(f) != 0;
  const int err = errno;
  std::fclose(f);
  if (failed)
    throw input_error(
        one_line(path + ": cannot read scene file (" + std::strerror(err ? err : EIO) + ")"));
  return text;
}

} // namespace

AcceptedKeys accepted_keys(Engine engine) {
  AcceptedKeys out;
  for (const auto &name : engine_sections(engine))
    for (const char *key : find_section(name)->keys)
      out.keys.push_back(name + "." + key);
  out.observables = engine_observables(engine);
  return out;
}

Scene load_scene(const std::string &path, const std::vector<std::string> &overrides) {
  return parse_scene(read_file(path), path, overrides);
}

Scene parse_scene(const std::string &text, const std::string &file,
                  const std::vector<std::string> &overrides) {
  Ctx c(file);
  value root = parse_toml(text, file);

  Scene s;
  s.file = file;
  s.text = text;
  for (const auto &o : overrides)
    apply_override(c, root, o);
  if (!overrides.empty()) {
    // Output files store the scene that ran: the overridden table, re-serialised (the
    // file's comments are lost), headed by where it came from.
    s.text = "# " + one_line(file) + " with overrides:\n";
    for (const auto &o : overrides)
      s.text += "# --set " + one_line(o) + "\n";
    s.text += toml::format(root);
  }
  s.canonical = detail::canonical_text(root);

  // The engine decides which sections exist, so it is checked first.
  const value *run = section(c, root, "run");
  s.run.engine = parse_engine(c, run);

  for (const auto &[name, v] : in_file_order(root)) {
    if (find_section(name) == nullptr)
      c.fail(name, unknown_section_message(name, *v));
  }

  parse_run(c, run, s.run);
  // Refuses the sections of other engines; `allowed` lists this engine's.
  const auto refuse_sections = [&](std::initializer_list<const char *> names, const char *engine,
                                   const char *allowed) {
    for (const char *name : names)
      if (section(c, root, name) != nullptr)
        c.fail(name, std::string("section [") + name + "] is for engine " + engine_of(name) +
                         "; allowed with run.engine = \"" + engine + "\": " + allowed);
  };
  if (s.run.engine == Engine::kmc) {
    refuse_sections({"domain", "fluid", "body_force", "walls", "colloids", "thermostat", "lattice",
                     "tagged", "colloid", "continuum"},
                    "kmc", "[run], [kmc], [output]");
    check_keys(c, section(c, root, "kmc"), "kmc");
    s.kmc = detail::parse_kmc(
        section(c, root, "kmc"),
        [&c](const std::string &key, const std::string &message) { c.fail(key, message); });
    s.output.observables = {"current", "density_profile"};
    if (s.kmc->samples > 0)
      s.output.observables.insert(s.output.observables.end(), {"shock_position", "charge_profile"});
  } else if (s.run.engine == Engine::continuum) {
    refuse_sections({"domain", "fluid", "body_force", "walls", "colloids", "thermostat", "kmc",
                     "lattice", "tagged", "colloid"},
                    "continuum", "[run], [continuum], [output]");
    check_keys(c, section(c, root, "continuum"), "continuum");
    s.continuum = detail::parse_continuum(
        section(c, root, "continuum"),
        [&c](const std::string &key, const std::string &message) { c.fail(key, message); });
    s.output.observables = {"density", "shock_position"};
    if (s.continuum->model == ContinuumModel::jamming)
      s.output.observables = {"density", "velocity"};
    if (s.continuum->model == ContinuumModel::segregation)
      s.output.observables = {"density", "evolution", "steady_density"};
  } else if (s.run.engine == Engine::lgca) {
    refuse_sections(
        {"domain", "fluid", "body_force", "walls", "colloids", "thermostat", "kmc", "continuum"},
        "lgca", "[run], [lattice], [tagged], [colloid], [output]");
    check_keys(c, section(c, root, "lattice"), "lattice");
    const auto fail = [&c](const std::string &key, const std::string &message) {
      c.fail(key, message);
    };
    s.lgca = detail::parse_lgca(section(c, root, "lattice"), fail);
    if (const value *t = section(c, root, "tagged")) {
      check_keys(c, t, "tagged");
      s.tagged = detail::parse_tagged(*t, *s.lgca, fail);
    }
    if (const value *t = section(c, root, "colloid")) {
      check_keys(c, t, "colloid");
      s.colloid = detail::parse_colloid(*t, *s.lgca, fail);
    }
    s.output.observables = {"shear_wave"};
    if (s.tagged)
      s.output.observables.push_back("vacf");
    if (s.colloid)
      s.output.observables.insert(s.output.observables.end(),
                                  {"colloid_vacf", "colloid_diffusion"});
  } else {
    for (const char *name : {"kmc", "lattice", "tagged", "colloid", "continuum"})
      if (section(c, root, name) != nullptr)
        c.fail(name, std::string("section [") + name + "] needs run.engine = \"" + engine_of(name) +
                         "\"; allowed with run.engine = \"" + std::string(to_string(s.run.engine)) +
                         "\": [run], [domain], [fluid], [body_force], [walls], [colloids], "
                         "[thermostat], [output]");
    parse_domain(c, section(c, root, "domain"), s.run.dimensions, s.domain);
    parse_fluid(c, section(c, root, "fluid"), s.domain, s.run.dimensions, s.fluid);
    s.body_force = parse_body_force(c, section(c, root, "body_force"), s.run.dimensions);
    s.walls = parse_walls(c, section(c, root, "walls"), s.body_force);
    s.colloids = parse_colloids(c, section(c, root, "colloids"), s.domain, s.run.dimensions,
                                s.walls.has_value());
    s.thermostat = parse_thermostat(c, section(c, root, "thermostat"), s.fluid.collision);
    if (s.colloids && s.colloids->coupling == ColloidCoupling::no_slip)
      check_no_slip(c, s);
  }
  parse_output(c, section(c, root, "output"), s.run.engine, s.output);
  const auto &obs = s.output.observables;
  if (s.continuum) {
    // The observables each continuum model writes (by model: conservation-law, jamming,
    // segregation).
    const std::vector<std::vector<std::string>> writes{{"density", "shock_position"},
                                                       {"density", "velocity"},
                                                       {"density", "evolution", "steady_density"}};
    const char *const models[] = {"conservation-law", "jamming", "segregation"};
    const auto model = static_cast<std::size_t>(s.continuum->model);
    const auto &mine = writes[model];
    for (const auto &name : obs)
      if (std::find(mine.begin(), mine.end(), name) == mine.end()) {
        std::string list;
        for (const auto &x : mine)
          list += (list.empty() ? "\"" : ", \"") + x + "\"";
        c.fail("output.observables", "output.observables lists \"" + name +
                                         "\", which continuum.model = \"" + models[model] +
                                         "\" does not write; allowed: " + list);
      }
  }
  const bool poiseuille = s.walls && s.body_force && s.body_force->kind == ForceKind::constant &&
                          s.body_force->value[0] != 0.0;
  for (const char *name :
       {"settling_velocity", "colloid_positions", "colloid_vacf", "colloid_diffusion",
        "colloid_msd", "colloid_angular_vacf", "density_kde"})
    if (std::find(obs.begin(), obs.end(), name) != obs.end() && !s.colloids &&
        s.run.engine == Engine::mpcd)
      c.fail("output.observables", std::string("output.observables lists \"") + name +
                                       "\", which follows colloids; allowed only with [colloids]");
  if (std::find(obs.begin(), obs.end(), "viscosity") != obs.end() && !poiseuille)
    c.fail("output.observables",
           "output.observables lists \"viscosity\", which fits the Poiseuille profile; allowed "
           "only with [walls] and a body_force.value whose x component is non-zero");
  // The fit needs two distinct values of y (L - y) over the unit bins: two bins are symmetric.
  if (std::find(obs.begin(), obs.end(), "viscosity") != obs.end() && s.domain.size[1] < 3.0)
    c.fail("output.observables", "output.observables lists \"viscosity\" with domain.size[1] = " +
                                     float_text(s.domain.size[1]) +
                                     ", too narrow to fit a parabola; allowed: domain.size[1] "
                                     ">= 3");
  return s;
}

} // namespace narrows::scene
