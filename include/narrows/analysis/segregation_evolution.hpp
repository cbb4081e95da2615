// The evolution parameter of a density profile and when it stops evolving. Kanehl (thesis)
// eq 5.31: Delta(t) = int dy [c(y, t) - c(y, 0)]^2 / int dy c(y, 0)^2, here over profiles at the
// centres of equal bins (the bin width cancels). The thesis judges the steady state by eye; the
// criterion here: a least-squares line through Delta over the last K = max(4, ceil(n/4)) of n
// values is flat when |slope| <= 2 sigma_slope, sigma_slope from the residuals (K - 2 degrees of
// freedom).
#pragma once

#include <cstddef>
#include <span>

namespace narrows::analysis {

// Delta of profile c against the reference c0 (same bins); NaN if c0 is 0 everywhere.
double evolution_parameter(std::span<const double> c, std::span<const double> c0);

struct SteadyCheck {
  bool judged = false; // at least 4 values
  bool steady = false;
  std::size_t points = 0; // K
  double slope = 0.0, sigma = 0.0;
};

// The criterion over the series (t[i], delta[i]), t increasing.
SteadyCheck steady_check(std::span<const double> t, std::span<const double> delta);

} // namespace narrows::analysis
