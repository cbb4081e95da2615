// Validation of the [kmc] section: lattice, rate tables, initial measure, times, replicas.
// Unknown keys of [kmc] itself are refused by the schema check (Checker::check_keys).
#include "parse_kmc.hpp"

#include "narrows/models/three_state/preset.hpp"
#include "narrows/models/three_state/rates.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace narrows::scene::detail {

namespace {

const std::string rate_allowed = "a rate >= 0";

} // namespace

void parse_bulk_rates(const Checker &c, const toml::value &v, Kmc &out, const std::string &name) {
  const std::string allowed_keys =
      "pair transitions \"ab->cd\" with states 0, 1, 2 (e.g. \"10->01\") or Tabatabaei's labels "
      "w_ij (\"w24\", i = 3 n'_k + n'_(k+1) + 1 target, j initial)";
  if (!v.is_table())
    c.wrong_type(name, v, "a table { \"10->01\" = 1.0, ... } of " + allowed_keys);
  std::map<int, std::string> seen;
  for (const auto &[k, x] : sorted(v)) {
    const std::string key = name + ".\"" + k + "\"";
    const auto t = three_state::parse_pair_key(k);
    if (!t)
      c.fail(key, "unknown transition " + key + "; allowed: " + allowed_keys);
    const int idx = t->first * 9 + t->second;
    if (seen.count(idx))
      c.fail(key, key + " names the same transition as " + name + ".\"" + seen[idx] + "\" (" +
                      three_state::pair_name(t->first, t->second) + " = " +
                      three_state::seed_label(t->first, t->second) +
                      "); allowed: each transition once");
    seen[idx] = k;
    out.rates[idx] = c.number(*x, key, rate_allowed, [](double r) { return r >= 0.0; });
  }
}

namespace {

void parse_site_rates(const Checker &c, const toml::value &v, bool left, Kmc &out) {
  const std::string name = left ? "kmc.left" : "kmc.right";
  const std::string allowed_keys =
      std::string("state changes of site ") + (left ? "1" : "L") +
      " \"a->b\" with states 0, 1, 2 (e.g. \"0->1\") or Tabatabaei's names " +
      (left ? "alpha1-3, gamma1-3 (eq 2.2)" : "delta1-3, beta1-3 (eq 2.3)");
  if (!v.is_table())
    c.wrong_type(name, v, "a table { \"0->1\" = 0.3, ... } of " + allowed_keys);
  auto &table = left ? out.left : out.right;
  std::map<int, std::string> seen;
  for (const auto &[k, x] : sorted(v)) {
    const std::string key = name + ".\"" + k + "\"";
    const auto t = three_state::parse_site_key(k, left);
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

// P(n) for n = 0, 1, 2 from an array of 3 numbers >= 0 summing to 1.
std::array<double, 3> parse_probabilities(const Checker &c, const toml::value &p,
                                          const std::string &key) {
  const std::string allowed = "an array of 3 numbers >= 0 summing to 1 (P(n) for n = 0, 1, 2)";
  if (!p.is_array() || p.as_array().size() != 3)
    c.wrong_type(key, p, allowed);
  std::array<double, 3> out{};
  double sum = 0.0;
  for (int s = 0; s < 3; ++s) {
    out[s] = c.number(p.as_array()[s], key + "[" + std::to_string(s) + "]", allowed,
                      [](double x) { return x >= 0.0; });
    sum += out[s];
  }
  if (std::abs(sum - 1.0) > 1e-9)
    c.fail(key, key + " = " + repr(p) + " sums to " + float_text(sum) + "; allowed: " + allowed);
  return out;
}

// Returns whether the probabilities were given (otherwise a preset's fugacities fill them).
bool parse_initial(const Checker &c, const toml::value &v, Kmc &out) {
  const std::string allowed =
      "{ kind = \"product\", probabilities = [p0, p1, p2] } or { kind = \"shock\", site = k, "
      "left = [p0, p1, p2], right = [p0, p1, p2] } (probabilities may be left out when "
      "kmc.fugacity is given)";
  if (!v.is_table())
    c.wrong_type("kmc.initial", v, allowed);
  const toml::value *kind = find(&v, "kind");
  if (kind == nullptr)
    c.fail("kmc.initial.kind",
           "missing required key 'kmc.initial.kind'; allowed: \"product\", \"shock\"");
  if (!kind->is_string())
    c.wrong_type("kmc.initial.kind", *kind, "\"product\" or \"shock\"");
  const std::string k = kind->as_string().str;
  if (k != "product" && k != "shock")
    c.fail("kmc.initial.kind",
           "kmc.initial.kind = " + repr(*kind) + " is not known; allowed: \"product\", \"shock\"");
  const bool shock = k == "shock";
  out.initial_kind = shock ? KmcInitial::shock : KmcInitial::product;
  for (const auto &[key, x] : sorted(v)) {
    (void)x;
    const bool ok = key == "kind" || (!shock && key == "probabilities") ||
                    (shock && (key == "site" || key == "left" || key == "right"));
    if (!ok)
      c.fail("kmc.initial." + key, "unknown key 'kmc.initial." + key + "' for kind = \"" + k +
                                       "\"; allowed keys: " +
                                       (shock ? "kind, site, left, right" : "kind, probabilities"));
  }
  const bool fugacity = !out.fugacity.empty();
  if (!shock) {
    const toml::value *p = find(&v, "probabilities");
    if (p == nullptr) {
      if (fugacity)
        return false;
      c.fail("kmc.initial.probabilities",
             "missing required key 'kmc.initial.probabilities'; allowed: an array of 3 numbers "
             ">= 0 summing to 1 (or give kmc.preset and kmc.fugacity)");
    }
    out.initial = parse_probabilities(c, *p, "kmc.initial.probabilities");
    return true;
  }
  const std::string site_allowed =
      "an integer from 1 to " + std::to_string(out.length - 1) + " (sites 1..site left of it)";
  const toml::value *site = find(&v, "site");
  if (site == nullptr)
    c.fail("kmc.initial.site", "missing required key 'kmc.initial.site'; allowed: " + site_allowed);
  const std::int64_t L = out.length;
  out.shock_site = c.integer(*site, "kmc.initial.site", site_allowed,
                             [L](std::int64_t n) { return n >= 1 && n < L; });
  const toml::value *left = find(&v, "left");
  const toml::value *right = find(&v, "right");
  if ((left == nullptr) != (right == nullptr))
    c.fail(left ? "kmc.initial.right" : "kmc.initial.left",
           std::string("missing key '") + (left ? "kmc.initial.right" : "kmc.initial.left") +
               "'; allowed: both left and right probabilities, or neither (from kmc.fugacity)");
  if (left == nullptr) {
    if (out.fugacity.size() == 2)
      return false;
    c.fail("kmc.initial.left",
           "missing key 'kmc.initial.left'; allowed: left and right probabilities, or "
           "kmc.fugacity = [z_left, z_right] with a kmc.preset");
  }
  out.initial = parse_probabilities(c, *left, "kmc.initial.left");
  out.initial_right = parse_probabilities(c, *right, "kmc.initial.right");
  return true;
}

const char *const family2_names[] = {"h1", "h2", "h3", "h4", "h5", "h6", "r1", "r2",
                                     "r3", "r4", "r5", "r6", "r7", "r8", "r9"};

} // namespace

void parse_family2(const Checker &c, const toml::value &v, Kmc &out, const std::string &name) {
  const std::string allowed_keys = "c (> 0, required) and rates h1-h6, r1-r9 (>= 0, default 0)";
  if (!v.is_table())
    c.wrong_type(name, v, "a table of " + allowed_keys);
  std::array<double, 6> h{};
  std::array<double, 9> r{};
  bool has_c = false;
  for (const auto &[k, x] : sorted(v)) {
    const std::string key = name + "." + k;
    if (k == "c") {
      out.c = c.number(*x, key, "a number > 0 (ratio of B to A, eq 2.81)",
                       [](double y) { return y > 0.0; });
      has_c = true;
      continue;
    }
    int idx = -1;
    for (int i = 0; i < 15; ++i)
      if (k == family2_names[i])
        idx = i;
    if (idx < 0)
      c.fail(key, "unknown key '" + key + "'; allowed keys in " + name + ": " + allowed_keys);
    const double val = c.number(*x, key, rate_allowed, [](double y) { return y >= 0.0; });
    if (idx < 6)
      h[idx] = val;
    else
      r[idx - 6] = val;
  }
  if (!has_c)
    c.fail(name + ".c", "missing required key '" + name + ".c'; allowed: a number > 0 (eq 2.81)");
  out.rates = three_state::family2_rates(h, r, out.c);
}

// Family 1 allows only the ten transitions of eq 2.5 (those keeping n_k + n_(k+1)).
void check_family1_rates(const Checker &c, const Kmc &out, const std::string &name,
                         const std::string &with) {
  for (int from = 0; from < 9; ++from)
    for (int to = 0; to < 9; ++to)
      if (out.rates[from * 9 + to] > 0.0 && from / 3 + from % 3 != to / 3 + to % 3)
        c.fail(name, name + " gives " + three_state::pair_name(from, to) + " (" +
                         three_state::seed_label(from, to) +
                         "), which is not a transition of family 1; allowed with " + with +
                         ": w24, w42, w37, w73, w86, w68, w35, w53, w57, w75 (eq 2.5)");
}

Kmc parse_kmc(const toml::value *sec, const Checker &c) {
  if (sec == nullptr)
    c.fail("kmc", "missing required section [kmc] (run.engine = \"kmc\"); allowed keys in [kmc]: " +
                      join(names_of(find_section("kmc")->keys)) +
                      " (length, rates or parameters, initial or fugacity, and time are required)");
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

  if (const toml::value *v = find(sec, "preset")) {
    const std::string allowed = "\"none\", \"family1\" (eq 2.5), \"family2\" (eq 2.79)";
    if (!v->is_string())
      c.wrong_type("kmc.preset", *v, allowed);
    const std::string s = v->as_string().str;
    if (s == "family1")
      out.preset = KmcPreset::family1;
    else if (s == "family2")
      out.preset = KmcPreset::family2;
    else if (s != "none")
      c.fail("kmc.preset", "kmc.preset = " + repr(*v) + " is not known; allowed: " + allowed);
  }
  const toml::value *params = find(sec, "parameters");
  if (out.preset == KmcPreset::family2) {
    if (find(sec, "rates") != nullptr)
      c.fail("kmc.rates", "kmc.rates is given with kmc.preset = \"family2\", whose 24 rates "
                          "come from kmc.parameters (eq 2.86); allowed: one of the two");
    if (params == nullptr)
      c.fail("kmc.parameters", "missing required key 'kmc.parameters' for kmc.preset = "
                               "\"family2\"; allowed: a table with c and rates h1-h6, r1-r9");
    parse_family2(c, *params, out, "kmc.parameters");
  } else {
    if (params != nullptr)
      c.fail("kmc.parameters",
             "kmc.parameters needs kmc.preset = \"family2\"; allowed otherwise: kmc.rates");
    if (const toml::value *v = find(sec, "rates"))
      parse_bulk_rates(c, *v, out, "kmc.rates");
    else
      c.fail("kmc.rates", "missing required key 'kmc.rates'; allowed: a table of pair "
                          "transition rates, e.g. rates = { \"10->01\" = 1.0 }");
    if (out.preset == KmcPreset::family1)
      check_family1_rates(c, out, "kmc.rates", "kmc.preset = \"family1\"");
  }
  if (const toml::value *v = find(sec, "fugacity")) {
    const std::string allowed = "a number z >= 0 or an array [z_left, z_right] of two (a shock); "
                                "needs kmc.preset";
    if (out.preset == KmcPreset::none)
      c.fail("kmc.fugacity", "kmc.fugacity needs kmc.preset = \"family1\" or \"family2\"");
    if (v->is_array()) {
      if (v->as_array().size() != 2)
        c.wrong_type("kmc.fugacity", *v, allowed);
      for (int i = 0; i < 2; ++i)
        out.fugacity.push_back(c.number(v->as_array()[i], "kmc.fugacity[" + std::to_string(i) + "]",
                                        allowed, [](double z) { return z >= 0.0; }));
    } else {
      out.fugacity.push_back(
          c.number(*v, "kmc.fugacity", allowed, [](double z) { return z >= 0.0; }));
    }
  }
  if (const toml::value *v = find(sec, "boundary_rates")) {
    const std::string allowed =
        "\"given\" (kmc.left, kmc.right) or \"fugacity\" (made to fit kmc.fugacity)";
    if (!v->is_string())
      c.wrong_type("kmc.boundary_rates", *v, allowed);
    const std::string s = v->as_string().str;
    if (s == "fugacity")
      out.boundary_from_fugacity = true;
    else if (s != "given")
      c.fail("kmc.boundary_rates",
             "kmc.boundary_rates = " + repr(*v) + " is not known; allowed: " + allowed);
    if (out.boundary_from_fugacity) {
      if (out.fugacity.empty() || out.boundary != KmcBoundary::open)
        c.fail("kmc.boundary_rates", "kmc.boundary_rates = \"fugacity\" needs kmc.fugacity "
                                     "and kmc.boundary = \"open\"");
      for (const char *side : {"left", "right"})
        if (find(sec, side) != nullptr)
          c.fail(std::string("kmc.") + side,
                 std::string("kmc.") + side +
                     " is given with kmc.boundary_rates = \"fugacity\"; allowed: one of the two");
    }
  }
  if (const toml::value *v = find(sec, "boundary_coupling"))
    out.boundary_coupling = c.number(*v, "kmc.boundary_coupling",
                                     "a number > 0 (base rate of generated boundary rates)",
                                     [](double x) { return x > 0.0; });
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

  bool initial_given = false;
  if (const toml::value *v = find(sec, "initial"))
    initial_given = parse_initial(c, *v, out);
  else if (out.fugacity.size() == 1)
    initial_given = false; // the stationary product measure of the preset
  else
    c.fail("kmc.initial",
           "missing required key 'kmc.initial'; allowed: { kind = \"product\", probabilities "
           "= [p0, p1, p2] } or { kind = \"shock\", site = k, ... }");
  if (out.initial_kind == KmcInitial::product && !initial_given && out.fugacity.size() != 1)
    c.fail("kmc.initial.probabilities",
           "kmc.initial of kind \"product\" without probabilities needs one fugacity; found "
           "kmc.fugacity with " +
               std::to_string(out.fugacity.size()) + " values");

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

  if (const toml::value *v = find(sec, "samples"))
    out.samples = c.integer(*v, "kmc.samples",
                            "an integer from 0 to 100000 (shock position samples over kmc.time)",
                            [](std::int64_t n) { return n >= 0 && n <= 100000; });
  else if (out.initial_kind == KmcInitial::shock)
    out.samples = 100;

  const bool keep_charge = find(sec, "charge") != nullptr;
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
  three_state::apply_preset(out, keep_charge, initial_given);

  // The work of one replica: a Poisson number of tries at rate slots x R_max over the simulated
  // time (kmc/lattice.cpp), R_max the largest total rate out of one bond or boundary state.
  if (const toml::value *v = find(sec, "max_tries"))
    out.max_tries = c.number(*v, "kmc.max_tries", "a number > 0 (expected tries per replica)",
                             [](double x) { return x > 0.0 && std::isfinite(x); });
  double r_max = 0.0;
  for (int from = 0; from < 9; ++from) {
    double sum = 0.0;
    for (int to = 0; to < 9; ++to)
      if (to != from && out.rates[from * 9 + to] > 0.0)
        sum += out.rates[from * 9 + to];
    r_max = std::max(r_max, sum);
  }
  const bool open = out.boundary == KmcBoundary::open;
  for (const auto *table : {&out.left, &out.right})
    for (int from = 0; open && from < 3; ++from) {
      double sum = 0.0;
      for (int to = 0; to < 3; ++to)
        if (to != from && (*table)[from * 3 + to] > 0.0)
          sum += (*table)[from * 3 + to];
      r_max = std::max(r_max, sum);
    }
  const double slots = static_cast<double>(out.length) + (open ? 1.0 : 0.0);
  const double tries = slots * r_max * (out.warmup + out.time);
  if (!(tries <= out.max_tries)) {
    char line[400];
    std::snprintf(line, sizeof line,
                  "kmc: %.3g expected tries per replica (%.0f slots x largest total rate %.3g x "
                  "(warmup + time) %.3g); allowed: at most kmc.max_tries = %.3g (raise "
                  "kmc.max_tries to run it: about 1e8 tries take a second)",
                  tries, slots, r_max, out.warmup + out.time, out.max_tries);
    c.fail("kmc.max_tries", line);
  }
  return out;
}

void parse_kmc_scene(const Checker &c, const toml::value &root, Scene &s) {
  const toml::value *sec = c.section(root, "kmc");
  c.check_keys(sec, "kmc");
  s.kmc = parse_kmc(sec, c);
}

} // namespace narrows::scene::detail
