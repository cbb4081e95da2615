// Self-diffusion of fluid particles from the mean-square displacement. Displacements are
// accumulated per particle id from minimum-image position changes (|v dt| << L/2).
#pragma once

#include "narrows/engines/mpcd/simulation.hpp"

#include <cmath>
#include <vector>

namespace narrows::validation {

struct DiffusionResult {
  double D, D_error; // from the MSD slope between lag_lo and lag_hi, error over time origins
};

// For `origins` consecutive windows of lag_hi steps, MSD(lag) averaged over all particles;
// D = (MSD(lag_hi) - MSD(lag_lo)) / (2 d (lag_hi - lag_lo) dt) per window; the spread of the
// window values gives the standard error (windows do not overlap, so they are independent
// up to the slow hydrodynamic tail).
inline DiffusionResult measure_diffusion(const scene::Scene &s, int warmup, int origins, int lag_lo,
                                         int lag_hi) {
  mpcd::MpcdSimulation sim(s, MPI_COMM_SELF);
  for (int i = 0; i < warmup; ++i)
    sim.advance();
  const int d = s.run.dimensions;
  const auto &f = sim.fluid();
  const std::size_t n = f.size();
  std::vector<double> prev(n * d), disp(n * d);
  auto snapshot = [&](std::vector<double> &out) {
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < d; ++k)
        out[f.id[i] * d + k] = f.x[k][i];
  };
  std::vector<double> now(n * d), D_window;
  for (int o = 0; o < origins; ++o) {
    std::fill(disp.begin(), disp.end(), 0.0);
    snapshot(prev);
    double msd_lo = 0.0;
    for (int t = 1; t <= lag_hi; ++t) {
      sim.advance();
      snapshot(now);
      double msd = 0.0;
      for (std::size_t j = 0; j < n * d; ++j) {
        const double L = s.domain.size[j % d];
        double dx = now[j] - prev[j];
        dx -= L * std::round(dx / L);
        disp[j] += dx;
        msd += disp[j] * disp[j];
      }
      prev.swap(now);
      if (t == lag_lo)
        msd_lo = msd / n;
      if (t == lag_hi)
        D_window.push_back((msd / n - msd_lo) / (2.0 * d * (lag_hi - lag_lo) * s.fluid.dt));
    }
  }
  double mean = 0.0, var = 0.0;
  for (double x : D_window)
    mean += x / origins;
  for (double x : D_window)
    var += (x - mean) * (x - mean) / (origins - 1);
  return {mean, std::sqrt(var / origins)};
}

} // namespace narrows::validation
