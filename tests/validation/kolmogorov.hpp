// Shared measurement for the viscosity validations: a Kolmogorov flow (a_x = A sin(k y),
// k = 2 pi/L_y) in a periodic box has the steady profile u_x = A/(k^2 nu) sin(k y), so the
// amplitude of the sin(k y) mode of the particle velocities gives nu without walls.
#pragma once

#include "fluid_scene.hpp"
#include "narrows/analysis/fluid_observables.hpp"
#include "narrows/engines/mpcd/simulation.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

namespace narrows::validation {

struct KolmogorovResult {
  double nu, nu_error; // measured, with one standard error from block averages
  double kT;           // mean thermal temperature over the measurement
  int blocks;
};

// Runs `warmup` steps (the flow develops in a few momentum-relaxation times), then samples
// the mode amplitude every `every` steps for `blocks` blocks of `block_steps` steps. Blocks
// must be several relaxation times L^2/(4 pi^2 nu) long to be independent.
inline KolmogorovResult measure_kolmogorov(const scene::Scene &s, int warmup, int blocks,
                                           int block_steps, int every = 5) {
  mpcd::MpcdSimulation sim(s, MPI_COMM_SELF);
  for (int i = 0; i < warmup; ++i)
    sim.advance();
  const double k = 2.0 * std::numbers::pi / s.domain.size[1];
  const double A = s.body_force->amplitude;
  const int d = s.run.dimensions;
  std::vector<double> block_amp;
  double kT_sum = 0.0;
  long kT_samples = 0;
  for (int b = 0; b < blocks; ++b) {
    double amp_sum = 0.0;
    int samples = 0;
    for (int i = 0; i < block_steps; ++i) {
      sim.advance();
      if (i % every != 0)
        continue;
      const auto &f = sim.fluid();
      double proj = 0.0;
      for (std::size_t j = 0; j < f.size(); ++j)
        proj += f.v[0][j] * std::sin(k * f.x[1][j]);
      const double amp = 2.0 * proj / static_cast<double>(f.size());
      amp_sum += amp;
      ++samples;
      // The flow's own kinetic energy, amp^2/2 per particle along x, is not heat.
      kT_sum += analysis::temperature(f, MPI_COMM_SELF) - 0.5 * amp * amp / d;
      ++kT_samples;
    }
    block_amp.push_back(amp_sum / samples);
  }
  double mean = 0.0, var = 0.0;
  for (double a : block_amp)
    mean += a / blocks;
  for (double a : block_amp)
    var += (a - mean) * (a - mean) / (blocks - 1);
  const double amp_err = std::sqrt(var / blocks);
  const double nu = A / (k * k * mean);
  return {nu, nu * amp_err / mean, kT_sum / kT_samples, blocks};
}

inline scene::Scene kolmogorov_scene(int dim, scene::Collision rule, double n, double dt,
                                     double angle_deg, std::array<double, 3> size, double amplitude,
                                     std::uint64_t seed = 7) {
  scene::Scene s = fluid_scene(dim, rule, n, dt, angle_deg, size, seed);
  s.body_force = scene::BodyForce{scene::ForceKind::sine, {0, 0, 0}, amplitude};
  return s;
}

} // namespace narrows::validation
