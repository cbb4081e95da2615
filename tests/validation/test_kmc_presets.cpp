// Families 1 and 2 of Tabatabaei (2008) ch.2 in the kmc engine (issue 7, acceptance 2 and 3), run
// from the scenes in run/: on the product-measure manifold the current, the density relation and
// the vanishing nearest-neighbour correlations; on the shock manifold the shock drift and
// diffusion. Errors are standard errors over independent replicas; each comparison is within
// 3 of them, or 4 where nine correlated comparisons are made at once.
#include "narrows/engines/kmc/driver.hpp"
#include "narrows/engines/kmc/lattice.hpp"
#include "narrows/models/three_state/preset.hpp"
#include "narrows/scene/parse.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <numeric>

using namespace narrows;

namespace {

scene::Kmc load(const char *name, const std::vector<std::string> &sets = {}) {
  return *scene::load_scene(std::string(NARROWS_SOURCE_DIR) + "/run/" + name, sets).kmc;
}

// Jackknife mean and standard error of f(per-replica averages) over replicas.
struct Estimate {
  double value = 0.0, error = 0.0;
};
Estimate jackknife(const std::vector<std::vector<double>> &reps,
                   const std::function<double(const std::vector<double> &)> &f) {
  const std::size_t R = reps.size(), W = reps[0].size();
  std::vector<double> sum(W, 0.0);
  for (const auto &r : reps)
    for (std::size_t i = 0; i < W; ++i)
      sum[i] += r[i];
  std::vector<double> all(W);
  for (std::size_t i = 0; i < W; ++i)
    all[i] = sum[i] / static_cast<double>(R);
  std::vector<double> loo(R), m(W);
  for (std::size_t j = 0; j < R; ++j) {
    for (std::size_t i = 0; i < W; ++i)
      m[i] = (sum[i] - reps[j][i]) / static_cast<double>(R - 1);
    loo[j] = f(m);
  }
  const double mean = std::accumulate(loo.begin(), loo.end(), 0.0) / static_cast<double>(R);
  double var = 0.0;
  for (double x : loo)
    var += (x - mean) * (x - mean);
  return {f(all), std::sqrt(var * static_cast<double>(R - 1) / static_cast<double>(R))};
}

// Per replica, averaged over the bulk sites/bonds [skip, L - skip): P(n) for n = 0..2,
// P(pair code) for the 9 codes, and the mean current.
std::vector<std::vector<double>> replica_averages(const scene::Kmc &m, std::uint64_t seed,
                                                  std::size_t skip) {
  std::vector<std::vector<double>> out;
  kmc::LatticeOptions lo;
  lo.pair_histogram = true;
  const std::size_t L = static_cast<std::size_t>(m.length);
  for (std::int64_t r = 0; r < m.replicas; ++r) {
    kmc::Lattice lat(m, seed, static_cast<std::uint64_t>(r), lo);
    lat.run_until(m.warmup);
    lat.start_observing(m.time);
    lat.run_until(m.warmup + m.time);
    const auto res = lat.result();
    std::vector<double> v(13, 0.0);
    const double sites = static_cast<double>(L - 2 * skip);
    for (std::size_t k = skip; k < L - skip; ++k)
      for (int n = 0; n < 3; ++n)
        v[n] += res.density[3 * k + n] / sites;
    for (std::size_t k = skip; k < L - skip; ++k)
      for (int c = 0; c < 9; ++c)
        v[3 + c] += res.pair[9 * k + c] / sites;
    v[12] = res.mean_current;
    out.push_back(v);
  }
  return out;
}

} // namespace

// Acceptance 2: family 1 on the product-measure manifold (eq 2.36 holds), open chain whose
// ends are made to fit the fugacity, so the stationary state is the product measure exactly.
TEST(KmcFamily1, ProductMeasureCurrentDensityRelationAndNoCorrelations) {
  const scene::Kmc m = load("kmc_family1_product.toml");
  const auto rep = three_state::analyse(m);
  ASSERT_TRUE(rep.warnings.empty()) << rep.warnings[0];
  const three_state::Branch &b = rep.branches.at(0);
  const auto reps = replica_averages(m, 21, 10);

  const Estimate j = jackknife(reps, [](const std::vector<double> &v) { return v[12]; });
  std::printf("  current %.5f +- %.2g, eq 2.48: %.5f\n", j.value, j.error, b.current);
  EXPECT_LT(std::abs(j.value - b.current), 3.0 * j.error);

  // eq 2.59: rho^2 - sigma^2 = 4 r (1 - rho)^2 with rho = P(A) + P(B), sigma = P(A) - P(B).
  const double r = rep.ratio;
  const Estimate rel = jackknife(reps, [r](const std::vector<double> &v) {
    const double rho = v[0] + v[2], sigma = v[0] - v[2];
    return rho * rho - sigma * sigma - 4.0 * r * (1.0 - rho) * (1.0 - rho);
  });
  const Estimate sig = jackknife(reps, [](const std::vector<double> &v) { return v[0] - v[2]; });
  std::printf("  sigma %.5f +- %.2g (eq 2.27: %.5f); eq 2.59 remainder %.2g +- %.2g\n", sig.value,
              sig.error, b.sigma, rel.value, rel.error);
  EXPECT_LT(std::abs(sig.value - b.sigma), 3.0 * sig.error);
  EXPECT_LT(std::abs(rel.value), 3.0 * rel.error);

  // Nearest-neighbour connected correlations P(a, b) - P(a) P(b), bulk average.
  for (int c = 0; c < 9; ++c) {
    const Estimate corr = jackknife(
        reps, [c](const std::vector<double> &v) { return v[3 + c] - v[c / 3] * v[c % 3]; });
    std::printf("  pair %d%d: connected correlation %+.2g +- %.2g\n", c / 3, c % 3, corr.value,
                corr.error);
    EXPECT_LT(std::abs(corr.value), 4.0 * corr.error) << "pair " << c / 3 << c % 3;
  }
}

// Acceptance 3: family 2 current eq 2.126 (and 2.128 on the shock manifold), product measure
// of each of the two fugacities of the shock scene.
TEST(KmcFamily2, ProductMeasureCurrent) {
  for (const char *z : {"0.2", "1.0"}) {
    scene::Kmc m =
        load("kmc_family2_shock.toml",
             {std::string("kmc.fugacity=") + z, "kmc.initial={kind=\"product\"}", "kmc.samples=0",
              "kmc.length=200", "kmc.time=2000.0", "kmc.warmup=50.0", "kmc.replicas=16"});
    const auto rep = three_state::analyse(m);
    ASSERT_TRUE(rep.warnings.empty()) << rep.warnings[0];
    const three_state::Branch &b = rep.branches.at(0);
    const auto s = kmc::run_replicas(m, 5, MPI_COMM_WORLD);
    // eq 2.128 with p = 1, q = 0.2 (the scene's shock manifold)
    const double j128 = (1.0 - 0.2) * b.rho * (1.0 - b.rho);
    std::printf("  z = %s: current %.5f +- %.2g, eq 2.126: %.5f, eq 2.128: %.5f\n", z,
                s.mean_current, s.mean_current_error, b.current, j128);
    EXPECT_NEAR(b.current, j128, 1e-12);
    EXPECT_LT(std::abs(s.mean_current - b.current), 3.0 * s.mean_current_error);
  }
}

namespace {

// Drift to the right and diffusion of the shock from the first and the last sample; the
// errors are those of the mean and of the variance over replicas.
void expect_shock(const char *scene_name, std::uint64_t seed, std::int64_t replicas) {
  const scene::Kmc m = load(scene_name, {"kmc.replicas=" + std::to_string(replicas)});
  const auto rep = three_state::analyse(m);
  ASSERT_TRUE(rep.warnings.empty()) << rep.warnings[0];
  ASSERT_TRUE(rep.shock);
  const auto s = kmc::run_replicas(m, seed, MPI_COMM_WORLD);
  const std::size_t n = s.shock_time.size() - 1;
  const double T = s.shock_time[n];
  const double v = (s.shock_mean[n] - s.shock_mean[0]) / T;
  const double v_err = std::hypot(s.shock_mean_error[n], s.shock_mean_error[0]) / T;
  const double D = (s.shock_var[n] - s.shock_var[0]) / (2.0 * T);
  const double D_err = std::hypot(s.shock_var_error[n], s.shock_var_error[0]) / (2.0 * T);
  std::printf("  %s: velocity %.5f +- %.2g (theory %.5f), D %.5f +- %.2g (theory %.5f), "
              "%lld replicas, %.2f s\n",
              scene_name, v, v_err, -rep.v_s, D, D_err, rep.d_s, static_cast<long long>(replicas),
              s.seconds);
  EXPECT_LT(std::abs(v + rep.v_s), 3.0 * v_err);
  EXPECT_LT(std::abs(D - rep.d_s), 3.0 * D_err);
}

} // namespace

// Acceptance 3: on the shock manifold (eq 2.109-2.111) the shock is a random walk with v_s and
// D_s of eq 2.115-2.116.
TEST(KmcFamily2, ShockDriftAndDiffusion) { expect_shock("kmc_family2_shock.toml", 5, 800); }

// Acceptance 3: family 1 with w24 = 0 (eq 2.72-2.76): v_s = 2 D_s = w42 rho_1^A.
TEST(KmcFamily1, SpecialCaseShockMovesLeftWithVEqualTwoD) {
  const scene::Kmc m = load("kmc_family1_shock.toml");
  const auto rep = three_state::analyse(m);
  EXPECT_NEAR(rep.v_s, 2.0 * rep.d_s, 1e-12);
  EXPECT_NEAR(rep.v_s, 1.0 * rep.branches.at(0).rho_a, 1e-12); // w42 = 1
  expect_shock("kmc_family1_shock.toml", 9, 800);
}
