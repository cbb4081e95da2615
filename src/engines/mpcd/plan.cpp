// Resolving a scene into the MPCD plan, and the words of the pipeline for what it resolved.
#include "narrows/engines/mpcd/plan.hpp"

#include "narrows/colloids/potentials.hpp"
#include "narrows/engines/mpcd/colloid_placement.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace narrows::mpcd {

std::string format_number(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

std::string stream_text(const scene::Scene &s, const MpcdPlan &p, const mpcd::Box &box) {
  const int dim = p.dim;
  std::string name;
  switch (p.stream) {
  case MpcdPlan::Stream::channel:
    name = std::string("stream with ") + (p.slip ? "slip (specular)" : "no-slip bounce-back") +
           " walls at y = 0 and y = " + format_number(box.length[1]);
    if (s.body_force) {
      name += ", constant force [";
      for (int k = 0; k < dim; ++k)
        name += format_number(p.force[k]) + (k + 1 < dim ? ", " : "], exact hit times");
    }
    return name;
  case MpcdPlan::Stream::free:
    return "stream (free flight)";
  case MpcdPlan::Stream::constant_force:
    name = "stream (constant force [";
    for (int k = 0; k < dim; ++k)
      name += format_number(p.force[k]) + (k + 1 < dim ? ", " : "])");
    return name;
  case MpcdPlan::Stream::sine_force:
    return "stream (sine force a_x = " + format_number(p.sine_amplitude) +
           " sin(2 pi y/L_y), exact)";
  }
  return name;
}

namespace {

// The fields on the colloids, for the pipeline line: ", gravity", ", the body force (M a)" or
// both.
std::string colloid_drive_text(const scene::Scene &s) {
  std::string t;
  if (s.colloids->gravity != std::array<double, 3>{0.0, 0.0, 0.0})
    t += ", gravity";
  if (s.body_force && s.body_force->acts_on == scene::DriveTarget::fluid_and_colloids)
    t += ", the body force on the colloids too (M a: body_force.acts_on = \"fluid+colloids\")";
  return t;
}

// "2 kinds: 100 of r 2 M 125.664, 100 of r 4 M 600" ([[colloids.kind]]).
std::string kinds_text(const scene::Colloids &c, int dim, double density) {
  std::string t = std::to_string(c.kinds.size()) + " kinds:";
  std::uint64_t first = 0;
  for (const auto &k : c.kinds) {
    t += (first > 0 ? ", " : " ") + std::to_string(k.count) + " of r " + format_number(k.radius) +
         " M " + format_number(c.mass_of_id(dim, density, first, k.radius));
    first += static_cast<std::uint64_t>(k.count);
  }
  return t;
}

std::string md_text(const scene::Scene &s, const MpcdPlan &p) {
  const auto &c = *s.colloids;
  const int dim = p.dim;
  // Sizes from the scene (on a restart the colloids are not here yet): the radii are drawn
  // from (seed, id) alone.
  std::string size = "r " + format_number(c.radius) + ", M " +
                     format_number(c.effective_mass(dim, s.fluid.density));
  double r_lo = c.radius, r_hi = c.radius;
  if (c.radius_sd > 0.0) {
    for (std::int64_t i = 0; i < c.count; ++i) {
      const double r = colloid_radius(c, p.seed, static_cast<std::uint64_t>(i));
      r_lo = std::min(r_lo, r);
      r_hi = std::max(r_hi, r);
    }
    size = "r " + format_number(c.radius) + " sd " + format_number(c.radius_sd) +
           " truncated at 3 sd, drawn " + format_number(r_lo) + " to " + format_number(r_hi);
    if (c.mass > 0.0)
      size += ", M " + format_number(c.mass);
    else
      size += ", M " + format_number(c.mass_of(dim, s.fluid.density, r_lo)) + " to " +
              format_number(c.mass_of(dim, s.fluid.density, r_hi));
  }
  if (!c.kinds.empty()) {
    size = kinds_text(c, dim, s.fluid.density);
    r_lo = c.max_radius();
    r_hi = 0.0;
    for (const auto &k : c.kinds) {
      r_lo = std::min(r_lo, k.radius);
      r_hi = std::max(r_hi, k.radius);
    }
  }
  std::string md = "MD: " + std::to_string(c.count) + " colloids (" + size + "), " +
                   std::to_string(c.md_substeps) + " velocity-Verlet sub-steps of " +
                   format_number(p.md.tau) + ": WCA colloid-fluid, 48-24 colloid-colloid";
  if (s.walls) {
    const double lo = c.wall_sigma_of(r_lo), hi = c.wall_sigma_of(r_hi);
    if (lo == hi)
      md += ", LJ wall (sigma_w " + format_number(lo) + ", cut-off " +
            format_number(colloids::wall_cutoff(lo)) + ")";
    else
      md += ", LJ wall (sigma_w 2 r_a " + format_number(lo) + " to " + format_number(hi) +
            ", cut-off " + format_number(colloids::wall_cutoff(lo)) + " to " +
            format_number(colloids::wall_cutoff(hi)) + ")";
  }
  md += colloid_drive_text(s);
  return md;
}

std::string no_slip_text(const scene::Scene &s, const MpcdPlan &p) {
  const auto &c = *s.colloids;
  const std::string size = c.kinds.empty()
                               ? "r " + format_number(c.radius) +
                                     (c.radius_sd > 0.0 ? " sd " + format_number(c.radius_sd) : "")
                               : kinds_text(c, p.dim, s.fluid.density);
  std::string t =
      "no-slip colloids: " + std::to_string(c.count) + " (" + size + ") move " +
      (p.no_slip_params.hard_contacts
           ? "with event-driven rough hard-sphere contacts (Kanehl (thesis) eq 4.19-4.30)"
       : p.no_slip_params.spring_contacts
           ? "with linear springs and Coulomb friction (Kanehl (thesis) eq 4.39-4.42: kn " +
                 format_number(c.spring.kn) + ", kt " + format_number(c.spring.kt) + ", mu_cc " +
                 format_number(c.spring.mu_cc) + ", mu_cw " + format_number(c.spring.mu_cw) + ", " +
                 std::to_string(c.spring.substeps) + " sub-steps per step)"
           : "ballistically (no contacts)");
  t += colloid_drive_text(s);
  return t;
}

} // namespace

std::string colloids_text(const scene::Scene &s, const MpcdPlan &p) {
  if (!p.colloids)
    return "";
  return p.no_slip ? no_slip_text(s, p) : md_text(s, p);
}

MpcdPlan make_plan(const scene::Scene &s, const mpcd::Box &box, int ranks) {
  MpcdPlan p;
  const auto &f = s.fluid;
  p.dim = box.dim;
  p.seed = s.run.seed;
  p.dt = f.dt;
  p.kT = f.kT;
  if (s.walls) {
    p.stream = MpcdPlan::Stream::channel;
    p.slip = s.walls->slip;
    if (s.body_force)
      p.force = s.body_force->value;
  } else if (!s.body_force) {
    p.stream = MpcdPlan::Stream::free;
  } else if (s.body_force->kind == scene::ForceKind::constant) {
    p.stream = MpcdPlan::Stream::constant_force;
    p.force = s.body_force->value;
  } else {
    p.stream = MpcdPlan::Stream::sine_force;
    p.sine_amplitude = s.body_force->amplitude;
  }
  if (s.colloids) {
    const auto &c = *s.colloids;
    p.colloids = true;
    p.md.substeps = c.md_substeps;
    p.md.tau = f.dt / c.md_substeps;
    if (s.body_force) {
      const auto &b = *s.body_force;
      p.md.fluid_accel = b.kind == scene::ForceKind::sine
                             ? std::abs(b.amplitude)
                             : std::sqrt(b.value[0] * b.value[0] + b.value[1] * b.value[1] +
                                         b.value[2] * b.value[2]);
    }
    p.forces.epsilon = c.epsilon;
    p.forces.sigma_wall = c.wall_sigma; // 0: 2 r_a for each colloid
    p.forces.wall_q = c.wall_q;
    p.forces.gravity = scene::colloid_acceleration(s);
    if (c.coupling == scene::ColloidCoupling::no_slip) {
      p.no_slip = true;
      auto &q = p.no_slip_params;
      q.dt = f.dt;
      q.kT = f.kT;
      q.density = f.density;
      q.seed = s.run.seed;
      q.gravity = scene::colloid_acceleration(s);
      if (s.body_force && s.body_force->kind == scene::ForceKind::constant)
        q.fluid_accel = s.body_force->value;
      if (s.body_force && s.body_force->kind == scene::ForceKind::sine)
        q.sine_amplitude = s.body_force->amplitude;
      q.hard_contacts = c.contacts == scene::ColloidContacts::hard;
      q.spring_contacts = c.contacts == scene::ColloidContacts::spring;
      q.implicit = c.exchange_implicit;
      q.spring = {c.spring.kn, c.spring.kt, c.spring.mu_cc, c.spring.mu_cw, c.spring.substeps};
    }
  }
  p.ranks = ranks;
  p.slabs = ranks > 1;
  p.collision = f.collision;
  p.angle_rad = f.angle_deg * std::numbers::pi / 180.0;
  p.density = f.density;
  if (s.walls && s.walls->virtual_particles) {
    p.virtual_particles = true;
    p.virtual_mirror = s.walls->virtual_flow == scene::VirtualFlow::mirror;
    p.virtual_at_noise =
        f.collision == scene::Collision::at || f.collision == scene::Collision::at_a;
  }
  if (s.thermostat) {
    p.thermostat = s.thermostat->kind == scene::ThermostatKind::layers
                       ? MpcdPlan::Thermostat::layers
                       : MpcdPlan::Thermostat::monte_carlo;
    p.gamma = s.thermostat->gamma;
  }
  p.sort_every = f.sort_every > 0 ? static_cast<std::uint64_t>(f.sort_every) : 0;
  return p;
}

} // namespace narrows::mpcd
