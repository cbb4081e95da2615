// Validation of the [kmc] section: lattice, rate tables, initial measure, times, replicas.
// Unknown keys of [kmc] itself are refused by the generic schema check in parse.cpp.
#include "parse_kmc.hpp"

#include "narrows/kmc/rates.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace narrows::scene::detail {

namespace {

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

class Checker {
public:
  explicit Checker(const KmcFail &fail) : fail_(fail) {}

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
  const KmcFail &fail_;
};

const toml::value *find(const toml::value *table, const char *key) {
  if (table == nullptr)
    return nullptr;
  const auto &t = table->as_table();
  const auto it = t.find(key);
  return it == t.end() ? nullptr : &it->second;
}

// Keys sorted by name: messages do not depend on hash order.
std::map<std::string, const toml::value *> sorted(const toml::value &table) {
  std::map<std::string, const toml::value *> out;
  for (const auto &[k, v] : table.as_table())
    out.emplace(k, &v);
  return out;
}

const std::string rate_allowed = "a rate >= 0";

void parse_bulk_rates(const Checker &c, const toml::value &v, Kmc &out) {
  const std::string allowed_keys =
      "pair transitions \"ab->cd\" with states 0, 1, 2 (e.g. \"10->01\") or the seed's labels "
      "w_ij (\"w24\", i = 3 n'_k + n'_(k+1) + 1 target, j initial)";
  if (!v.is_table())
    c.wrong_type("kmc.rates", v, "a table { \"10->01\" = 1.0, ... } of " + allowed_keys);
  std::map<int, std::string> seen;
  for (const auto &[k, x] : sorted(v)) {
    const std::string key = "kmc.rates.\"" + k + "\"";
    const auto t = kmc::parse_pair_key(k);
    if (!t)
      c.fail(key, "unknown transition " + key + "; allowed: " + allowed_keys);
    const int idx = t->first * 9 + t->second;
    if (seen.count(idx))
      c.fail(key, key + " names the same transition as kmc.rates.\"" + seen[idx] + "\" (" +
                      kmc::pair_name(t->first, t->second) + " = " +
                      kmc::seed_label(t->first, t->second) + "); allowed: each transition once");
    seen[idx] = k;
    out.rates[idx] = c.number(*x, key, rate_allowed, [](double r) { return r >= 0.0; });
  }
}

void parse_site_rates(const Checker &c, const toml::value &v, bool left, Kmc &out) {
  const std::string name = left ? "kmc.left" : "kmc.right";
  const std::string allowed_keys =
      std::string("state changes of site ") + (left ? "1" : "L") +
      " \"a->b\" with states 0, 1, 2 (e.g. \"0->1\") or the seed's names " +
      (left ? "alpha1-3, gamma1-3 (eq 2.2)" : "delta1-3, beta1-3 (eq 2.3)");
  if (!v.is_table())
    c.wrong_type(name, v, "a table { \"0->1\" = 0.3, ... } of " + allowed_keys);
  auto &table = left ? out.left : out.right;
  std::map<int, std::string> seen;
  for (const auto &[k, x] : sorted(v)) {
    const std::string key = name + ".\"" + k + "\"";
    const auto t = kmc::parse_site_key(k, left);
    if (!t)
      c.fail(key, "unknown transition " + key + "; allowed: " + allowed_keys);
    const int idx = t->first * 3 + t->second;
    if (seen.count(idx))
      c.fail(key, key + " names the same transition as " + name + ".\"" + seen[idx] +
                      "\"; allowed: each transition once");
    seen[idx] = k;
    table[idx] = c.number(*x, key, rate_allowed, [](double r) { return r >= 0.0; });
  }
}

void parse_initial(const Checker &c, const toml::value &v, Kmc &out) {
  const std::string allowed =
      "{ kind = \"product\", probabilities = [p0, p1, p2] } with p >= 0 summing to 1";
  if (!v.is_table())
    c.wrong_type("kmc.initial", v, allowed);
  for (const auto &[k, x] : sorted(v)) {
    (void)x;
    if (k != "kind" && k != "probabilities")
      c.fail("kmc.initial." + k, "unknown key 'kmc.initial." + k +
                                     "'; allowed keys in kmc.initial: kind, probabilities");
  }
  const toml::value *kind = find(&v, "kind");
  if (kind == nullptr)
    c.fail("kmc.initial.kind", "missing required key 'kmc.initial.kind'; allowed: \"product\"");
  if (!kind->is_string())
    c.wrong_type("kmc.initial.kind", *kind, "\"product\"");
  if (kind->as_string().str != "product")
    c.fail("kmc.initial.kind", "kmc.initial.kind = " + repr(*kind) +
                                   " is not available in this version; allowed: \"product\"");
  const toml::value *p = find(&v, "probabilities");
  const std::string p_allowed = "an array of 3 numbers >= 0 summing to 1 (P(n) for n = 0, 1, 2)";
  if (p == nullptr)
    c.fail("kmc.initial.probabilities",
           "missing required key 'kmc.initial.probabilities'; allowed: " + p_allowed);
  if (!p->is_array() || p->as_array().size() != 3)
    c.wrong_type("kmc.initial.probabilities", *p, p_allowed);
  double sum = 0.0;
  for (int s = 0; s < 3; ++s) {
    out.initial[s] =
        c.number(p->as_array()[s], "kmc.initial.probabilities[" + std::to_string(s) + "]",
                 p_allowed, [](double x) { return x >= 0.0; });
    sum += out.initial[s];
  }
  if (std::abs(sum - 1.0) > 1e-9)
    c.fail("kmc.initial.probabilities", "kmc.initial.probabilities = " + repr(*p) + " sums to " +
                                            number_text(sum) + "; allowed: " + p_allowed);
}

} // namespace

Kmc parse_kmc(const toml::value *sec, const KmcFail &fail) {
  const Checker c(fail);
  if (sec == nullptr)
    c.fail("kmc", "missing required section [kmc] (run.engine = \"kmc\"); allowed keys in [kmc]: "
                  "length, boundary, rates, left, right, initial, time, warmup, replicas, charge "
                  "(length, rates, initial and time are required)");
  Kmc out;

  const std::string len_allowed = "an integer from 2 (open) or 3 (periodic) to 2147483647 (sites)";
  if (const toml::value *v = find(sec, "length"))
    out.length = c.integer(*v, "kmc.length", len_allowed,
                           [](std::int64_t n) { return n >= 2 && n <= 2147483647; });
  else
    c.fail("kmc.length", "missing required key 'kmc.length'; allowed: " + len_allowed);

  if (const toml::value *v = find(sec, "boundary")) {
    if (!v->is_string())
      c.wrong_type("kmc.boundary", *v, "\"open\" or \"periodic\"");
    const std::string s = v->as_string().str;
    if (s == "open")
      out.boundary = KmcBoundary::open;
    else if (s == "periodic")
      out.boundary = KmcBoundary::periodic;
    else
      c.fail("kmc.boundary",
             "kmc.boundary = " + repr(*v) + " is not a known boundary; allowed: open, periodic");
  }

  if (out.boundary == KmcBoundary::periodic && out.length < 3)
    c.out_of_range("kmc.length", *find(sec, "length"), len_allowed);

  if (const toml::value *v = find(sec, "rates"))
    parse_bulk_rates(c, *v, out);
  else
    c.fail("kmc.rates", "missing required key 'kmc.rates'; allowed: a table of pair transition "
                        "rates, e.g. rates = { \"10->01\" = 1.0 }");
  for (const char *side : {"left", "right"})
    if (const toml::value *v = find(sec, side)) {
      if (out.boundary == KmcBoundary::periodic && !(v->is_table() && v->as_table().empty()))
        c.fail(std::string("kmc.") + side,
               std::string("kmc.") + side + " = " + repr(*v) +
                   " needs kmc.boundary = \"open\"; allowed: no boundary rates when periodic");
      parse_site_rates(c, *v, side[0] == 'l', out);
    }

  bool any = false;
  for (double r : out.rates)
    any = any || r > 0.0;
  if (!any)
    c.fail("kmc.rates", "kmc.rates has no positive rate; allowed: at least one bulk transition "
                        "with a rate > 0");

  if (const toml::value *v = find(sec, "initial"))
    parse_initial(c, *v, out);
  else
    c.fail("kmc.initial",
           "missing required key 'kmc.initial'; allowed: { kind = \"product\", probabilities "
           "= [p0, p1, p2] }");

  const std::string time_allowed = "a number > 0 (simulated time observed after warm-up)";
  if (const toml::value *v = find(sec, "time"))
    out.time = c.number(*v, "kmc.time", time_allowed, [](double x) { return x > 0.0; });
  else
    c.fail("kmc.time", "missing required key 'kmc.time'; allowed: " + time_allowed);
  if (const toml::value *v = find(sec, "warmup"))
    out.warmup = c.number(*v, "kmc.warmup", "a number >= 0 (simulated time before observing)",
                          [](double x) { return x >= 0.0; });
  if (const toml::value *v = find(sec, "replicas"))
    out.replicas = c.integer(*v, "kmc.replicas", "an integer from 1 to 1000000",
                             [](std::int64_t n) { return n >= 1 && n <= 1000000; });

  if (const toml::value *v = find(sec, "charge")) {
    const std::string allowed =
        "an array of 3 integers [C(0), C(1), C(2)] (the charge the current counts; default "
        "[0, 1, 2])";
    if (!v->is_array() || v->as_array().size() != 3)
      c.wrong_type("kmc.charge", *v, allowed);
    for (int s = 0; s < 3; ++s)
      out.charge[s] = static_cast<int>(
          c.integer(v->as_array()[s], "kmc.charge[" + std::to_string(s) + "]", allowed,
                    [](std::int64_t n) { return n >= -1000 && n <= 1000; }));
  }
  return out;
}

} // namespace narrows::scene::detail
