// Validation of the [continuum] section: model, flux and its parameters, grid, boundary,
// initial data, time and numerics; and the observables each model writes. Unknown keys of
// [continuum] itself are refused by the schema check (Checker::check_keys).
#include "parse_continuum.hpp"
#include "parse_jamming_vss.hpp"
#include "parse_kmc.hpp"

#include "narrows/models/three_state/preset.hpp"
#include "narrows/models/three_state/rates.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace narrows::scene::detail {

namespace {

std::string choice_list(const std::vector<std::string> &names) {
  std::string s;
  for (const auto &n : names)
    s += (s.empty() ? "\"" : ", \"") + n + "\"";
  return s;
}

// The index of a string value among `names`, or a one-line refusal.
std::size_t choice(const Checker &c, const toml::value &v, const std::string &key,
                   const std::vector<std::string> &names) {
  if (!v.is_string())
    c.wrong_type(key, v, choice_list(names));
  for (std::size_t i = 0; i < names.size(); ++i)
    if (v.as_string().str == names[i])
      return i;
  c.fail(key, key + " = " + repr(v) + " is not known; allowed: " + choice_list(names));
}

bool finite(double) { return true; }

// The value of continuum.<name>, or a refusal saying what is allowed.
const toml::value &required_key(const Checker &c, const toml::value *sec, const char *name,
                                const std::string &what) {
  const toml::value *x = find(sec, name);
  if (x == nullptr)
    c.fail(std::string("continuum.") + name,
           std::string("missing required key 'continuum.") + name + "'; allowed: " + what);
  return *x;
}

// The grid spacing length / cells within 1e-100 to 1e100: the time step divides by dx^2, which
// is 0 below about 1e-162 (continuum.length = 5e-324 gave dt = 10 and a NaN Courant number).
void check_spacing(const Checker &c, const Continuum &out) {
  const double dx = out.length / static_cast<double>(out.cells);
  if (!(dx >= 1e-100 && dx <= 1e100)) {
    char line[300];
    std::snprintf(line, sizeof line,
                  "continuum.length = %.3g over continuum.cells = %lld gives a spacing of %.3g; "
                  "allowed: a length / cells from 1e-100 to 1e100",
                  out.length, static_cast<long long>(out.cells), dx);
    c.fail("continuum.length", line);
  }
}

// The densities a flux is defined for: charge sigma in [-1, 1] (family 1), particle density in
// [0, 1] (tasep, family 2), any number (burgers, colloid-chain).
struct Range {
  double lo, hi;
  std::string text;
};
Range density_range(ContinuumFlux f) {
  if (f == ContinuumFlux::family1)
    return {-1.0, 1.0, "a charge density from -1 to 1 (family 1)"};
  if (f == ContinuumFlux::tasep || f == ContinuumFlux::family2)
    return {0.0, 1.0, "a particle density from 0 to 1"};
  return {-1e300, 1e300, "a finite number"};
}

double density(const Checker &c, const toml::value &v, const std::string &key, const Range &r) {
  return c.number(v, key, r.text, [&r](double x) { return x >= r.lo && x <= r.hi; });
}

void parse_lattice_gas(const Checker &c, const toml::value *sec, Continuum &out) {
  Kmc &m = out.lattice_gas;
  const toml::value *rates = find(sec, "rates");
  const toml::value *params = find(sec, "parameters");
  if (out.flux == ContinuumFlux::family2) {
    if (rates != nullptr)
      c.fail("continuum.rates", "continuum.rates is given with continuum.flux = \"family2\", "
                                "whose rates come from continuum.parameters (eq 2.86); allowed: "
                                "continuum.parameters");
    if (params == nullptr)
      c.fail("continuum.parameters",
             "missing required key 'continuum.parameters' for continuum.flux = \"family2\"; "
             "allowed: a table with c and rates h1-h6, r1-r9 (as kmc.parameters)");
    m.preset = KmcPreset::family2;
    parse_family2(c, *params, m, "continuum.parameters");
    return;
  }
  if (params != nullptr)
    c.fail("continuum.parameters", "continuum.parameters needs continuum.flux = \"family2\"; "
                                   "allowed otherwise: continuum.rates");
  if (out.flux == ContinuumFlux::family1) {
    if (rates == nullptr)
      c.fail("continuum.rates", "missing required key 'continuum.rates' for continuum.flux = "
                                "\"family1\"; allowed: family 1's pair rates as in kmc.rates, "
                                "e.g. { w42 = 1.0, w24 = 0.2 }");
    m.preset = KmcPreset::family1;
    parse_bulk_rates(c, *rates, m, "continuum.rates");
    check_family1_rates(c, m, "continuum.rates", "continuum.flux = \"family1\"");
  } else { // tasep: ASEP hops of particles (state 1) into holes (state 0): family 2 without B
    m.preset = KmcPreset::family2;
    m.c = 0.0;
    if (rates == nullptr)
      m.rates[three_state::pair_code(1, 0) * 9 + three_state::pair_code(0, 1)] = 1.0;
    else
      parse_bulk_rates(c, *rates, m, "continuum.rates");
    for (int from = 0; from < 9; ++from)
      for (int to = 0; to < 9; ++to) {
        const bool hop =
            (from == three_state::pair_code(1, 0) && to == three_state::pair_code(0, 1)) ||
            (from == three_state::pair_code(0, 1) && to == three_state::pair_code(1, 0));
        if (m.rates[from * 9 + to] > 0.0 && !hop)
          c.fail("continuum.rates",
                 "continuum.rates gives " + three_state::pair_name(from, to) +
                     ", which is not a hop of TASEP/ASEP; allowed with continuum.flux = "
                     "\"tasep\": \"10->01\" (right, default 1) and \"01->10\" (left)");
      }
  }
  bool any = false;
  for (double r : m.rates)
    any = any || r > 0.0;
  if (!any)
    c.fail("continuum.rates", "continuum.rates has no positive rate; allowed: at least one "
                              "transition with a rate > 0");
}

// Refuses a key of the initial table that its kind does not have (`mine`: the kind's keys).
void check_initial_keys(const Checker &c, const toml::value &v, const toml::value &kind,
                        const std::vector<std::string> &mine) {
  for (const auto &[key, x] : sorted(v)) {
    (void)x;
    if (std::find(mine.begin(), mine.end(), key) == mine.end()) {
      std::string list;
      for (const auto &m : mine)
        list += (list.empty() ? "" : ", ") + m;
      c.fail("continuum.initial." + key, "unknown key 'continuum.initial." + key + "' for kind = " +
                                             repr(kind) + "; allowed keys: " + list);
    }
  }
}

// The value of continuum.initial.<name>, or a refusal saying what is allowed.
const toml::value &required_initial(const Checker &c, const toml::value &v, const char *name,
                                    const std::string &what) {
  const toml::value *x = find(&v, name);
  if (x == nullptr)
    c.fail(std::string("continuum.initial.") + name,
           std::string("missing required key 'continuum.initial.") + name + "'; allowed: " + what);
  return *x;
}

void parse_initial(const Checker &c, const toml::value &v, const Range &range, Continuum &out) {
  const std::string allowed = "{ kind = \"riemann\", left, right, position } or { kind = "
                              "\"profile\" | \"cells\", values = [...] } or { kind = \"sine\", "
                              "mean, amplitude }";
  if (!v.is_table())
    c.wrong_type("continuum.initial", v, allowed);
  const toml::value *kind = find(&v, "kind");
  if (kind == nullptr)
    c.fail("continuum.initial.kind", "missing required key 'continuum.initial.kind'; allowed: "
                                     "\"riemann\", \"profile\", \"sine\", \"cells\"");
  const std::size_t k =
      choice(c, *kind, "continuum.initial.kind", {"riemann", "profile", "sine", "cells"});
  out.initial = static_cast<ContinuumInitial>(k);
  const std::vector<std::vector<std::string>> keys{{"kind", "left", "right", "position"},
                                                   {"kind", "values"},
                                                   {"kind", "mean", "amplitude"},
                                                   {"kind", "values"}};
  check_initial_keys(c, v, *kind, keys[k]);
  const auto required = [&](const char *name, const std::string &what) -> const toml::value & {
    return required_initial(c, v, name, what);
  };
  if (out.initial == ContinuumInitial::riemann) {
    out.left = density(c, required("left", range.text), "continuum.initial.left", range);
    out.right = density(c, required("right", range.text), "continuum.initial.right", range);
    out.position = out.length / 2.0;
    if (const toml::value *p = find(&v, "position")) {
      const double L = out.length;
      out.position = c.number(*p, "continuum.initial.position",
                              "a number from 0 to continuum.length (the jump)",
                              [L](double x) { return x >= 0.0 && x <= L; });
    }
  } else if (out.initial == ContinuumInitial::profile || out.initial == ContinuumInitial::cells) {
    const bool cells = out.initial == ContinuumInitial::cells;
    const std::string what = cells ? "an array of continuum.cells = " + std::to_string(out.cells) +
                                         " values (" + range.text + "), the initial cell averages"
                                   : "an array of 2 to 10000000 values (" + range.text +
                                         "), at equally spaced points from 0 to continuum.length";
    const toml::value &p = required("values", what);
    if (!p.is_array() || p.as_array().size() < 2 || p.as_array().size() > 10000000 ||
        (cells && static_cast<std::int64_t>(p.as_array().size()) != out.cells))
      c.wrong_type("continuum.initial.values", p, what);
    for (std::size_t i = 0; i < p.as_array().size(); ++i)
      out.profile.push_back(density(c, p.as_array()[i],
                                    "continuum.initial.values[" + std::to_string(i) + "]", range));
  } else {
    out.mean = density(c, required("mean", range.text), "continuum.initial.mean", range);
    const double room = std::min(out.mean - range.lo, range.hi - out.mean);
    const std::string what =
        "a number with mean +- amplitude inside the flux's range (" + range.text + ")";
    out.amplitude = c.number(required("amplitude", what), "continuum.initial.amplitude", what,
                             [room](double a) { return std::abs(a) <= room; });
  }
}

// Initial data of the jamming model: phi about a mean (sine, random) or given at the points.
void parse_jamming_initial(const Checker &c, const toml::value &v, Continuum &out) {
  const std::string allowed = "{ kind = \"sine\", mean, amplitude, mode } or { kind = "
                              "\"random\", mean, amplitude, seed } or { kind = \"eigenmode\", "
                              "mean, amplitude, modes, seed } or { kind = \"cells\", "
                              "values = [...], velocity = [...] }";
  if (!v.is_table())
    c.wrong_type("continuum.initial", v, allowed);
  const toml::value *kind = find(&v, "kind");
  if (kind == nullptr)
    c.fail("continuum.initial.kind", "missing required key 'continuum.initial.kind'; allowed "
                                     "with continuum.model = \"jamming\": \"sine\", \"random\", "
                                     "\"cells\", \"eigenmode\"");
  const std::size_t k =
      choice(c, *kind, "continuum.initial.kind", {"sine", "random", "cells", "eigenmode"});
  const ContinuumInitial kinds[] = {ContinuumInitial::sine, ContinuumInitial::random,
                                    ContinuumInitial::cells, ContinuumInitial::eigenmode};
  out.initial = kinds[k];
  const std::vector<std::vector<std::string>> keys{{"kind", "mean", "amplitude", "mode"},
                                                   {"kind", "mean", "amplitude", "seed"},
                                                   {"kind", "values", "velocity"},
                                                   {"kind", "mean", "amplitude", "modes", "seed"}};
  check_initial_keys(c, v, *kind, keys[k]);
  const auto required = [&](const char *name, const std::string &what) -> const toml::value & {
    return required_initial(c, v, name, what);
  };
  const std::string fraction = "an area fraction from 0 to 1";
  const auto in_unit = [](double x) { return x >= 0.0 && x <= 1.0; };
  if (out.initial == ContinuumInitial::cells) {
    const std::string what = "an array of continuum.cells = " + std::to_string(out.cells) +
                             " values (" + fraction + "), phi at the points x_i = i length / cells";
    const toml::value &p = required("values", what);
    if (!p.is_array() || static_cast<std::int64_t>(p.as_array().size()) != out.cells)
      c.wrong_type("continuum.initial.values", p, what);
    for (std::size_t i = 0; i < p.as_array().size(); ++i)
      out.profile.push_back(c.number(p.as_array()[i],
                                     "continuum.initial.values[" + std::to_string(i) + "]",
                                     fraction, in_unit));
    if (const toml::value *u = find(&v, "velocity")) {
      const std::string uwhat = "an array of continuum.cells = " + std::to_string(out.cells) +
                                " finite numbers, v at the points";
      if (!u->is_array() || static_cast<std::int64_t>(u->as_array().size()) != out.cells)
        c.wrong_type("continuum.initial.velocity", *u, uwhat);
      for (std::size_t i = 0; i < u->as_array().size(); ++i)
        out.velocity.push_back(c.number(u->as_array()[i],
                                        "continuum.initial.velocity[" + std::to_string(i) + "]",
                                        "a finite number", finite));
    }
    out.mean = 0.0;
    for (double x : out.profile)
      out.mean += x / static_cast<double>(out.cells);
    return;
  }
  out.mean = c.number(required("mean", fraction), "continuum.initial.mean", fraction,
                      [](double x) { return x > 0.0 && x < 1.0; });
  const double room = std::min(out.mean, 1.0 - out.mean);
  const std::int64_t top = (out.cells - 1) / 3;
  if (out.initial == ContinuumInitial::eigenmode) {
    // The modes first: the amplitude's range depends on how many there are.
    const std::string mwhat = "an array of distinct integers from 1 to " + std::to_string(top) +
                              " (continuum.cells / 3: the modes the 2/3 rule keeps)";
    if (const toml::value *x = find(&v, "modes")) {
      if (!x->is_array() || x->as_array().empty())
        c.wrong_type("continuum.initial.modes", *x, mwhat);
      for (std::size_t i = 0; i < x->as_array().size(); ++i) {
        const std::int64_t n =
            c.integer(x->as_array()[i], "continuum.initial.modes[" + std::to_string(i) + "]", mwhat,
                      [top](std::int64_t n) { return n >= 1 && n <= top; });
        if (std::find(out.modes.begin(), out.modes.end(), n) != out.modes.end())
          c.fail("continuum.initial.modes", "continuum.initial.modes[" + std::to_string(i) +
                                                "] = " + std::to_string(n) +
                                                " is given twice; allowed: " + mwhat);
        out.modes.push_back(n);
      }
    } else {
      for (std::int64_t n = 1; n <= top; ++n)
        out.modes.push_back(n);
    }
  }
  const double count =
      out.initial == ContinuumInitial::eigenmode ? static_cast<double>(out.modes.size()) : 1.0;
  const std::string what =
      out.initial == ContinuumInitial::eigenmode
          ? "a number >= 0 with mean +- (number of modes) x amplitude from 0 to 1 (" +
                std::to_string(out.modes.size()) + " modes)"
          : "a number with mean +- amplitude from 0 to 1";
  out.amplitude = c.number(required("amplitude", what), "continuum.initial.amplitude", what,
                           [room, count, this_kind = out.initial](double a) {
                             return count * std::abs(a) <= room &&
                                    (this_kind != ContinuumInitial::eigenmode || a >= 0.0);
                           });
  if (out.initial == ContinuumInitial::sine) {
    const std::string mwhat = "an integer from 1 to " + std::to_string(top) +
                              " (continuum.cells / 3: the modes the 2/3 rule keeps)";
    if (const toml::value *x = find(&v, "mode"))
      out.mode = c.integer(*x, "continuum.initial.mode", mwhat,
                           [top](std::int64_t n) { return n >= 1 && n <= top; });
  } else if (const toml::value *x = find(&v, "seed")) {
    out.seed = static_cast<std::uint64_t>(c.integer(*x, "continuum.initial.seed", "an integer >= 0",
                                                    [](std::int64_t n) { return n >= 0; }));
  }
}

// The keys only model "segregation" reads.
const std::vector<const char *> segregation_keys{"dimensions", "half_width",  "centre_speed",
                                                 "shear",      "k_c",         "k_eta",
                                                 "k_d",        "max_packing", "kind"};

// Refuses the segregation model's keys under another model (`name`, `allowed` its own keys).
void refuse_segregation_keys(const Checker &c, const toml::value *sec, const std::string &name,
                             const std::string &allowed) {
  for (const char *k : segregation_keys)
    if (find(sec, k) != nullptr)
      c.fail(std::string("continuum.") + k,
             std::string("continuum.") + k +
                 " is a key of continuum.model = \"segregation\"; allowed with \"" + name +
                 "\": " + allowed);
}

// model = "segregation": the channel, the flow, the constants of the theory and the kinds; the
// other models' keys are refused.
void parse_segregation(const Checker &c, const toml::value *sec, Continuum &out) {
  for (const char *k :
       {"flux", "rates", "parameters", "c", "c_prime", "v_cm", "reservoirs", "limiter", "mu", "vss",
        "vss_fit", "drive", "diffusion", "boundary", "length", "initial"})
    if (find(sec, k) != nullptr)
      c.fail(std::string("continuum.") + k,
             std::string("continuum.") + k +
                 " is not a key of continuum.model = \"segregation\"; allowed: dimensions, "
                 "half_width, cells, centre_speed, shear, k_c, k_eta, k_d, max_packing, kind, "
                 "time, samples, cfl, max_work");
  const auto required = [&](const char *name, const std::string &what) -> const toml::value & {
    return required_key(c, sec, name, what);
  };
  Segregation &s = out.segregation;
  if (const toml::value *v = find(sec, "dimensions"))
    s.dimensions = static_cast<int>(c.integer(*v, "continuum.dimensions", "2 or 3",
                                              [](std::int64_t d) { return d == 2 || d == 3; }));
  s.max_packing = s.dimensions == 2 ? 0.82 : 0.64;
  s.k_d = s.dimensions == 2 ? 7.46 : 0.61;
  const std::string w_allowed = "a number > 0 (walls at y = -half_width and +half_width)";
  s.half_width = c.number(required("half_width", w_allowed), "continuum.half_width", w_allowed,
                          [](double x) { return x > 0.0; });
  out.length = 2.0 * s.half_width;
  const std::string cells_allowed = "an even integer from 4 to 1000000 (cells across the channel)";
  out.cells = c.integer(required("cells", cells_allowed), "continuum.cells", cells_allowed,
                        [](std::int64_t n) { return n >= 4 && n <= 1000000 && n % 2 == 0; });
  const std::string v_allowed = "a number >= 0 (centre speed v0 of the Poiseuille flow)";
  s.centre_speed = c.number(required("centre_speed", v_allowed), "continuum.centre_speed",
                            v_allowed, [](double x) { return x >= 0.0; });
  if (const toml::value *v = find(sec, "shear"))
    s.shear = choice(c, *v, "continuum.shear", {"poiseuille", "viscous"}) == 0
                  ? SegregationShear::poiseuille
                  : SegregationShear::viscous;
  const auto positive = [](double x) { return x > 0.0; };
  if (const toml::value *v = find(sec, "k_c"))
    s.k_c = c.number(*v, "continuum.k_c", "a number > 0 (K_c of eq 5.3)", positive);
  if (const toml::value *v = find(sec, "k_eta"))
    s.k_eta = c.number(*v, "continuum.k_eta", "a number >= 0 (K_eta of eq 5.3)",
                       [](double x) { return x >= 0.0; });
  if (const toml::value *v = find(sec, "k_d"))
    s.k_d = c.number(*v, "continuum.k_d", "a number > 0 (K_d of eq 5.23)", positive);
  if (const toml::value *v = find(sec, "max_packing"))
    s.max_packing = c.number(*v, "continuum.max_packing", "a number > 0 and < 1 (phi_M of eq 5.29)",
                             [](double x) { return x > 0.0 && x < 1.0; });
  const std::string kinds_allowed =
      "one or two tables [[continuum.kind]] with radius, fraction, diffusivity";
  const toml::value &kinds = required("kind", kinds_allowed);
  if (!kinds.is_array() || kinds.as_array().empty() || kinds.as_array().size() > 2)
    c.wrong_type("continuum.kind", kinds, kinds_allowed);
  const auto &kind_keys = sub_keys("continuum", "kind");
  double total = 0.0;
  for (std::size_t i = 0; i < kinds.as_array().size(); ++i) {
    const toml::value &k = kinds.as_array()[i];
    const std::string key = "continuum.kind[" + std::to_string(i) + "]";
    if (!k.is_table())
      c.wrong_type(key, k, "a table with radius, fraction, diffusivity");
    for (const auto &[name, x] : sorted(k)) {
      (void)x;
      if (find_key(kind_keys, name) == nullptr)
        c.fail(key + "." + name, "unknown key '" + key + "." + name +
                                     "'; allowed keys: " + join(names_of(kind_keys)));
    }
    const auto field = [&](const char *name, const std::string &what) -> const toml::value & {
      const toml::value *x = find(&k, name);
      if (x == nullptr)
        c.fail(key + "." + name,
               "missing required key '" + key + "." + name + "'; allowed: " + what);
      return *x;
    };
    SegregationKind kind;
    const double w = s.half_width;
    const std::string r_allowed = "a number > 0 and < continuum.half_width (the colloid radius)";
    kind.radius = c.number(field("radius", r_allowed), key + ".radius", r_allowed,
                           [w](double x) { return x > 0.0 && x < w; });
    const std::string f_allowed = "a number > 0 (mean area/volume fraction; all kinds together "
                                  "below max_packing = " +
                                  repr(toml::value(s.max_packing)) + ")";
    kind.fraction = c.number(field("fraction", f_allowed), key + ".fraction", f_allowed,
                             [&](double x) { return x > 0.0 && total + x < s.max_packing; });
    total += kind.fraction;
    const std::string d_allowed = "a number > 0 (single-colloid diffusivity D_0)";
    kind.diffusivity =
        c.number(field("diffusivity", d_allowed), key + ".diffusivity", d_allowed, positive);
    s.kinds.push_back(kind);
  }
}

// model = "jamming": its own keys, and a refusal of the conservation law's.
void parse_jamming(const Checker &c, const toml::value *sec, Continuum &out) {
  for (const char *k :
       {"flux", "rates", "parameters", "c", "c_prime", "v_cm", "reservoirs", "limiter"})
    if (find(sec, k) != nullptr)
      c.fail(std::string("continuum.") + k,
             std::string("continuum.") + k +
                 " is a key of continuum.model = \"conservation-law\"; allowed with "
                 "\"jamming\": mu or vss or vss_fit, drive, diffusion, length, cells, boundary, "
                 "initial, time, "
                 "samples, cfl, max_work");
  const auto required = [&](const char *name, const std::string &what) -> const toml::value & {
    return required_key(c, sec, name, what);
  };
  parse_jamming_vss(c, sec, out);
  if (const toml::value *v = find(sec, "drive"))
    out.drive = c.number(*v, "continuum.drive", "a number > 0 (sigma of eq 6.3)",
                         [](double x) { return x > 0.0; });
  out.cfl = 0.1; // the splitting error of growth rates: 0.9 % at 0.1, 6 % at 0.4
  out.diffusion = 1.0;
  if (const toml::value *v = find(sec, "diffusion"))
    out.diffusion = c.number(*v, "continuum.diffusion", "a number > 0 (D of eq 6.2)",
                             [](double x) { return x > 0.0; });
  out.boundary = ContinuumBoundary::periodic;
  if (const toml::value *v = find(sec, "boundary"))
    choice(c, *v, "continuum.boundary", {"periodic"});
  const std::string len_allowed = "a number > 0 (the periodic domain [0, length))";
  out.length = c.number(required("length", len_allowed), "continuum.length", len_allowed,
                        [](double x) { return x > 0.0; });
  const std::string cells_allowed = "an even integer from 8 to 16777216 (grid points)";
  out.cells = c.integer(required("cells", cells_allowed), "continuum.cells", cells_allowed,
                        [](std::int64_t n) { return n >= 8 && n <= 16777216 && n % 2 == 0; });
  check_spacing(c, out);
  parse_jamming_initial(c,
                        required("initial", "{ kind = \"sine\", mean, amplitude, mode }, { kind "
                                            "= \"random\", mean, amplitude, seed }, { kind = "
                                            "\"cells\", values, velocity }"),
                        out);
}

} // namespace

namespace {
void parse_conservation_law(const Checker &c, const toml::value *sec, Continuum &out);
} // namespace

Continuum parse_continuum(const toml::value *sec, const Checker &c) {
  if (sec == nullptr)
    c.fail("continuum", "missing required section [continuum] (run.engine = \"continuum\"); "
                        "required keys: model, flux, length, cells, initial, time");
  Continuum out;
  const auto required = [&](const char *name, const std::string &what) -> const toml::value & {
    return required_key(c, sec, name, what);
  };
  out.model = static_cast<ContinuumModel>(
      choice(c, required("model", "\"conservation-law\", \"jamming\", \"segregation\""),
             "continuum.model", {"conservation-law", "jamming", "segregation"}));
  if (out.model == ContinuumModel::jamming) {
    refuse_segregation_keys(c, sec, "jamming",
                            "mu or vss or vss_fit, drive, diffusion, length, cells, boundary, "
                            "initial, time, "
                            "samples, cfl, max_work");
    parse_jamming(c, sec, out);
  } else if (out.model == ContinuumModel::segregation) {
    parse_segregation(c, sec, out);
  } else {
    refuse_segregation_keys(c, sec, "conservation-law",
                            "flux and its parameters, length, cells, diffusion, boundary, "
                            "reservoirs, initial, time, samples, cfl, max_work, limiter");
    for (const char *k : {"mu", "vss", "vss_fit", "drive"})
      if (find(sec, k) != nullptr)
        c.fail(std::string("continuum.") + k,
               std::string("continuum.") + k +
                   " is a key of continuum.model = \"jamming\"; allowed with "
                   "\"conservation-law\": none");
  }
  if (out.model == ContinuumModel::conservation_law)
    parse_conservation_law(c, sec, out);
  const std::string time_allowed = "a number > 0 (simulated time)";
  out.time = c.number(required("time", time_allowed), "continuum.time", time_allowed,
                      [](double x) { return x > 0.0; });
  if (const toml::value *v = find(sec, "samples"))
    out.samples = c.integer(*v, "continuum.samples",
                            "an integer from 1 to 100000 (samples over continuum.time)",
                            [](std::int64_t n) { return n >= 1 && n <= 100000; });
  if (const toml::value *v = find(sec, "cfl"))
    out.cfl = c.number(*v, "continuum.cfl", "a number > 0 and <= 0.5 (Courant number)",
                       [](double x) { return x > 0.0 && x <= 0.5; });
  if (const toml::value *v = find(sec, "max_work"))
    out.max_work =
        c.number(*v, "continuum.max_work", "a number > 0 (grid-point steps a run may take)",
                 [](double x) { return x > 0.0; });
  return out;
}

namespace {

// model = "conservation-law": flux and its parameters, grid, boundary, initial data, limiter.
void parse_conservation_law(const Checker &c, const toml::value *sec, Continuum &out) {
  const auto required = [&](const char *name, const std::string &what) -> const toml::value & {
    return required_key(c, sec, name, what);
  };
  const std::vector<std::string> fluxes{"burgers", "tasep", "family1", "family2", "colloid-chain"};
  out.flux = static_cast<ContinuumFlux>(
      choice(c, required("flux", choice_list(fluxes)), "continuum.flux", fluxes));

  const bool lattice_gas = out.flux == ContinuumFlux::tasep || out.flux == ContinuumFlux::family1 ||
                           out.flux == ContinuumFlux::family2;
  if (lattice_gas)
    parse_lattice_gas(c, sec, out);
  else
    for (const char *k : {"rates", "parameters"})
      if (find(sec, k) != nullptr)
        c.fail(std::string("continuum.") + k,
               std::string("continuum.") + k +
                   " sets the rates of a lattice-gas flux; allowed with continuum.flux = \"" +
                   fluxes[static_cast<std::size_t>(out.flux)] + "\": none");
  for (const auto &[name, field] :
       {std::pair{"c", &out.c}, std::pair{"c_prime", &out.c_prime}, std::pair{"v_cm", &out.v_cm}})
    if (const toml::value *v = find(sec, name)) {
      if (out.flux != ContinuumFlux::colloid_chain)
        c.fail(std::string("continuum.") + name, std::string("continuum.") + name +
                                                     " is a parameter of the colloid-chain flux "
                                                     "(Tabatabaei (2008) eq 5.3); allowed with "
                                                     "continuum.flux = \"" +
                                                     fluxes[static_cast<std::size_t>(out.flux)] +
                                                     "\": none");
      *field = c.number(*v, std::string("continuum.") + name, "a finite number", finite);
    }

  const std::string len_allowed = "a number > 0 (the domain [0, length])";
  out.length = c.number(required("length", len_allowed), "continuum.length", len_allowed,
                        [](double x) { return x > 0.0; });
  const std::string cells_allowed = "an integer from 4 to 100000000";
  out.cells = c.integer(required("cells", cells_allowed), "continuum.cells", cells_allowed,
                        [](std::int64_t n) { return n >= 4 && n <= 100000000; });
  check_spacing(c, out);
  if (const toml::value *v = find(sec, "diffusion"))
    out.diffusion = c.number(*v, "continuum.diffusion", "a number >= 0 (D of D rho_xx)",
                             [](double x) { return x >= 0.0; });
  if (const toml::value *v = find(sec, "boundary"))
    out.boundary = choice(c, *v, "continuum.boundary", {"open", "periodic"}) == 0
                       ? ContinuumBoundary::open
                       : ContinuumBoundary::periodic;

  const Range range = density_range(out.flux);
  parse_initial(c,
                required("initial", "{ kind = \"riemann\", left, right, position }, { kind "
                                    "= \"profile\", values }, { kind = \"sine\", mean, "
                                    "amplitude }"),
                range, out);
  // Reservoirs default to the initial data at the two ends.
  if (out.initial == ContinuumInitial::riemann)
    out.reservoirs = {out.left, out.right};
  else if (out.initial == ContinuumInitial::profile || out.initial == ContinuumInitial::cells)
    out.reservoirs = {out.profile.front(), out.profile.back()};
  else
    out.reservoirs = {out.mean, out.mean};
  if (const toml::value *v = find(sec, "reservoirs")) {
    const std::string allowed = "an array [left, right] of two densities (" + range.text + ")";
    if (out.boundary != ContinuumBoundary::open)
      c.fail("continuum.reservoirs", "continuum.reservoirs needs continuum.boundary = \"open\"; "
                                     "allowed when periodic: none");
    if (!v->is_array() || v->as_array().size() != 2)
      c.wrong_type("continuum.reservoirs", *v, allowed);
    for (int i = 0; i < 2; ++i)
      out.reservoirs[i] =
          density(c, v->as_array()[i], "continuum.reservoirs[" + std::to_string(i) + "]", range);
  }

  if (const toml::value *v = find(sec, "limiter"))
    out.limiter = choice(c, *v, "continuum.limiter", {"mc", "minmod"}) == 0
                      ? ContinuumLimiter::mc
                      : ContinuumLimiter::minmod;
}

} // namespace

void parse_continuum_scene(const Checker &c, const toml::value &root, Scene &s) {
  const toml::value *sec = c.section(root, "continuum");
  c.check_keys(sec, "continuum");
  s.continuum = parse_continuum(sec, c);
}

void check_continuum_observables(const Checker &c, const Scene &s) {
  // Each model writes the observables it writes by default and those it writes on request
  // (scene/schema.hpp), no others.
  std::vector<std::string> mine;
  std::string list;
  for (const auto &o : engine_schema(Engine::continuum).observables)
    if ((o.by_default != nullptr && o.by_default(s)) ||
        (o.on_request != nullptr && o.on_request(s))) {
      mine.emplace_back(o.name);
      list += (list.empty() ? "\"" : ", \"") + std::string(o.name) + "\"";
    }
  const char *const models[] = {"conservation-law", "jamming", "segregation"};
  const auto model = static_cast<std::size_t>(s.continuum->model);
  for (const auto &name : s.output.observables)
    if (std::find(mine.begin(), mine.end(), name) == mine.end())
      c.fail("output.observables", "output.observables lists \"" + name +
                                       "\", which continuum.model = \"" + models[model] +
                                       "\" does not write; allowed: " + list);
}

} // namespace narrows::scene::detail
