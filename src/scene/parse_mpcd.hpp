// Validation of the MPCD engine's sections (engine "mpcd"): the solvent and its box
// (parse_mpcd_fluid.cpp), the colloids (parse_mpcd_colloids.cpp), and the engine as a whole
// (parse_mpcd.cpp), called by parse_scene.
#pragma once

#include "checker.hpp"
#include "narrows/scene/scene.hpp"

#include <toml.hpp>

#include <optional>

namespace narrows::scene::detail {

// The sections of an mpcd scene from its table `root`, into `s` (s.run already read).
void parse_mpcd(const Checker &c, const toml::value &root, Scene &s);
// Refuses an observable of output.observables that the scene cannot measure.
void check_mpcd_observables(const Checker &c, const Scene &s);

// Sections may be null (absent); the optional ones then give nullopt.
void parse_domain(const Checker &c, const toml::value *domain, int dims, Domain &out);
void parse_fluid(const Checker &c, const toml::value *fluid, const Domain &domain, int dims,
                 Fluid &out);
std::optional<BodyForce> parse_body_force(const Checker &c, const toml::value *bf, int dims);
std::optional<Walls> parse_walls(const Checker &c, const toml::value *w,
                                 const std::optional<BodyForce> &force);
std::optional<Thermostat> parse_thermostat(const Checker &c, const toml::value *sec,
                                           Collision rule);
std::optional<Colloids> parse_colloids(const Checker &c, const toml::value *sec,
                                       const Domain &domain, int dims, bool walls);
// The conditions no-slip colloids put on the fluid, the time step and the contacts.
void check_no_slip(const Checker &c, const Scene &s);

} // namespace narrows::scene::detail
