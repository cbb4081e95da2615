// Exact Riemann and characteristic solutions (see continuum/exact.hpp).
#include "narrows/engines/continuum/exact.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace narrows::continuum {

namespace {

// +1 convex, -1 concave on [a, b] (sampled second differences), 0 otherwise.
int convexity(const Flux &flux, double a, double b) {
  const double lo = std::min(a, b), hi = std::max(a, b);
  int sign = 0;
  const int n = 256;
  for (int i = 0; i < n; ++i) {
    const double s0 = flux.speed(lo + (hi - lo) * i / n);
    const double s1 = flux.speed(lo + (hi - lo) * (i + 1) / n);
    const double d = s1 - s0;
    if (std::abs(d) < 1e-12)
      continue;
    const int s = d > 0.0 ? 1 : -1;
    if (sign != 0 && s != sign)
      return 0;
    sign = s;
  }
  return sign;
}

} // namespace

Riemann riemann(const Flux &flux, double l, double r) {
  Riemann out;
  if (l == r) {
    out.fan_lo = out.fan_hi = flux.speed(l);
    return out;
  }
  const int cx = convexity(flux, l, r);
  if (cx == 0)
    throw std::invalid_argument("riemann: the flux changes convexity between the states");
  // Convex: a shock when l > r (characteristics converge); concave: when l < r.
  out.shock = cx > 0 ? l > r : l < r;
  if (out.shock)
    out.speed = (flux(l) - flux(r)) / (l - r);
  out.fan_lo = flux.speed(l);
  out.fan_hi = flux.speed(r);
  return out;
}

double riemann_density(const Flux &flux, double l, double r, double xi) {
  const Riemann rp = riemann(flux, l, r);
  if (rp.shock)
    return xi < rp.speed ? l : r;
  if (xi <= rp.fan_lo)
    return l;
  if (xi >= rp.fan_hi)
    return r;
  // J' is monotone between l and r: bisect J'(rho) = xi.
  double a = l, b = r;
  for (int it = 0; it < 200 && a != b; ++it) {
    const double m = 0.5 * (a + b);
    if (flux.speed(m) < xi)
      a = m;
    else
      b = m;
    if (std::abs(b - a) < 1e-15)
      break;
  }
  return 0.5 * (a + b);
}

double characteristic_density(const Flux &flux, const std::function<double(double)> &rho0,
                              double lo, double hi, double x, double t) {
  // g(rho) = rho - rho0(x - J'(rho) t) is increasing in rho before characteristics cross.
  const auto g = [&](double rho) { return rho - rho0(x - flux.speed(rho) * t); };
  double a = lo, b = hi;
  if (g(a) > 0.0 || g(b) < 0.0)
    throw std::invalid_argument("characteristic_density: no root in [lo, hi]");
  for (int it = 0; it < 200; ++it) {
    const double m = 0.5 * (a + b);
    (g(m) < 0.0 ? a : b) = m;
    if (b - a < 1e-15)
      break;
  }
  return 0.5 * (a + b);
}

} // namespace narrows::continuum
