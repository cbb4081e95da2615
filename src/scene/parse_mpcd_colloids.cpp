// Validation of [colloids] (engine "mpcd"): one kind or several ([[colloids.kind]]), the
// coupling to the fluid and the contacts ([colloids.spring]), the placement (lattice, random,
// a list, a file, a grown packing) and the statistics; and the conditions no-slip colloids put
// on the rest of the scene.
#include "parse_mpcd.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace narrows::scene::detail {

using toml::value;

namespace {

// [[colloids.kind]]: an array of tables {radius, count, mass}. The one-kind keys radius,
// radius_sd, mass and count cannot be given beside it.
std::vector<ColloidKind> parse_colloid_kinds(const Checker &c, const value *sec,
                                             const value &kinds) {
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
    const auto &kind_keys = sub_keys("colloids", "kind");
    for (const auto &[k, v] : in_file_order(a[i])) {
      (void)v;
      if (find_key(kind_keys, k) == nullptr)
        c.fail(key + "." + k,
               "unknown key '" + key + "." + k +
                   "'; allowed keys in [[colloids.kind]]: " + join(names_of(kind_keys)));
    }
    ColloidKind kind;
    if (const value *v = find(&a[i], "radius"))
      kind.radius = c.number(*v, key + ".radius", "a number > 0 (cell units)", positive);
    else
      c.missing(key + ".radius", "a number > 0 (cell units)");
    if (const value *v = find(&a[i], "count"))
      kind.count = c.integer(*v, key + ".count", "an integer from 1 to 1000000",
                             [](std::int64_t n) { return n >= 1 && n <= 1000000; });
    else
      c.missing(key + ".count", "an integer from 1 to 1000000");
    if (const value *v = find(&a[i], "mass"))
      kind.mass =
          c.number(*v, key + ".mass",
                   "a number > 0 (default: fluid mass density times the colloid volume)", positive);
    out.push_back(kind);
  }
  return out;
}

// [colloids.spring]: kn, kt, mu_cc, mu_cw (a number >= 0 or inf) and substeps.
ColloidSprings parse_colloid_springs(const Checker &c, const value &sec) {
  if (!sec.is_table())
    c.wrong_type("colloids.spring", sec, "a table [colloids.spring]");
  const auto &spring_keys = sub_keys("colloids", "spring");
  for (const auto &[k, v] : in_file_order(sec)) {
    (void)v;
    if (find_key(spring_keys, k) == nullptr)
      c.fail("colloids.spring." + k,
             "unknown key 'colloids.spring." + k +
                 "'; allowed keys in [colloids.spring]: " + join(names_of(spring_keys)));
  }
  ColloidSprings out;
  if (const value *v = find(&sec, "kn"))
    out.kn = c.number(*v, "colloids.spring.kn", "a number > 0 (kT / a^2)",
                      [](double x) { return x > 0.0; });
  if (const value *v = find(&sec, "kt"))
    out.kt = c.number(*v, "colloids.spring.kt", "a number >= 0 (kT / a^2)",
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
    x = c.number(*v, key, allowed, [](double y) { return y >= 0.0; });
  };
  mu("mu_cc", out.mu_cc);
  mu("mu_cw", out.mu_cw);
  if (const value *v = find(&sec, "substeps"))
    out.substeps =
        static_cast<int>(c.integer(*v, "colloids.spring.substeps", "an integer from 1 to 10000",
                                   [](std::int64_t n) { return n >= 1 && n <= 10000; }));
  return out;
}

// The keys of the colloid statistics (observables colloid_vacf ... density_kde).
void parse_colloid_statistics(const Checker &c, const value *sec, Colloids &out) {
  if (const value *v = find(sec, "correlation_every"))
    out.correlation_every =
        c.integer(*v, "colloids.correlation_every", "an integer from 1 to 1000000 (steps)",
                  [](std::int64_t n) { return n >= 1 && n <= 1000000; });
  const std::int64_t every = out.correlation_every;
  if (const value *v = find(sec, "max_lag"))
    out.max_lag = c.integer(
        *v, "colloids.max_lag",
        "a multiple of colloids.correlation_every = " + std::to_string(every) +
            ", at most 100000 times it (steps)",
        [every](std::int64_t n) { return n >= 0 && n % every == 0 && n / every <= 100000; });
  else if (out.max_lag % every != 0)
    c.fail("colloids.max_lag", "colloids.max_lag defaults to 1000, not a multiple of "
                               "colloids.correlation_every = " +
                                   std::to_string(every) +
                                   "; allowed: an explicit max_lag, a multiple of it");
  if (const value *v = find(sec, "kde_width"))
    out.kde_width = c.number(*v, "colloids.kde_width", "a number > 0 (cell units)",
                             [](double x) { return x > 0.0; });
  if (const value *v = find(sec, "statistics_from"))
    out.statistics_from = c.integer(*v, "colloids.statistics_from", "an integer >= 0 (step)",
                                    [](std::int64_t n) { return n >= 0; });
}

// The densest fraction placement = "packing" takes: random close packing of bidisperse disks
// (about 0.84) and of spheres (about 0.64); beyond it the overlaps cannot go.
double packing_limit(int dims) { return dims == 2 ? 0.84 : 0.64; }

std::string packing_allowed(int dims) {
  return "a number > 0 and at most " + float_text(packing_limit(dims)) +
         " (random close packing of " + (dims == 2 ? "disks" : "spheres") + ")";
}

const value *fraction_or_missing(const Checker &c, const value *fraction, int dims) {
  if (fraction == nullptr)
    c.missing("colloids.packing_fraction", packing_allowed(dims));
  return fraction;
}

// placement = "packing": the target fraction, and the counts that realise it: one kind
// round(phi V / v); several kinds their counts (the number ratio) times one factor, each rounded.
void parse_packing(const Checker &c, const value *sec, const value &fraction, const Domain &domain,
                   int dims, bool walls, bool no_slip, Colloids &out) {
  if (!no_slip)
    c.fail("colloids.placement", "colloids.placement = \"packing\" grows the colloids with the "
                                 "spring contacts of no-slip colloids; allowed with coupling = "
                                 "\"no-slip\"");
  out.packing_fraction = c.number(fraction, "colloids.packing_fraction", packing_allowed(dims),
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
  if (const value *v = find(sec, "packing_max_work"))
    out.packing_max_work = c.number(*v, "colloids.packing_max_work",
                                    "a number > 0 (colloid-steps the packing may take)",
                                    [](double x) { return x > 0.0; });
  bool none = out.count < 1;
  for (const auto &k : out.kinds)
    none = none || k.count < 1;
  if (none || out.count > 1000000)
    c.fail("colloids.packing_fraction",
           "colloids.packing_fraction = " + repr(fraction) + " makes " + std::to_string(out.count) +
               " colloids" + (none ? " (a kind with none)" : "") +
               " in this box; allowed: 1 to 1000000 colloids, at least one of each kind");
}

} // namespace

std::optional<Colloids> parse_colloids(const Checker &c, const value *sec, const Domain &domain,
                                       int dims, bool walls) {
  if (sec == nullptr)
    return std::nullopt;
  c.check_keys(sec, "colloids");
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
    out.radius = c.number(*v, "colloids.radius", "a number > 0 (cell units)", positive);
  } else {
    c.missing("colloids.radius", "a number > 0 (cell units; Tabatabaei (2008) uses 2)");
  }
  const double r = out.radius;
  if (const value *v = find(sec, "radius_sd"))
    // Radii are drawn within +-3 sd of the mean: at most 0.2 r keeps every one >= 0.4 r.
    out.radius_sd =
        c.number(*v, "colloids.radius_sd",
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
        c.choice(*v, "colloids.coupling", "a known coupling", {"md", "no-slip"}));
  const bool no_slip = out.coupling == ColloidCoupling::no_slip;
  if (const value *v = find(sec, "contacts")) {
    out.contacts = static_cast<ColloidContacts>(
        c.choice(*v, "colloids.contacts", "a known contact model", {"none", "hard", "spring"}));
    if (out.contacts != ColloidContacts::none && !no_slip)
      c.fail("colloids.contacts",
             "colloids.contacts = " + repr(*v) +
                 " resolves contacts of no-slip colloids; allowed with coupling = \"md\": "
                 "\"none\" (the 48-24 potential keeps MD colloids apart)");
  }
  if (const value *v = find(sec, "exchange")) {
    out.exchange_implicit = c.choice(*v, "colloids.exchange", "a known impulse exchange",
                                     {"implicit", "explicit"}) == 0;
    if (!no_slip)
      c.fail("colloids.exchange", "colloids.exchange = " + repr(*v) +
                                      " sets how no-slip colloids take the fluid's impulses; "
                                      "allowed only with coupling = \"no-slip\"");
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
        c.number(*v, "colloids.mass",
                 "a number > 0 (default: fluid mass density times the colloid volume)", positive);
  if (const value *v = find(sec, "epsilon"))
    out.epsilon = c.number(*v, "colloids.epsilon", "a number > 0 (kT units)", positive);
  if (const value *v = find(sec, "wall_q"))
    out.wall_q = c.number(*v, "colloids.wall_q", "a number > 0", positive);
  if (const value *v = find(sec, "md_substeps"))
    out.md_substeps =
        static_cast<int>(c.integer(*v, "colloids.md_substeps", "an integer from 1 to 10000",
                                   [](std::int64_t n) { return n >= 1 && n <= 10000; }));
  if (const value *v = find(sec, "gravity"))
    out.gravity = c.vector(*v, "colloids.gravity", dims,
                           "the gravitational acceleration g (force: mass times g)");
  const double half_width = domain.size[1] / 2.0;
  if (const value *v = find(sec, "wall_sigma")) {
    if (!walls)
      c.fail("colloids.wall_sigma", "colloids.wall_sigma = " + repr(*v) +
                                        " sets the colloid-wall potential; allowed only with "
                                        "[walls]");
    out.wall_sigma =
        c.number(*v, "colloids.wall_sigma",
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
    const std::size_t i = c.choice(*placement, "colloids.placement", "a known placement",
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
  if (const value *v = find(sec, "packing_max_work"); v != nullptr && !packing)
    c.fail("colloids.packing_max_work",
           "colloids.packing_max_work = " + repr(*v) +
               " bounds the work of placement = \"packing\"; allowed only with it");
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
      const std::string name = c.string(*positions_file, "colloids.positions_file", allowed);
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
        const auto p = c.vector(a[i], key, dims, "a position inside the box");
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
      out.count = c.integer(*count, "colloids.count", "an integer from 1 to 1000000",
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
void check_no_slip(const Checker &c, const Scene &s) {
  const auto &col = *s.colloids;
  const auto rule = s.fluid.collision;
  if (rule != Collision::srd && rule != Collision::at && rule != Collision::at_a)
    c.fail("colloids.coupling", std::string("colloids.coupling = \"no-slip\" with "
                                            "fluid.collision = \"") +
                                    to_string(rule) +
                                    "\"; allowed with srd, at or at+a (the ghost particles "
                                    "inside the colloids take part in the cell collision)");
  if (s.fluid.density > 250.0) // docs/scenes.md: fluid.density <= 250 (ghost particles per cell)
    c.fail("fluid.density",
           "fluid.density = " + float_text(s.fluid.density) +
               " with colloids.coupling = \"no-slip\"; allowed: a density up to 250 (the ghost "
               "particles per cell of the colloids)");
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
    if (omega_h > 0.25) {
      // The sub-steps that would do, as a number (no integer cast: kn = 1e300 needs ~1e149);
      // beyond the key's range of 10000 only softer springs (or a smaller fluid.dt) help.
      const double needed = std::ceil(k.substeps * omega_h / 0.25);
      const std::string key =
          k.kn >= (d == 2 ? 3.0 : 3.5) * k.kt ? "colloids.spring.kn" : "colloids.spring.kt";
      const double h_min = s.fluid.dt / 10000.0; // the smallest sub-step
      const double k_max = 0.5 * m_min * (0.25 / h_min) * (0.25 / h_min);
      char k_text[32];
      std::snprintf(k_text, sizeof k_text, "%.3g", k_max);
      if (!(needed <= 10000.0))
        c.fail(key, key + " = " + float_text(key == "colloids.spring.kn" ? k.kn : k.kt) +
                        ": the stiffest contact of the lightest colloids (M " + float_text(m_min) +
                        ") oscillates " + float_text(omega_h) +
                        " radians per sub-step at colloids.spring.substeps = " +
                        std::to_string(k.substeps) + "; allowed: at most 0.25, which needs " +
                        float_text(needed) +
                        " sub-steps, above the largest, 10000: softer springs (stiffness "
                        "max(kn, " +
                        (d == 2 ? "3" : "3.5") + " kt) <= " + k_text + ") or a smaller fluid.dt");
      c.fail("colloids.spring.substeps",
             "colloids.spring.substeps = " + std::to_string(k.substeps) +
                 ": the stiffest contact of the lightest colloids (M " + float_text(m_min) +
                 ") oscillates " + float_text(omega_h) +
                 " radians per sub-step; allowed: at most 0.25, i.e. substeps >= " +
                 std::to_string(static_cast<int>(needed)) + ", or softer springs");
    }
  }
  if (col.contacts == ColloidContacts::none && (s.walls || col.count > 1))
    c.fail("colloids.contacts",
           std::string("colloids.contacts = \"none\" with no-slip colloids and ") +
               (s.walls ? "[walls]" : "colloids.count = " + std::to_string(col.count)) +
               ": they could overlap each other or a wall; allowed: contacts = \"hard\" or "
               "\"spring\", or "
               "one colloid in a periodic box");
}

} // namespace narrows::scene::detail
