// Validation of the MPCD solvent and its box: [domain], [fluid], [body_force], [walls],
// [thermostat].
#include "parse_mpcd.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace narrows::scene::detail {

using toml::value;

namespace {

constexpr std::int64_t max_cells_per_axis = std::int64_t{1} << 20;
constexpr double max_particles = 1099511627776.0; // 2^40

} // namespace

void parse_domain(const Checker &c, const value *domain, int dims, Domain &out) {
  c.check_keys(domain, "domain");
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
    const double x = c.number(a[d], key, per_axis, [](double) { return true; });
    if (x != std::floor(x))
      c.fail(key,
             key + " = " + repr(a[d]) + " is not a whole number of cells; allowed: " + per_axis);
    if (x < 2.0 || x > static_cast<double>(max_cells_per_axis))
      c.out_of_range(key, a[d], per_axis);
    out.size[d] = x;
  }
  if (const value *b = find(domain, "balance")) {
    const std::vector<std::string> kinds{"none", "work", "time"};
    const std::size_t i = c.choice(*b, "domain.balance", "how the slabs are chosen", kinds);
    out.balance = i == 0 ? Balance::none : i == 1 ? Balance::work : Balance::time;
  }
  if (const value *v = find(domain, "balance_every"))
    out.balance_every = c.integer(*v, "domain.balance_every",
                                  "an integer from 0 (balance at the start only) to 2^31 - 1",
                                  [](std::int64_t n) { return n >= 0 && n < (1LL << 31); });
  if (const value *v = find(domain, "balance_threshold"))
    out.balance_threshold = c.number(*v, "domain.balance_threshold",
                                     "a number >= 1 (max/mean of the counted work or busy time)",
                                     [](double x) { return x >= 1.0 && x < 1e6; });
}

void parse_fluid(const Checker &c, const value *fluid, const Domain &domain, int dims, Fluid &out) {
  const std::vector<std::string> rules{"srd", "at", "at+a", "random-permute", "random-maxwell"};
  if (fluid == nullptr)
    c.fail("fluid", "missing required section [fluid]; allowed keys in [fluid]: " +
                        join(names_of(find_section("fluid")->keys)) +
                        " (collision and dt are required)");
  c.check_keys(fluid, "fluid");

  if (const value *v = find(fluid, "collision")) {
    const std::size_t i = c.choice(*v, "fluid.collision", "a known collision rule", rules);
    constexpr std::array<Collision, 5> values{Collision::srd, Collision::at, Collision::at_a,
                                              Collision::random_permute, Collision::random_maxwell};
    out.collision = values[i];
  } else {
    c.missing("fluid.collision", join(rules));
  }

  const std::string density_allowed = "a number > 0 (mean particles per cell)";
  if (const value *v = find(fluid, "density")) {
    out.density = c.number(*v, "fluid.density", density_allowed, [](double x) { return x > 0.0; });
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
    out.dt = c.number(*v, "fluid.dt", dt_allowed, [](double x) { return x > 0.0; });
  else
    c.missing("fluid.dt", dt_allowed);

  // The rotation angle only matters for srd; with the other rules it is accepted and ignored, so
  // a sweep over collision rules can keep one scene.
  if (const value *v = find(fluid, "angle"))
    out.angle_deg = c.number(*v, "fluid.angle", "0 < angle < 360 (degrees)",
                             [](double x) { return x > 0.0 && x < 360.0; });

  if (const value *v = find(fluid, "kT"))
    out.kT = c.number(*v, "fluid.kT", "a number > 0", [](double x) { return x > 0.0; });

  if (const value *v = find(fluid, "sort_every"))
    out.sort_every = static_cast<int>(
        c.integer(*v, "fluid.sort_every", "an integer from 0 (never sort) to 2147483647",
                  [](std::int64_t n) { return n >= 0 && n <= std::numeric_limits<int>::max(); }));
}

std::optional<BodyForce> parse_body_force(const Checker &c, const value *bf, int dims) {
  if (bf == nullptr)
    return std::nullopt;
  c.check_keys(bf, "body_force");
  BodyForce out;
  const value *kind = find(bf, "kind");
  const value *val = find(bf, "value");
  const value *amp = find(bf, "amplitude");
  if (kind != nullptr) {
    const std::size_t i =
        c.choice(*kind, "body_force.kind", "a known body force kind", {"constant", "sine"});
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
      out.value[d] = c.number(a[d], "body_force.value[" + std::to_string(d) + "]",
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
        c.number(*amp, "body_force.amplitude", amp_allowed, [](double) { return true; });
  }
  if (const value *on = find(bf, "acts_on")) {
    const std::size_t i =
        c.choice(*on, "body_force.acts_on", "a known drive target", {"fluid", "fluid+colloids"});
    out.acts_on = i == 0 ? DriveTarget::fluid : DriveTarget::fluid_and_colloids;
    if (out.acts_on == DriveTarget::fluid_and_colloids && out.kind == ForceKind::sine)
      c.fail("body_force.acts_on",
             "body_force.acts_on = \"fluid+colloids\" cannot be combined with body_force.kind = "
             "\"sine\" (the Kolmogorov force varies across a colloid); allowed: \"fluid\", or a "
             "constant body_force.value");
  }
  return out;
}

std::optional<Thermostat> parse_thermostat(const Checker &c, const value *sec, Collision rule) {
  if (sec == nullptr)
    return std::nullopt;
  c.check_keys(sec, "thermostat");
  Thermostat out;
  const value *kind = find(sec, "kind");
  if (kind == nullptr)
    c.missing("thermostat.kind",
              "\"layers\" (Tabatabaei (2008) eq 3.53-3.54) or \"monte-carlo\" (eq "
              "3.55-3.57)");
  out.kind = static_cast<ThermostatKind>(
      c.choice(*kind, "thermostat.kind", "a known thermostat", {"layers", "monte-carlo"}));
  if (const value *g = find(sec, "gamma")) {
    if (out.kind != ThermostatKind::monte_carlo)
      c.fail("thermostat.gamma", "thermostat.gamma = " + repr(*g) +
                                     " is the step of the Monte Carlo thermostat; allowed only "
                                     "with kind = \"monte-carlo\"");
    out.gamma = c.number(*g, "thermostat.gamma", "a number in (0, 1]",
                         [](double x) { return x > 0.0 && x <= 1.0; });
  }
  if (rule != Collision::srd && rule != Collision::random_permute)
    c.fail("thermostat", std::string("[thermostat] with fluid.collision = \"") + to_string(rule) +
                             "\"; allowed with srd or random-permute (MPC-AT thermostats "
                             "itself, random-maxwell draws at kT)");
  return out;
}

std::optional<Walls> parse_walls(const Checker &c, const value *w,
                                 const std::optional<BodyForce> &force) {
  if (w == nullptr)
    return std::nullopt;
  c.check_keys(w, "walls");
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
        c.choice(*v, "walls.virtual_flow", "a known virtual-particle flow", {"rest", "mirror"});
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

} // namespace narrows::scene::detail
