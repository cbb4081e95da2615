// Helpers of the section parsers (parse_kmc.cpp, parse_lgca.cpp): one-line renderings of TOML
// values for messages and a Checker that turns a wrong type or range into the one-line input
// error of the scene ("<key>: found ...; allowed: ...").
#pragma once

#include <toml.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <map>
#include <string>

namespace narrows::scene::detail {

// fail(key, message) throws the one-line input error (it never returns); the caller adds the
// source (file or --set).
using SectionFail = std::function<void(const std::string &key, const std::string &message)>;

// Shortest round-trip text of a number, always with a '.' or exponent (nan, inf as such).
std::string float_text(double x);
// A short one-line rendering of a value for messages (nested arrays and tables abridged).
std::string repr(const toml::value &v, int depth = 0);
const char *type_name(const toml::value &v);
// The value of `key` in `table` (null table or missing key: null).
const toml::value *find(const toml::value *table, const char *key);
// Keys sorted by name: messages do not depend on hash order.
std::map<std::string, const toml::value *> sorted(const toml::value &table);

class Checker {
public:
  explicit Checker(const SectionFail &fail) : fail_(fail) {}

  [[noreturn]] void fail(const std::string &key, const std::string &message) const {
    fail_(key, message);
    std::abort(); // fail_ throws
  }
  [[noreturn]] void wrong_type(const std::string &key, const toml::value &v,
                               const std::string &allowed) const {
    fail(key, key + ": found " + repr(v) + " (" + type_name(v) + "); allowed: " + allowed);
  }
  [[noreturn]] void out_of_range(const std::string &key, const toml::value &v,
                                 const std::string &allowed) const {
    fail(key, key + " = " + repr(v) + " is out of range; allowed: " + allowed);
  }

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

private:
  const SectionFail &fail_;
};

} // namespace narrows::scene::detail
