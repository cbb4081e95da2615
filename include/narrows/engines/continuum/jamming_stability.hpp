// Linear stability of homogeneous flow phi = phi0, v = v_ss(phi0) in the jamming model
// (Kanehl (thesis) eq 6.7-6.11): a perturbation exp(i k x + lambda t) grows at Re lambda, with
//   lambda = lambda* - i k v0,  lambda* = a +- sqrt(a^2 - xi D k^2 + i k phi0 sigma xi' / xi),
//   a = -(D k^2 + xi) / 2,
// the eigenvalues of the 2x2 matrix of eq 6.10 (with sigma = D = 1 exactly eq 6.11).
#pragma once

#include "narrows/engines/continuum/jamming_model.hpp"

#include <complex>

namespace narrows::continuum {

// The eigenvalue of larger real part (the growth rate is its real part, the phase velocity
// -Im lambda / k).
std::complex<double> growth_rate(const JammingModel &model, double phi0, double k);
// The other eigenvalue (the fast relaxation of v towards v_ss).
std::complex<double> decay_rate(const JammingModel &model, double phi0, double k);

// The long-wave limit: Re lambda = k^2 (phi0^2 v_ss'^2 v_ss / (sigma D) - 1) + O(k^4), so
// homogeneous flow is unstable to long waves iff phi0^2 v_ss'(phi0)^2 v_ss(phi0) > sigma D.
// Returns phi0^2 v_ss'^2 v_ss / (sigma D) - 1 (> 0: unstable).
double long_wave_coefficient(const JammingModel &model, double phi0);
// The drive sigma below which homogeneous flow at phi0 is unstable to long waves:
// phi0^2 v_ss'(phi0)^2 v_ss(phi0) / D (the stability boundary in the (phi0, drive) plane).
double critical_drive(const JammingModel &model, double phi0);

// The upper edge of the unstable band 0 < k < k_c (0 when no wave number up to k_max grows):
// scanned from k -> 0 (the sign of long_wave_coefficient) on `samples` points up to k_max and
// refined by bisection.
double unstable_band_edge(const JammingModel &model, double phi0, double k_max, int samples = 2000);

} // namespace narrows::continuum
