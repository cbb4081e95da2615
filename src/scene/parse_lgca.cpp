// Validation of the [lattice] and [tagged] sections: model, size, density, initial state,
// walls, body force, obstacles, field blocks, VACF lags; and [colloid]. Unknown keys of the
// sections themselves are refused by the schema check (Checker::check_keys).
#include "parse_lgca.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace narrows::scene::detail {

namespace {

constexpr std::int64_t max_sites_per_axis = std::int64_t{1} << 20;

const char *const model_names[] = {"fhp-i", "fhp-ii", "fhp-iii", "fhp-saturated", "dhumieres-1d"};

std::string model_list() {
  std::string s;
  for (const char *n : model_names)
    s += std::string(s.empty() ? "" : ", ") + "\"" + n + "\"";
  return s;
}

void parse_obstacles(const Checker &c, const toml::value &v, Lgca &out) {
  const std::string allowed =
      "an array of discs [x, y, radius] in lattice coordinates (row y at y sqrt(3)/2), "
      "radius > 0";
  if (!v.is_array())
    c.wrong_type("lattice.obstacles", v, allowed);
  const auto &a = v.as_array();
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string key = "lattice.obstacles[" + std::to_string(i) + "]";
    if (!a[i].is_array() || a[i].as_array().size() != 3)
      c.wrong_type(key, a[i], allowed);
    const auto &d = a[i].as_array();
    LgcaObstacle ob;
    ob.x = c.number(d[0], key + "[0]", allowed, [](double) { return true; });
    ob.y = c.number(d[1], key + "[1]", allowed, [](double) { return true; });
    ob.radius = c.number(d[2], key + "[2]", allowed, [](double r) { return r > 0.0; });
    out.obstacles.push_back(ob);
  }
}

} // namespace

Lgca parse_lgca(const toml::value *sec, const Checker &c) {
  Lgca out;
  const toml::value *model = find(sec, "model");
  if (model == nullptr)
    c.fail("lattice.model", "missing required key 'lattice.model'; allowed: " + model_list());
  if (!model->is_string())
    c.wrong_type("lattice.model", *model, model_list());
  {
    const std::string m = model->as_string().str;
    bool known = false;
    for (int i = 0; i < 5; ++i)
      if (m == model_names[i]) {
        out.model = static_cast<LgcaModel>(i);
        known = true;
      }
    if (!known)
      c.fail("lattice.model",
             "lattice.model = " + repr(*model) + " is not known; allowed: " + model_list());
  }
  const bool one_d = out.model == LgcaModel::dhumieres_1d;

  const std::string size_allowed =
      one_d ? "an array [L] of one integer from 3 to " + std::to_string(max_sites_per_axis)
            : "an array [size_x, size_y] of integers from 2 to " +
                  std::to_string(max_sites_per_axis) + ", size_y even";
  const toml::value *size = find(sec, "size");
  if (size == nullptr)
    c.fail("lattice.size", "missing required key 'lattice.size'; allowed: " + size_allowed);
  if (!size->is_array() || size->as_array().size() != (one_d ? 1u : 2u))
    c.wrong_type("lattice.size", *size, size_allowed);
  for (std::size_t k = 0; k < size->as_array().size(); ++k)
    out.size.push_back(c.integer(size->as_array()[k], "lattice.size[" + std::to_string(k) + "]",
                                 size_allowed, [k, one_d](std::int64_t n) {
                                   return n >= (one_d ? 3 : 2) && n <= max_sites_per_axis &&
                                          (one_d || k == 0 || n % 2 == 0);
                                 }));

  const std::string density_allowed = "a number with 0 < density < 1 (mean occupation per link)";
  if (const toml::value *v = find(sec, "density"))
    out.density = c.number(*v, "lattice.density", density_allowed,
                           [](double d) { return d > 0.0 && d < 1.0; });
  else
    c.fail("lattice.density",
           "missing required key 'lattice.density'; allowed: " + density_allowed);
  {
    // Observables divide by the particle count: a lattice expected to hold less than one
    // particle measures nothing (all-NaN results).
    double links = out.model == LgcaModel::fhp_ii || out.model == LgcaModel::fhp_iii ? 7 : 6;
    if (one_d)
      links = 5; // lattice/dhumieres_1d.hpp
    for (const auto n : out.size)
      links *= static_cast<double>(n);
    if (links * out.density < 1.0) {
      char line[300];
      std::snprintf(line, sizeof line,
                    "lattice.density = %g gives %.3g particles expected on %.0f links; allowed: "
                    "a density giving at least one particle (>= %.3g)",
                    out.density, links * out.density, links, 1.0 / links);
      c.fail("lattice.density", line);
    }
  }

  if (const toml::value *v = find(sec, "initial")) {
    const std::string allowed =
        one_d ? "\"equilibrium\" or \"zero-momentum\"" : "\"equilibrium\" or \"shear-wave\"";
    if (!v->is_string())
      c.wrong_type("lattice.initial", *v, allowed);
    const std::string s = v->as_string().str;
    if (s == "equilibrium")
      out.initial = LgcaInitial::equilibrium;
    else if (s == "shear-wave" && !one_d)
      out.initial = LgcaInitial::shear_wave;
    else if (s == "zero-momentum" && one_d)
      out.initial = LgcaInitial::zero_momentum;
    else
      c.fail("lattice.initial", "lattice.initial = " + repr(*v) + " is not known" +
                                    (one_d ? " for the 1D model" : "") + "; allowed: " + allowed);
  }
  if (const toml::value *v = find(sec, "amplitude")) {
    // Occupations d + (rho/3) c_i.u must stay in [0, 1]: |u| <= min(d, 1 - d) 3 / rho.
    const double b = out.model == LgcaModel::fhp_ii || out.model == LgcaModel::fhp_iii ? 7 : 6;
    const double most = std::min(out.density, 1.0 - out.density) * 3.0 / (b * out.density);
    out.amplitude = c.number(*v, "lattice.amplitude",
                             "a number with 0 <= amplitude <= " + float_text(most) +
                                 " (occupations stay in [0, 1] at this density)",
                             [most](double a) { return a >= 0.0 && a <= most; });
    if (out.initial != LgcaInitial::shear_wave && out.amplitude != 0.0)
      c.fail("lattice.amplitude", "lattice.amplitude = " + repr(*v) +
                                      " needs lattice.initial = \"shear-wave\"; allowed: 0 with "
                                      "an equilibrium start");
  } else if (out.initial == LgcaInitial::shear_wave) {
    out.amplitude = 0.05;
  }
  if (const toml::value *v = find(sec, "walls")) {
    if (!v->is_boolean())
      c.wrong_type("lattice.walls", *v, "true or false (solid rows y = 0 and y = size_y - 1)");
    out.walls = v->as_boolean();
  }
  if (const toml::value *v = find(sec, "body_force"))
    out.body_force = c.number(
        *v, "lattice.body_force",
        "a probability from 0 to 1 per site and step of moving a particle from link 3 (-x) to "
        "link 0 (+x)",
        [](double p) { return p >= 0.0 && p <= 1.0; });
  if (const toml::value *v = find(sec, "obstacles"))
    parse_obstacles(c, *v, out);
  if (one_d && (out.walls || out.body_force > 0.0 || !out.obstacles.empty()))
    c.fail(out.walls              ? "lattice.walls"
           : out.body_force > 0.0 ? "lattice.body_force"
                                  : "lattice.obstacles",
           "walls, body_force and obstacles are for the FHP models; allowed with model "
           "\"dhumieres-1d\": model, size, density, initial");
  if (!one_d) {
    const std::int64_t X = out.size[0], Y = out.size[1];
    const std::string allowed = "an integer >= 1 dividing both lattice sizes (" +
                                std::to_string(X) + ", " + std::to_string(Y) + ")";
    if (const toml::value *v = find(sec, "block"))
      out.block = c.integer(*v, "lattice.block", allowed,
                            [X, Y](std::int64_t n) { return n >= 1 && X % n == 0 && Y % n == 0; });
    else
      for (std::int64_t b : {8, 4, 2, 1})
        if (X % b == 0 && Y % b == 0) {
          out.block = b;
          break;
        }
  } else if (find(sec, "block") != nullptr) {
    c.fail("lattice.block", "lattice.block is for the FHP models; allowed with model "
                            "\"dhumieres-1d\": model, size, density, initial");
  }
  return out;
}

Tagged parse_tagged(const toml::value &sec, const Lgca &lattice, const Checker &c) {
  Tagged out;
  const std::string allowed = "an integer from 1 to 1000000 (VACF lags 0..max_lag)";
  if (const toml::value *v = find(&sec, "max_lag"))
    out.max_lag = c.integer(*v, "tagged.max_lag", allowed,
                            [](std::int64_t n) { return n >= 1 && n <= 1000000; });
  else
    c.fail("tagged.max_lag", "missing required key 'tagged.max_lag'; allowed: " + allowed);
  if (const toml::value *v = find(&sec, "replicas")) {
    const bool one_d = lattice.model == LgcaModel::dhumieres_1d;
    const std::string r_allowed = one_d ? "an integer from 1 to 10000 (independent runs)"
                                        : "only with lattice.model = \"dhumieres-1d\"";
    out.replicas = c.integer(*v, "tagged.replicas", r_allowed,
                             [one_d](std::int64_t n) { return one_d && n >= 1 && n <= 10000; });
  }
  return out;
}

LgcaColloid parse_colloid(const toml::value &sec, const Lgca &lattice, const Checker &c) {
  LgcaColloid out;
  if (lattice.model == LgcaModel::dhumieres_1d)
    c.fail("colloid", "section [colloid] is for the FHP models; allowed with model "
                      "\"dhumieres-1d\": [lattice], [tagged]");
  const auto pair = [&](const char *key, double &a, double &b, const std::string &allowed) {
    const toml::value *v = find(&sec, key);
    if (v == nullptr)
      return false;
    const std::string k = std::string("colloid.") + key;
    if (!v->is_array() || v->as_array().size() != 2)
      c.wrong_type(k, *v, allowed);
    a = c.number(v->as_array()[0], k + "[0]", allowed, [](double) { return true; });
    b = c.number(v->as_array()[1], k + "[1]", allowed, [](double) { return true; });
    return true;
  };
  if (!pair("position", out.x, out.y,
            "an array [x, y] in lattice coordinates (row y at y sqrt(3)/2)"))
    c.fail("colloid.position",
           "missing required key 'colloid.position'; allowed: an array [x, y] in lattice "
           "coordinates");
  pair("velocity", out.vx, out.vy, "an array [v_x, v_y] with |v| < 1");
  if (std::abs(out.vx) >= 1.0 || std::abs(out.vy) >= 1.0)
    c.fail("colloid.velocity", "colloid.velocity = [" + float_text(out.vx) + ", " +
                                   float_text(out.vy) + "] is not allowed; allowed: |v| < 1");
  const double most = 0.25 * static_cast<double>(std::min(lattice.size[0], lattice.size[1]));
  if (const toml::value *v = find(&sec, "radius"))
    out.radius = c.number(*v, "colloid.radius",
                          "a number with 0.5 <= radius <= " + float_text(most) +
                              " (a quarter of the smaller lattice size)",
                          [most](double r) { return r >= 0.5 && r <= most; });
  if (const toml::value *v = find(&sec, "mass"))
    out.mass = c.number(*v, "colloid.mass", "a number > 0", [](double m) { return m > 0.0; });
  if (const toml::value *v = find(&sec, "held")) {
    if (!v->is_boolean())
      c.wrong_type("colloid.held", *v,
                   "true (held in place, van der Hoef & Frenkel §4.3) or false (a moving disc)");
    out.held = v->as_boolean();
  }
  // 1/sqrt(3), the covering radius of the lattice: a smaller moving disc covers no site at
  // some positions.
  if (!out.held && out.radius < 0.5774)
    c.fail("colloid.radius", "colloid.radius = " + float_text(out.radius) +
                                 " with colloid.held = false covers no site at some positions; "
                                 "allowed: radius >= 0.5774 (1/sqrt(3)) for a moving disc");
  // A moving disc has no contact rule with solid sites: it would sail into them.
  if (!out.held && (lattice.walls || !lattice.obstacles.empty()))
    c.fail("colloid.held", "colloid.held = false with lattice.walls = true or lattice.obstacles "
                           "is not available (no disc-solid contact); allowed: held = true, or "
                           "a moving disc without walls and obstacles");
  const auto lag = [&](const char *key, std::int64_t &slot) {
    if (const toml::value *v = find(&sec, key))
      slot = c.integer(*v, std::string("colloid.") + key, "an integer from 1 to 10000000",
                       [](std::int64_t n) { return n >= 1 && n <= 10000000; });
  };
  lag("max_lag", out.max_lag);
  lag("displacement_lag", out.displacement_lag);
  lag("displacement_every", out.displacement_every);
  if (out.displacement_lag % out.displacement_every != 0)
    c.fail("colloid.displacement_lag",
           "colloid.displacement_lag = " + std::to_string(out.displacement_lag) +
               " is not a multiple of colloid.displacement_every = " +
               std::to_string(out.displacement_every) + "; allowed: a multiple");
  return out;
}

void parse_lgca_scene(const Checker &c, const toml::value &root, Scene &s) {
  c.check_keys(c.section(root, "lattice"), "lattice");
  s.lgca = parse_lgca(c.section(root, "lattice"), c);
  if (const toml::value *t = c.section(root, "tagged")) {
    c.check_keys(t, "tagged");
    s.tagged = parse_tagged(*t, *s.lgca, c);
  }
  if (const toml::value *t = c.section(root, "colloid")) {
    c.check_keys(t, "colloid");
    s.colloid = parse_colloid(*t, *s.lgca, c);
  }
}

} // namespace narrows::scene::detail
