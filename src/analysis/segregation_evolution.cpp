// The evolution parameter and the steady-state criterion (see the header).
#include "narrows/analysis/segregation_evolution.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace narrows::analysis {

double evolution_parameter(std::span<const double> c, std::span<const double> c0) {
  double num = 0.0, den = 0.0;
  for (std::size_t j = 0; j < c.size(); ++j) {
    num += (c[j] - c0[j]) * (c[j] - c0[j]);
    den += c0[j] * c0[j];
  }
  return den > 0.0 ? num / den : std::numeric_limits<double>::quiet_NaN();
}

SteadyCheck steady_check(std::span<const double> t, std::span<const double> delta) {
  SteadyCheck out;
  const std::size_t n = delta.size();
  if (n < 4)
    return out;
  const std::size_t k = std::max<std::size_t>(4, (n + 3) / 4);
  const std::size_t first = n - k;
  double tm = 0.0, dm = 0.0;
  for (std::size_t i = first; i < n; ++i) {
    tm += t[i];
    dm += delta[i];
  }
  tm /= static_cast<double>(k);
  dm /= static_cast<double>(k);
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t i = first; i < n; ++i) {
    sxx += (t[i] - tm) * (t[i] - tm);
    sxy += (t[i] - tm) * (delta[i] - dm);
  }
  const double slope = sxy / sxx;
  double rss = 0.0;
  for (std::size_t i = first; i < n; ++i) {
    const double r = delta[i] - dm - slope * (t[i] - tm);
    rss += r * r;
  }
  out.judged = true;
  out.points = k;
  out.slope = slope;
  out.sigma = std::sqrt(rss / static_cast<double>(k - 2) / sxx);
  out.steady = std::abs(slope) <= 2.0 * out.sigma;
  return out;
}

} // namespace narrows::analysis
