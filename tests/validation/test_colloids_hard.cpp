// Issue 8 acceptance 7 (hard case) and 6 (single file): five colloids started touching the
// walls (centre at r_c from the wall, deep inside the wall potential, ~6000 kT) and each other
// (centre distance sigma_cc = 2 r_c), gravity g = 1.0 along the channel, 10^4 steps. Nothing
// may become non-finite, no fluid particle may leave the channel (InvariantCheck), no colloid
// may leave it, and with sigma_w = 2 r_c no colloid passes another (their cyclic order along x
// is kept). Fluid inside colloids: the wall ejects the colloids at speeds up to ~10 and heats
// the fluid (kT ~ 6 at step 100), so in the first 2000 steps a fluid particle may reach
// phi_cf ~ 50 kT (0.79 sigma_cf); none may pass 0.75 sigma_cf (phi_cf = 105 kT). After step 2000
// (kT back at 1 +- 2 %) none may come closer than 0.85 sigma_cf (phi_cf = 18.5 kT: the expected
// number of such visits over the samples is ~1e-6).
#include "narrows/engine/invariants.hpp"
#include "narrows/engine/mpcd_simulation.hpp"

#include "colloid_scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace narrows;

TEST(ColloidHardCase, TouchingStartUnderStrongGravity) {
  scene::Colloids c;
  c.radius = 2.0;
  c.placement = scene::ColloidPlacement::list;
  c.positions = {{10.0, 2.0, 0}, {14.0, 2.0, 0}, {18.0, 2.0, 0}, {22.0, 8.0, 0}, {26.0, 8.0, 0}};
  c.count = 5;
  c.gravity = {1.0, 0.0, 0.0};
  const scene::Scene s = narrows::testing::srd_colloid_scene(40.0, 10.0, true, 7, c);
  engine::MpcdSimulation sim(s, MPI_COMM_WORLD);
  const engine::InvariantCheck invariants(sim);
  const double L = 40.0, sigma = c.radius;
  const auto &col = sim.colloids();
  std::vector<double> unwrapped(col.x[0]), last(col.x[0]);
  double min_early = 1e9, min_late = 1e9, max_travel = 0.0;
  for (int step = 1; step <= 10000; ++step) {
    sim.advance();
    if (step % 10 != 0)
      continue;
    for (std::size_t a = 0; a < col.size(); ++a) {
      double d = col.x[0][a] - last[a];
      d -= L * std::round(d / L);
      unwrapped[a] += d;
      last[a] = col.x[0][a];
      ASSERT_TRUE(col.x[1][a] > 0.0 && col.x[1][a] < 10.0) << "colloid " << a << " step " << step;
    }
    // Cyclic order: each colloid stays ahead of its predecessor and less than L ahead.
    for (std::size_t a = 0; a < col.size(); ++a) {
      const double gap =
          a + 1 < col.size() ? unwrapped[a + 1] - unwrapped[a] : unwrapped[0] + L - unwrapped[a];
      ASSERT_GT(gap, 0.0) << "colloid order changed at step " << step;
    }
    if (step % 100 != 0)
      continue;
    ASSERT_NO_THROW(invariants.check(sim)) << "step " << step;
    const auto &f = sim.fluid();
    for (std::size_t i = 0; i < f.size(); ++i)
      for (std::size_t a = 0; a < col.size(); ++a) {
        double dx = f.x[0][i] - col.x[0][a];
        dx -= L * std::round(dx / L);
        const double dy = f.x[1][i] - col.x[1][a];
        double &m = step <= 2000 ? min_early : min_late;
        m = std::min(m, std::hypot(dx, dy) / sigma);
      }
  }
  for (std::size_t a = 0; a < col.size(); ++a)
    max_travel = std::max(max_travel, std::abs(unwrapped[a] - c.positions[a][0]));
  std::printf("closest fluid particle at %.4f sigma_cf (steps <= 2000), %.4f sigma_cf (later); "
              "colloids travelled up to %.1f along x\n",
              min_early, min_late, max_travel);
  EXPECT_GT(min_early, 0.75);
  EXPECT_GT(min_late, 0.85);
  EXPECT_GT(max_travel, 0.5 * L); // far enough to have passed each other, had they been able to
}
