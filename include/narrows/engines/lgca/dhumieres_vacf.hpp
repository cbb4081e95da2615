// Tagged-particle VACF of the 1D d'Humieres model by moment propagation (van der Hoef & Frenkel
// fig 1): one run draws an initial state from an ensemble and records successive VACF curves.
#pragma once

#include "narrows/engines/lgca/dhumieres_1d.hpp"

#include <cstdint>
#include <functional>
#include <vector>

namespace narrows::lgca::dhumieres {

struct VacfRun {
  std::vector<double> vacf; // mean over curves of <v(0) v(t)>, lags 0..max_lag (not normalised)
  int curves = 0;
  std::int64_t particles = 0, momentum = 0; // N and P of the run (both conserved)
  double seconds = 0.0;
  bool stopped = false; // `stop` answered true before every curve was measured
};

// Draws the initial state (seed), then collides (seed + 1 as the collision seed) and
// propagates for `curves` successive curves of lags 0..max_lag; moment propagation sees every
// post-collision state, the initial state being the post-collision state of step 0. `stop`
// (if given) is asked every 4096 steps; when it answers true the run ends early (stopped).
VacfRun measure_vacf(std::int64_t L, double d, Ensemble ensemble, Rule rule, std::uint64_t seed,
                     int max_lag, int curves, const std::function<bool()> &stop = nullptr);

} // namespace narrows::lgca::dhumieres
