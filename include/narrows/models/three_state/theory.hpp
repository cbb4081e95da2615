// Exact results the kmc engine is checked against.
#pragma once

namespace narrows::three_state::theory {

// Stationary current of open TASEP (hop rate 1, injection alpha, extraction beta) on L sites:
// J = Z_(L-1) / Z_L with the matrix-product normalisation of Derrida et al. (1993),
//   Z_N = sum_p p (2N-1-p)! / (N! (N-p)!) * (b^(p+1) - a^(p+1)) / (b - a), a = 1/alpha,
// b = 1/beta (the limit (p+1) a^p when a = b).
double tasep_open_current(int L, double alpha, double beta);

// Its L -> infinity limit: alpha(1-alpha) (low density, alpha < beta, alpha < 1/2),
// beta(1-beta) (high density), 1/4 (maximal current, alpha, beta >= 1/2).
double tasep_open_current_limit(double alpha, double beta);

} // namespace narrows::three_state::theory
