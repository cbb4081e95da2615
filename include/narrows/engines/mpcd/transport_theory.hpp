// Kinetic-theory transport coefficients of the MPCD fluids (PHYSICS.md, "Viscosity theory"),
// in MPCD units (a = 1, m = 1).
#pragma once

#include "narrows/scene/scene.hpp"

#include <optional>

namespace narrows::mpcd {

struct Viscosity {
  double kinetic;
  double collisional;
  double total() const { return kinetic + collisional; }
};

// f(n) = n - 1 + exp(-n): mean number of collision partners with Poisson cell occupancy.
double poisson_partners(double n);

// Kinematic viscosity of a rule in d dimensions at mean density n, time step dt, SRD angle
// (radians) and temperature kT; nothing when no formula applies (AT+a in 2D, random
// solvents).
std::optional<Viscosity> viscosity(scene::Collision rule, int dim, double n, double dt,
                                   double angle, double kT);

// SRD self-diffusion D = (kT dt/2)[d n/(f(n)(1 - cos alpha)) - 1].
double srd_self_diffusion(int dim, double n, double dt, double angle, double kT);

} // namespace narrows::mpcd
