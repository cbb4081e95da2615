// Two colloid kinds in a periodic SRD box (MD coupling): each kind's VACF at lag 0 is its
// equipartition value <|v|^2> = d kT / M_k, with the fluid temperature kT measured over the same
// samples, for a density-matched kind (M = n pi r^2) and one of given mass. This checks the
// kinds end to end (radii and masses per kind from the scene, ids kind by kind, the per-kind
// averages of the estimator on real dynamics). Tolerance: 4 of the reported errors (spread of
// 10 block averages), each asserted under 3 % of the value, so nothing more than 12 % off
// passes and a kind's mass wrong by 20 % (<v^2> off by 17 %) or a mixed-up kind (the two differ
// by a factor 2.8) fails. Eight colloids of each kind make the errors 1.5-2.5 % (measured 1.8 %
// and 2.2 %; with 3 heavy colloids kind 1's was 2.6 %); a block error of 9 degrees of freedom
// exceeds 3 % with a true 2 % with probability P(chi2_9 > 20.25) = 1.6 %, of 1.6 % 2e-4.
#include "narrows/analysis/colloid_time_correlations.hpp"
#include "narrows/analysis/fluid_observables.hpp"
#include "narrows/engines/mpcd/simulation.hpp"

#include "colloid_scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

using namespace narrows;

TEST(ColloidKinds, EachKindHasItsEquipartitionVelocity) {
  scene::Colloids c;
  c.kinds = {{1.5, 0.0, 8}, {2.5, 200.0, 8}};
  c.count = 16;
  c.radius = 2.5;
  c.placement = scene::ColloidPlacement::random;
  const scene::Scene s = narrows::testing::srd_colloid_scene(32.0, 32.0, false, 9, c);
  mpcd::MpcdSimulation sim(s, MPI_COMM_WORLD);
  const int warmup = 500, steps = 6000, every = 2;
  std::vector<std::size_t> kind(16);
  for (std::uint64_t id = 0; id < 16; ++id)
    kind[id] = s.colloids->kind_of(id);
  analysis::ColloidTimeCorrelations stats(kind, 2, 2, 0, every * s.fluid.dt,
                                          (steps - warmup) / every);
  double kT = 0.0;
  int temperatures = 0;
  for (int step = 1; step <= steps; ++step) {
    sim.advance();
    if (step > warmup && step % every == 0) {
      stats.add(sim.gather_colloids(), {32.0, 32.0, 0.0});
      if (step % 100 == 0) {
        kT += analysis::temperature(sim.fluid(), MPI_COMM_WORLD);
        ++temperatures;
      }
    }
  }
  kT /= temperatures;
  const auto vacf = stats.vacf();
  const double mass[2] = {10.0 * std::numbers::pi * 1.5 * 1.5, 200.0};
  for (int k = 0; k < 2; ++k) {
    const double expected = 2.0 * kT / mass[k];
    const double v2 = vacf.by_kind[k], err = vacf.error_by_kind[k];
    std::printf("kind %d: <v^2> = %.5g +- %.2g, 2 kT / M = %.5g (kT = %.4f)\n", k, v2, err,
                expected, kT);
    EXPECT_LT(err, 0.03 * expected) << "kind " << k;
    EXPECT_NEAR(v2, expected, 4.0 * err) << "kind " << k;
  }
}
