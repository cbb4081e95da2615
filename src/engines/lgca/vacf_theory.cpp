// Kinetic theory of the tagged-particle VACF (see lattice/vacf_theory.hpp).
#include "narrows/engines/lgca/vacf_theory.hpp"

#include "narrows/core/error.hpp"

#include <bit>
#include <cmath>
#include <string>

namespace narrows::lgca::theory {

double mean_square_velocity(const Links &links) {
  double s = 0.0;
  for (int i = 0; i < links.count(); ++i) {
    s += links.cx[i] * links.cx[i];
    if (links.dims() == 2)
      s += links.cy[i] * links.cy[i];
  }
  return s / links.count();
}

double mean_square_velocity_x(const Links &links) {
  double s = 0.0;
  for (int i = 0; i < links.count(); ++i)
    s += links.cx[i] * links.cx[i];
  return s / links.count();
}

double one_step_vacf(const Links &links, double d) {
  if (!(d > 0.0 && d < 1.0))
    throw input_error("lattice.density = " + std::to_string(d) + " not allowed; need 0 < d < 1");
  const int b = links.count(), dims = links.dims();
  double sum = 0.0;
  for (unsigned s = 1; s < (1u << b); ++s) {
    const int rho = std::popcount(s);
    double jx = 0.0, jy = 0.0;
    for (int j = 0; j < b; ++j)
      if ((s >> j) & 1u) {
        jx += links.cx[j];
        if (dims == 2)
          jy += links.cy[j];
      }
    // weight of s given that link i is occupied: d^(rho-1) (1-d)^(b-rho)
    const double w = std::pow(d, rho - 1) * std::pow(1.0 - d, b - rho);
    for (int i = 0; i < b; ++i)
      if ((s >> i) & 1u) {
        double cu = links.cx[i] * jx;
        if (dims == 2)
          cu += links.cy[i] * jy;
        sum += w * cu / rho;
      }
  }
  return sum / (b * mean_square_velocity(links));
}

double one_step_vacf_closed_form(int b, double d) {
  return (1.0 - d) * (1.0 - std::pow(1.0 - d, b - 1)) / (d * (b - 1));
}

double boltzmann_diffusion(double v2x, double z1) { return v2x * (0.5 + z1 / (1.0 - z1)); }

double mean_free_time(double z1) { return -1.0 / std::log(z1); }

double finite_size_correction(double d, double n) { return (1.0 - d) / n; }

double intermediate_plateau(double d, double n, double m2) { return (m2 - (1.0 - d)) / n; }

double long_time_limit(double n, double m2) { return m2 / n; }

} // namespace narrows::lgca::theory
