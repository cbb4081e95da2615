// Growth rates of the jamming model's homogeneous flow (see continuum/jamming_stability.hpp).
#include "narrows/engines/continuum/jamming_stability.hpp"

#include <cmath>

namespace narrows::continuum {

namespace {

// lambda* +- (eq 6.11 with sigma and D): the matrix [[-D k^2, -i k phi0], [-sigma xi'/xi, -xi]].
std::complex<double> lambda_star(const JammingModel &m, double phi0, double k, double sign) {
  const double xi = m.xi(phi0), D = m.diffusion();
  const double a = -(D * k * k + xi) / 2.0;
  const std::complex<double> disc(a * a - xi * D * k * k, k * phi0 * m.drive() * m.dxi(phi0) / xi);
  // std::sqrt takes the principal root (Re >= 0): a + root has the larger real part.
  return a + sign * std::sqrt(disc);
}

} // namespace

std::complex<double> growth_rate(const JammingModel &model, double phi0, double k) {
  const double v0 = model.vss(phi0);
  return lambda_star(model, phi0, k, 1.0) - std::complex<double>(0.0, k * v0);
}

std::complex<double> decay_rate(const JammingModel &model, double phi0, double k) {
  const double v0 = model.vss(phi0);
  return lambda_star(model, phi0, k, -1.0) - std::complex<double>(0.0, k * v0);
}

double long_wave_coefficient(const JammingModel &model, double phi0) {
  const double v = model.vss(phi0), dv = model.dvss(phi0);
  return phi0 * phi0 * dv * dv * v / (model.drive() * model.diffusion()) - 1.0;
}

double critical_drive(const JammingModel &model, double phi0) {
  const double v = model.vss(phi0), dv = model.dvss(phi0);
  return phi0 * phi0 * dv * dv * v / model.diffusion();
}

double unstable_band_edge(const JammingModel &model, double phi0, double k_max, int samples) {
  const auto g = [&](double k) { return growth_rate(model, phi0, k).real(); };
  double edge = 0.0;
  // The scan starts at k -> 0, where Re lambda = k^2 long_wave_coefficient + O(k^4): a band
  // narrower than the first sample k_max / samples (close to the stability boundary) is found
  // by bisection between 0 and that sample instead of being missed.
  double prev_k = 0.0;
  bool prev_unstable = long_wave_coefficient(model, phi0) > 0.0;
  for (int i = 1; i <= samples; ++i) {
    const double k = k_max * i / samples;
    const bool unstable = g(k) > 0.0;
    if (prev_unstable && !unstable) {
      double a = prev_k, b = k; // g(a) > 0 >= g(b)
      for (int it = 0; it < 100 && b - a > 1e-14 * b; ++it) {
        const double mid = 0.5 * (a + b);
        (g(mid) > 0.0 ? a : b) = mid;
      }
      edge = 0.5 * (a + b);
    }
    prev_unstable = unstable;
    prev_k = k;
  }
  if (prev_unstable)
    edge = k_max;
  return edge;
}

} // namespace narrows::continuum
