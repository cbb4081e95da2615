// Shock position of a three-state configuration (Tabatabaei (2008) §2.3.8, §2.4.2).
//
// Estimator (maximum likelihood over shock measures): the configuration is scored as a shock
// measure |k> (eq 2.23) with single-site probabilities p_left on sites 1..k and p_right on
// k+1..L, and the k in 0..L with the highest likelihood is returned (the first one on ties).
// When the dynamics keeps the family of shock measures closed (eq 2.62), the configuration given
// the true shock position k is exactly that product measure, so the estimator error has the
// same distribution wherever the shock is (away from the ends): differences of the mean and of
// the variance of the estimate between two times are exactly those of the true position. The
// error itself is a few sites. States of probability 0 in a branch count as log(1e-300).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace narrows::three_state {

std::int64_t shock_position(const std::vector<std::uint8_t> &state,
                            const std::array<double, 3> &p_left,
                            const std::array<double, 3> &p_right);

} // namespace narrows::three_state
