// Transport coefficients from kinetic theory.
#include "narrows/engines/mpcd/transport_theory.hpp"

#include <cmath>

namespace narrows::mpcd {

double poisson_partners(double n) { return n - 1.0 + std::exp(-n); }

std::optional<Viscosity> viscosity(scene::Collision rule, int dim, double n, double dt,
                                   double angle, double kT) {
  const double f = poisson_partners(n);
  const double ca = std::cos(angle), sa = std::sin(angle);
  switch (rule) {
  case scene::Collision::srd:
    if (dim == 2)
      return Viscosity{0.5 * kT * dt * (n / (f * sa * sa) - 1.0),
                       (1.0 / (12.0 * dt)) * (f / n) * (1.0 - ca)};
    return Viscosity{0.5 * kT * dt * (5.0 * n / (f * (2.0 - ca - std::cos(2.0 * angle))) - 1.0),
                     (1.0 / (18.0 * dt)) * (f / n) * (1.0 - ca)};
  case scene::Collision::at:
    return Viscosity{kT * dt * (n / f - 0.5), f / (12.0 * n * dt)};
  case scene::Collision::at_a:
    if (dim == 3)
      return Viscosity{kT * dt * (n / (n - 1.25) - 0.5), (n - 1.4) / (24.0 * n * dt)};
    return std::nullopt;
  default:
    return std::nullopt;
  }
}

double srd_self_diffusion(int dim, double n, double dt, double angle, double kT) {
  return 0.5 * kT * dt * (dim * n / (poisson_partners(n) * (1.0 - std::cos(angle))) - 1.0);
}

} // namespace narrows::mpcd
