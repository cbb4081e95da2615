// Shared measurement for the channel validations: walls at y = 0 and y = L_y, force g along
// x; the steady profile v_x = g y (L_y - y)/(2 nu) gives nu from its fitted curvature.
#pragma once

#include "fluid_scene.hpp"
#include "narrows/analysis/fluid_observables.hpp"
#include "narrows/analysis/poiseuille.hpp"
#include "narrows/engines/mpcd/simulation.hpp"

#include <cmath>
#include <vector>

namespace narrows::validation {

struct PoiseuilleResult {
  double nu, nu_error;          // measured, one standard error from block averages
  double slip, slip_error;      // fitted wall velocity / centre velocity
  double v0;                    // fitted centre velocity
  double kT;                    // thermal temperature (flow energy removed)
  std::vector<double> density;  // time-averaged density per bin row, over all blocks
  std::vector<double> velocity; // time-averaged v_x per bin row
  int blocks;
};

inline double mean_of(const std::vector<double> &a) {
  double m = 0.0;
  for (double x : a)
    m += x / static_cast<double>(a.size());
  return m;
}

inline double standard_error(const std::vector<double> &a) {
  const double m = mean_of(a);
  double var = 0.0;
  for (double x : a)
    var += (x - m) * (x - m) / static_cast<double>(a.size() - 1);
  return std::sqrt(var / static_cast<double>(a.size()));
}

// Runs `warmup` steps (several momentum-relaxation times L_y^2/(pi^2 nu)), then fits the
// profile of each of `blocks` blocks of `block_steps` steps (sampled every `every` steps).
inline PoiseuilleResult measure_poiseuille(const scene::Scene &s, int warmup, int blocks,
                                           int block_steps, int every = 2) {
  mpcd::MpcdSimulation sim(s, MPI_COMM_SELF);
  for (int i = 0; i < warmup; ++i)
    sim.advance();
  const double g = s.body_force->value[0];
  const double L = s.domain.size[1];
  const int d = s.run.dimensions;
  analysis::ProfileAccumulator acc(sim.box());
  std::vector<double> curvature, slip, centre;
  std::vector<double> density(acc.bin_centres().size(), 0.0), velocity(density.size(), 0.0);
  double kT_sum = 0.0;
  long kT_samples = 0;
  for (int b = 0; b < blocks; ++b) {
    for (int i = 0; i < block_steps; ++i) {
      sim.advance();
      if (i % every != 0)
        continue;
      acc.add(sim.fluid());
      if (i % (10 * every) == 0) {
        kT_sum += analysis::temperature(sim.fluid(), MPI_COMM_SELF);
        ++kT_samples;
      }
    }
    std::vector<double> v, rho;
    acc.finish(MPI_COMM_SELF, v, rho);
    const auto fit = analysis::fit_poiseuille(acc.bin_centres(), v, d, acc.bin_width(), L, g);
    curvature.push_back(g / (2.0 * fit.nu));
    slip.push_back(fit.wall_velocity);
    centre.push_back(fit.centre_velocity);
    for (std::size_t k = 0; k < rho.size(); ++k) {
      density[k] += rho[k] / blocks;
      velocity[k] += v[k * d] / blocks;
    }
  }
  PoiseuilleResult r;
  const double a = mean_of(curvature);
  r.nu = g / (2.0 * a);
  r.nu_error = r.nu * standard_error(curvature) / a;
  r.v0 = mean_of(centre);
  r.slip = mean_of(slip) / r.v0;
  r.slip_error = standard_error(slip) / r.v0;
  // The flow's kinetic energy per particle, (8/15) v0^2 for a parabola, is not heat.
  r.kT = kT_sum / kT_samples - 8.0 / 15.0 * r.v0 * r.v0 / d;
  r.density = density;
  r.velocity = velocity;
  r.blocks = blocks;
  return r;
}

inline scene::Scene channel_scene(int dim, scene::Collision rule, double n, double dt,
                                  double angle_deg, std::array<double, 3> size, double g,
                                  std::uint64_t seed = 11) {
  scene::Scene s = fluid_scene(dim, rule, n, dt, angle_deg, size, seed);
  s.body_force = scene::BodyForce{scene::ForceKind::constant, {g, 0, 0}, 0.0};
  s.walls = scene::Walls{};
  return s;
}

} // namespace narrows::validation
