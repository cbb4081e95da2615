// Exact TASEP currents (see kmc/theory.hpp).
#include "narrows/models/three_state/theory.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace narrows::three_state::theory {

namespace {

// log Z_N, summed in logs (the terms overflow doubles for N of a few hundred).
double log_z(int N, double alpha, double beta) {
  if (N == 0)
    return 0.0;
  const double a = 1.0 / alpha, b = 1.0 / beta;
  std::vector<double> terms;
  for (int p = 1; p <= N; ++p) {
    double log_ab; // log of (b^(p+1) - a^(p+1)) / (b - a)
    if (std::abs(a - b) < 1e-12 * std::max(a, b)) {
      log_ab = std::log(p + 1.0) + p * std::log(a);
    } else {
      const double hi = std::max(a, b), lo = std::min(a, b);
      // (hi^(p+1) - lo^(p+1)) / (hi - lo) = hi^p (1 - (lo/hi)^(p+1)) / (1 - lo/hi)
      const double x = lo / hi;
      log_ab = p * std::log(hi) + std::log1p(-std::pow(x, p + 1)) - std::log1p(-x);
    }
    terms.push_back(std::log(static_cast<double>(p)) + std::lgamma(2.0 * N - p) -
                    std::lgamma(N + 1.0) - std::lgamma(N - p + 1.0) + log_ab);
  }
  const double m = *std::max_element(terms.begin(), terms.end());
  double s = 0.0;
  for (double x : terms)
    s += std::exp(x - m);
  return m + std::log(s);
}

} // namespace

double tasep_open_current(int L, double alpha, double beta) {
  return std::exp(log_z(L - 1, alpha, beta) - log_z(L, alpha, beta));
}

double tasep_open_current_limit(double alpha, double beta) {
  if (alpha >= 0.5 && beta >= 0.5)
    return 0.25;
  return alpha < beta ? alpha * (1.0 - alpha) : beta * (1.0 - beta);
}

} // namespace narrows::three_state::theory
