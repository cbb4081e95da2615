// The one checker of scene values, which every section parser uses: typed getters that turn a
// wrong type, a value out of range or a missing key into the scene's one-line input error
//   <source>: <key> ... found ...; allowed: ...
// where <source> is the scene file, or "--set '<override>'" when the value came from the
// command line (the checker remembers which keys the overrides set).
#pragma once

#include "message_text.hpp"
#include "narrows/scene/schema.hpp"

#include <toml.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace narrows::scene::detail {

// The value of `key` in `table` (null table or missing key: null).
const toml::value *find(const toml::value *table, const char *key);
// Keys sorted by name: messages do not depend on hash order.
std::map<std::string, const toml::value *> sorted(const toml::value &table);
// Keys of a table in the order they appear in the file (ties: by name).
std::vector<std::pair<std::string, const toml::value *>> in_file_order(const toml::value &table);
// The names of keys of the schema, in its order.
std::vector<std::string> names_of(const std::vector<KeySpec> &keys);
// The keys of the table-valued key `section.key` of the schema (e.g. colloids.spring).
const std::vector<KeySpec> &sub_keys(std::string_view section, std::string_view key);

class Checker {
public:
  // `file`: the scene file, named by every message.
  explicit Checker(std::string file) : file_(std::move(file)) {}

  // Remember that the value at `key` (section.key) came from `--set '<text>'`.
  void from_override(const std::string &key, const std::string &text) { set_[key] = text; }
  const std::string &file() const { return file_; }

  // Throws the input error `message`, naming where the value at `key` came from.
  [[noreturn]] void fail(const std::string &key, const std::string &message) const;
  // Throws the input error `message` about the override `--set '<text>'` itself.
  [[noreturn]] void fail_set(const std::string &text, const std::string &message) const;
  [[noreturn]] void wrong_type(const std::string &key, const toml::value &v,
                               const std::string &allowed) const {
    fail(key, key + ": found " + repr(v) + " (" + type_name(v) + "); allowed: " + allowed);
  }
  [[noreturn]] void out_of_range(const std::string &key, const toml::value &v,
                                 const std::string &allowed) const {
    fail(key, key + " = " + repr(v) + " is out of range; allowed: " + allowed);
  }
  [[noreturn]] void missing(const std::string &key, const std::string &allowed) const {
    fail(key, "missing required key '" + key + "'; allowed: " + allowed);
  }

  // A number (integers accepted) that must be finite and satisfy ok(x).
  template <class Pred>
  double number(const toml::value &v, const std::string &key, const std::string &allowed,
                Pred ok) const {
    double x = 0.0;
    if (v.is_integer())
      x = static_cast<double>(v.as_integer());
    else if (v.is_floating())
      x = v.as_floating();
    else
      wrong_type(key, v, allowed);
    if (!std::isfinite(x) || !ok(x))
      out_of_range(key, v, allowed);
    return x;
  }

  template <class Pred>
  std::int64_t integer(const toml::value &v, const std::string &key, const std::string &allowed,
                       Pred ok) const {
    if (!v.is_integer())
      wrong_type(key, v, allowed);
    if (!ok(v.as_integer()))
      out_of_range(key, v, allowed);
    return v.as_integer();
  }

  std::string string(const toml::value &v, const std::string &key,
                     const std::string &allowed) const;
  // A string naming one of `names` (`what`: "a known collision rule"); returns its index.
  std::size_t choice(const toml::value &v, const std::string &key, const char *what,
                     const std::vector<std::string> &names) const;
  // An array of `dims` finite numbers (`what` they are, for the message).
  std::array<double, 3> vector(const toml::value &v, const std::string &key, int dims,
                               const std::string &what) const;

  // The table [name] of the scene (null if absent); refuses a value that is not a table.
  const toml::value *section(const toml::value &root, const char *name) const;
  // Refuses a key of the table `sec` (may be null) that the schema's section `name` lacks.
  void check_keys(const toml::value *sec, const char *name) const;

private:
  std::string file_;
  std::map<std::string, std::string> set_; // key -> the override that set it
};

} // namespace narrows::scene::detail
