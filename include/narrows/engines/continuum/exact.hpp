// Exact solutions of rho_t + J(rho)_x = 0 the scheme is validated against: the self-similar
// solution of a Riemann problem (a shock at the Rankine-Hugoniot speed or a rarefaction fan)
// for a flux that is convex or concave between the two states, and the smooth solution by
// characteristics before the shock forms.
#pragma once

#include "narrows/engines/continuum/flux.hpp"

#include <functional>

namespace narrows::continuum {

struct Riemann {
  bool shock = false;
  double speed = 0.0;                // shock: Rankine-Hugoniot (J(l) - J(r)) / (l - r)
  double fan_lo = 0.0, fan_hi = 0.0; // rarefaction: J'(l), J'(r), the edges of the fan in x/t
};

// Refuses (std::invalid_argument) a flux that changes convexity between l and r.
Riemann riemann(const Flux &flux, double l, double r);
// The solution at x/t = xi.
double riemann_density(const Flux &flux, double l, double r, double xi);

// rho(x, t) = rho0(x - J'(rho) t) by bisection around the characteristic through x (valid
// before characteristics cross; rho0 is evaluated at any real x, e.g. periodically).
double characteristic_density(const Flux &flux, const std::function<double(double)> &rho0,
                              double lo, double hi, double x, double t);

} // namespace narrows::continuum
