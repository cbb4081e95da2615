// Maximum-likelihood shock position (see kmc/shock.hpp).
#include "narrows/models/three_state/shock.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::three_state {

std::int64_t shock_position(const std::vector<std::uint8_t> &state,
                            const std::array<double, 3> &p_left,
                            const std::array<double, 3> &p_right) {
  // log L(k) = sum_{j <= k} log p_left(n_j) + sum_{j > k} log p_right(n_j)
  //          = const + S(k),  S(k) = sum_{j <= k} [log p_left(n_j) - log p_right(n_j)].
  std::array<double, 3> delta{};
  for (int s = 0; s < 3; ++s)
    delta[s] = std::log(std::max(p_left[s], 1e-300)) - std::log(std::max(p_right[s], 1e-300));
  double sum = 0.0, best = 0.0;
  std::int64_t best_k = 0;
  for (std::size_t j = 0; j < state.size(); ++j) {
    sum += delta[state[j]];
    if (sum > best) {
      best = sum;
      best_k = static_cast<std::int64_t>(j) + 1;
    }
  }
  return best_k;
}

} // namespace narrows::three_state
