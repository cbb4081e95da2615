// Poiseuille fit for the viscosity observable.
#include "narrows/analysis/poiseuille.hpp"

namespace narrows::analysis {

PoiseuilleFit fit_poiseuille(const std::vector<double> &centres,
                             const std::vector<double> &velocity, int dim, double bin_width,
                             double L, double g) {
  const std::size_t n = centres.size();
  double sq = 0, sv = 0, sqq = 0, sqv = 0;
  for (std::size_t b = 0; b < n; ++b) {
    const double c = centres[b];
    const double q = c * (L - c) - bin_width * bin_width / 12.0;
    const double v = velocity[b * static_cast<std::size_t>(dim)];
    sq += q;
    sv += v;
    sqq += q * q;
    sqv += q * v;
  }
  const double nb = static_cast<double>(n);
  const double a = (nb * sqv - sq * sv) / (nb * sqq - sq * sq);
  const double b = (sv - a * sq) / nb;
  PoiseuilleFit fit;
  fit.nu = g / (2.0 * a);
  fit.wall_velocity = b;
  fit.centre_velocity = a * L * L / 4.0 + b;
  return fit;
}

} // namespace narrows::analysis
