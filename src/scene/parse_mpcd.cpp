// The MPCD engine's scene: its sections in the order they depend on each other, and the
// observables a scene of it can measure.
#include "parse_mpcd.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace narrows::scene::detail {

void parse_mpcd(const Checker &c, const toml::value &root, Scene &s) {
  parse_domain(c, c.section(root, "domain"), s.run.dimensions, s.domain);
  parse_fluid(c, c.section(root, "fluid"), s.domain, s.run.dimensions, s.fluid);
  s.body_force = parse_body_force(c, c.section(root, "body_force"), s.run.dimensions);
  s.walls = parse_walls(c, c.section(root, "walls"), s.body_force);
  s.colloids = parse_colloids(c, c.section(root, "colloids"), s.domain, s.run.dimensions,
                              s.walls.has_value());
  s.thermostat = parse_thermostat(c, c.section(root, "thermostat"), s.fluid.collision);
  if (s.body_force && s.body_force->acts_on == DriveTarget::fluid_and_colloids && !s.colloids)
    c.fail("body_force.acts_on", "body_force.acts_on = \"fluid+colloids\" needs [colloids] (there "
                                 "are none to drive); allowed without them: \"fluid\"");
  if (s.colloids && s.colloids->coupling == ColloidCoupling::no_slip)
    check_no_slip(c, s);
}

namespace {

// axial_fields: bins that cover the periodic length exactly (so the mean
// of phi over the bins is the colloid area over the channel area).
void check_axial_fields(const Checker &c, const Scene &s) {
  const double length = s.domain.size[0], bin = s.output.axial_bin;
  const std::string allowed = "; allowed with \"axial_fields\": a width at most domain.size[0] "
                              "that divides it";
  if (bin > length * (1.0 + 1e-9))
    c.fail("output.axial_bin",
           "output.axial_bin = " + float_text(bin) +
               " is longer than the channel, domain.size[0] = " + float_text(length) + allowed);
  const double bins = std::round(length / bin);
  if (std::abs(bins * bin - length) > 1e-9 * length)
    c.fail("output.axial_bin", "output.axial_bin = " + float_text(bin) +
                                   " does not divide domain.size[0] = " + float_text(length) +
                                   " into whole bins" + allowed + " (e.g. " +
                                   float_text(length / bins) + ")");
}

} // namespace

void check_mpcd_observables(const Checker &c, const Scene &s) {
  const auto &obs = s.output.observables;
  const auto listed = [&obs](std::string_view name) {
    return std::find(obs.begin(), obs.end(), name) != obs.end();
  };
  for (const auto &o : engine_schema(Engine::mpcd).observables)
    if (o.follows_colloids && listed(o.name) && !s.colloids)
      c.fail("output.observables", "output.observables lists \"" + std::string(o.name) +
                                       "\", which follows colloids; allowed only with [colloids]");
  if (listed("contact_statistics") && s.colloids && s.colloids->contacts != ColloidContacts::spring)
    c.fail(
        "output.observables",
        std::string("output.observables lists \"contact_statistics\" with colloids.contacts = \"") +
            (s.colloids->contacts == ColloidContacts::hard ? "hard" : "none") +
            "\" (hard-sphere contacts are instantaneous: no overlaps, forces or lasting "
            "contacts to count); allowed only with colloids.contacts = \"spring\"");
  const bool poiseuille = s.walls && s.body_force && s.body_force->kind == ForceKind::constant &&
                          s.body_force->value[0] != 0.0;
  if (listed("viscosity") && !poiseuille)
    c.fail("output.observables",
           "output.observables lists \"viscosity\", which fits the Poiseuille profile; allowed "
           "only with [walls] and a body_force.value whose x component is non-zero");
  if (listed("axial_fields"))
    check_axial_fields(c, s);
  if (s.output.kde_window > 0 && !listed("density_kde"))
    c.fail("output.kde_window",
           "output.kde_window = " + std::to_string(s.output.kde_window) +
               " windows density_kde, which output.observables does not list; allowed: 0, or "
               "list \"density_kde\"");
  if (listed("evolution") && (!listed("density_kde") || s.output.kde_window == 0))
    c.fail("output.observables",
           "output.observables lists \"evolution\", Delta(t) of the density_kde windows, "
           "without them (output.kde_window = " +
               std::to_string(s.output.kde_window) +
               (listed("density_kde") ? "" : ", density_kde not listed") +
               "); allowed only with \"density_kde\" and output.kde_window > 0");
  // The fit needs two distinct values of y (L - y) over the unit bins: two bins are symmetric.
  if (listed("viscosity") && s.domain.size[1] < 3.0)
    c.fail("output.observables", "output.observables lists \"viscosity\" with domain.size[1] = " +
                                     float_text(s.domain.size[1]) +
                                     ", too narrow to fit a parabola; allowed: domain.size[1] "
                                     ">= 3");
}

} // namespace narrows::scene::detail
