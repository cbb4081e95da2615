// The kmc engine against the continuum engine (issue 22, acceptance 2): an OPEN three-state
// lattice gas of L = 1000 sites (family 1 and family 2 presets, boundary rates fitted to the
// two fugacities) and the conservation law rho_t + J(rho)_x = 0 with the same flux (the preset's
// eq 2.60 / 2.126, three_state::hydrodynamic_flux) and the same boundary densities held as
// reservoirs.
//
// - Mean density profile: the kmc chain starts with a shock in the middle, runs until the shock
//   has left (warm-up), then the time-averaged charge profile is compared, in blocks of 50 sites
//   at least 100 sites from either end, with the continuum solution of the same Riemann data run
//   to its steady state. The phase (which reservoir's density fills the bulk) is the continuum's
//   answer, not assumed: family 1 ends in the right reservoir's density, family 2 in the left's.
// - Shock: the mean shock displacement since t = 0 of the run/kmc_family*_shock.toml presets at
//   L = 1000 (the engine's maximum-likelihood estimator, whose offset of a site or so at a sharp
//   shock measure drops out of the displacement) against the continuum shock's at the same
//   times, while the shock is far from both ends.
// Errors are standard errors over independent replicas; each block or time is within 3.5 of
// them (16 blocks or 10 times per comparison: a family-wise false alarm rate below 1 %), the
// mean shock speed (slope of the displacement) within 3.
#include "narrows/engines/continuum/flux.hpp"
#include "narrows/engines/continuum/plan.hpp"
#include "narrows/engines/continuum/scheme.hpp"
#include "narrows/engines/continuum/shock.hpp"
#include "narrows/engines/kmc/lattice.hpp"
#include "narrows/models/three_state/preset.hpp"
#include "narrows/models/three_state/shock.hpp"
#include "narrows/scene/parse.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace narrows;

namespace {

scene::Kmc load(const char *name, const std::vector<std::string> &sets) {
  return *scene::load_scene(std::string(NARROWS_SOURCE_DIR) + "/run/" + name, sets).kmc;
}

// The conserved density of a branch: the charge sigma (family 1) or the particle density
// (family 2), what the preset's flux takes.
double density_of(const scene::Kmc &m, const three_state::Branch &b) {
  return m.preset == scene::KmcPreset::family1 ? b.sigma : b.rho;
}

// The conservation law of the kmc model's preset on its lattice (cell i = site i + 1), open,
// reservoirs at the two boundary densities, Riemann data left | right at `site`.
scene::Continuum continuum_of(const scene::Kmc &k, double left, double right, double site,
                              double time, std::int64_t samples) {
  scene::Continuum m;
  m.flux = k.preset == scene::KmcPreset::family1 ? scene::ContinuumFlux::family1
                                                 : scene::ContinuumFlux::family2;
  m.lattice_gas = k;
  m.length = static_cast<double>(k.length);
  m.cells = k.length;
  m.boundary = scene::ContinuumBoundary::open;
  m.reservoirs = {left, right};
  m.initial = scene::ContinuumInitial::riemann;
  m.left = left;
  m.right = right;
  m.position = site;
  m.time = time;
  m.samples = samples;
  return m;
}

struct ContinuumRun {
  std::vector<double> shock;  // shock position at the sample times (and t = 0)
  std::vector<double> change; // max |u(t) - u(t - dt_sample)| at each sample
  std::vector<double> u;      // the cells at the end
};

ContinuumRun run(const scene::Continuum &m) {
  const continuum::Plan p = continuum::make_plan(m);
  const continuum::Flux flux(m);
  continuum::Scheme scheme(flux, p.grid, m.diffusion, m.limiter);
  ContinuumRun out;
  out.u = continuum::initial_cells(m);
  out.shock.push_back(continuum::shock_position(out.u, p.grid.dx, false));
  std::vector<double> before = out.u;
  for (std::int64_t s = 1; s <= p.steps; ++s) {
    scheme.step(out.u, p.dt);
    if (s % p.per_sample == 0) {
      out.shock.push_back(continuum::shock_position(out.u, p.grid.dx, false));
      double d = 0.0;
      for (std::size_t i = 0; i < out.u.size(); ++i)
        d = std::max(d, std::abs(out.u[i] - before[i]));
      out.change.push_back(d);
      before = out.u;
    }
  }
  return out;
}

struct MeanError {
  std::vector<double> mean, error;
};

// Mean and standard error over replicas (rows) of each column.
MeanError over_replicas(const std::vector<std::vector<double>> &rows) {
  const std::size_t R = rows.size(), W = rows[0].size();
  MeanError out{std::vector<double>(W, 0.0), std::vector<double>(W, 0.0)};
  for (const auto &r : rows)
    for (std::size_t i = 0; i < W; ++i)
      out.mean[i] += r[i] / static_cast<double>(R);
  for (const auto &r : rows)
    for (std::size_t i = 0; i < W; ++i)
      out.error[i] += (r[i] - out.mean[i]) * (r[i] - out.mean[i]);
  for (auto &e : out.error)
    e = std::sqrt(e / static_cast<double>(R - 1) / static_cast<double>(R));
  return out;
}

// The steady-state comparison for one model (shock at the middle initially).
void steady_profile(const scene::Kmc &m, std::uint64_t seed) {
  const auto rep = three_state::analyse(m);
  ASSERT_EQ(rep.branches.size(), 2u);
  const double left = density_of(m, rep.branches[0]), right = density_of(m, rep.branches[1]);
  const auto L = static_cast<std::size_t>(m.length);
  const std::size_t block = 50, skip = 100, blocks = (L - 2 * skip) / block;

  // kmc: per replica, the time-averaged charge per site, in blocks.
  std::vector<std::vector<double>> rows;
  for (std::int64_t r = 0; r < m.replicas; ++r) {
    kmc::Lattice lat(m, seed, static_cast<std::uint64_t>(r));
    lat.run_until(m.warmup);
    lat.start_observing(m.time);
    lat.run_until(m.warmup + m.time);
    const auto res = lat.result();
    std::vector<double> v(blocks, 0.0);
    for (std::size_t b = 0; b < blocks; ++b)
      for (std::size_t k = skip + b * block; k < skip + (b + 1) * block; ++k)
        for (int n = 0; n < 3; ++n)
          v[b] += m.charge[n] * res.density[3 * k + n] / static_cast<double>(block);
    rows.push_back(v);
  }
  const MeanError q = over_replicas(rows);

  // Continuum: the same Riemann data, run for four times the shock's crossing time.
  const double cross =
      static_cast<double>(L) /
      std::abs((rep.branches[0].current - rep.branches[1].current) / (left - right));
  const auto c =
      run(continuum_of(m, left, right, static_cast<double>(m.shock_site), 4.0 * cross, 40));
  std::printf("  reservoirs %.5f | %.5f; continuum after t = %.4g: last change per sample %.2g\n",
              left, right, 4.0 * cross, c.change.back());
  ASSERT_LT(c.change.back(), 1e-9) << "the continuum run has not reached its steady state";

  double chi2 = 0.0, worst = 0.0;
  for (std::size_t b = 0; b < blocks; ++b) {
    double u = 0.0;
    for (std::size_t k = skip + b * block; k < skip + (b + 1) * block; ++k)
      u += c.u[k] / static_cast<double>(block);
    const double z = (q.mean[b] - u) / q.error[b];
    chi2 += z * z;
    worst = std::max(worst, std::abs(z));
    std::printf("  sites %4zu-%4zu: kmc %.5f +- %.2g, continuum %.5f, z = %+.2f\n",
                skip + b * block + 1, skip + (b + 1) * block, q.mean[b], q.error[b], u, z);
    EXPECT_LT(std::abs(z), 3.5) << "block " << b;
  }
  std::printf("  %zu blocks: chi^2 / dof = %.2f, largest |z| = %.2f\n", blocks,
              chi2 / static_cast<double>(blocks), worst);
}

// The mean shock position against time for a shock preset.
void shock_against_time(const scene::Kmc &m, std::uint64_t seed) {
  const auto rep = three_state::analyse(m);
  const double left = density_of(m, rep.branches[0]), right = density_of(m, rep.branches[1]);
  const auto samples = static_cast<std::size_t>(m.samples);
  std::vector<std::vector<double>> rows;
  for (std::int64_t r = 0; r < m.replicas; ++r) {
    kmc::Lattice lat(m, seed, static_cast<std::uint64_t>(r));
    std::vector<double> x;
    for (std::size_t i = 0; i <= samples; ++i) {
      lat.run_until(m.time * static_cast<double>(i) / static_cast<double>(samples));
      x.push_back(static_cast<double>(
          three_state::shock_position(lat.state(), m.initial, m.initial_right)));
    }
    for (std::size_t i = samples; i > 0; --i)
      x[i] -= x[0]; // the displacement: the estimator's offset at a sharp shock drops out
    rows.push_back(x);
  }
  const MeanError x = over_replicas(rows);
  const auto c = run(continuum_of(m, left, right, static_cast<double>(m.shock_site), m.time,
                                  static_cast<std::int64_t>(samples)));
  ASSERT_EQ(c.shock.size(), samples + 1);
  const double rh = (rep.branches[0].current - rep.branches[1].current) / (left - right);
  std::printf("  shock %.5f | %.5f at site %lld: Rankine-Hugoniot speed %.5f, seed v_s %.5f "
              "(to the right); at t = 0 kmc %.2f +- %.2f, continuum %.2f\n",
              left, right, static_cast<long long>(m.shock_site), rh, -rep.v_s, x.mean[0],
              x.error[0], c.shock[0]);
  double chi2 = 0.0;
  for (std::size_t i = 1; i <= samples; ++i) {
    const double dc = c.shock[i] - c.shock[0];
    const double z = (x.mean[i] - dc) / x.error[i];
    chi2 += z * z;
    std::printf("  t = %7.1f: displacement kmc %8.2f +- %.2f, continuum %8.2f, z = %+.2f\n",
                m.time * static_cast<double>(i) / static_cast<double>(samples), x.mean[i],
                x.error[i], dc, z);
    EXPECT_LT(std::abs(z), 3.5) << "sample " << i;
  }
  std::printf("  %zu times: chi^2 / dof = %.2f (neighbouring times are correlated)\n", samples,
              chi2 / static_cast<double>(samples));
  // The mean speed: least-squares slope of the displacement through the origin, per replica
  // (mean and standard error over replicas) and of the continuum's.
  const auto slope = [&](const std::vector<double> &d) {
    double num = 0.0, den = 0.0;
    for (std::size_t i = 1; i <= samples; ++i) {
      const double t = m.time * static_cast<double>(i) / static_cast<double>(samples);
      num += t * d[i];
      den += t * t;
    }
    return num / den;
  };
  std::vector<std::vector<double>> speeds;
  for (const auto &r : rows)
    speeds.push_back({slope(r)});
  const MeanError v = over_replicas(speeds);
  std::vector<double> dc(samples + 1);
  for (std::size_t i = 0; i <= samples; ++i)
    dc[i] = c.shock[i] - c.shock[0];
  const double vc = slope(dc);
  std::printf("  speed: kmc %.5f +- %.2g, continuum %.5f (%+.2f errors, %+.2f %%)\n", v.mean[0],
              v.error[0], vc, (v.mean[0] - vc) / v.error[0], 100.0 * (v.mean[0] - vc) / vc);
  EXPECT_LT(std::abs(v.mean[0] - vc), 3.0 * v.error[0]);
  // Far from both ends all the time: the comparison is of the bulk shock.
  EXPECT_GT(*std::min_element(c.shock.begin(), c.shock.end()), 150.0);
  EXPECT_LT(*std::max_element(c.shock.begin(), c.shock.end()),
            static_cast<double>(m.length) - 150.0);
}

} // namespace

// Family 1 with the product-measure rates of run/kmc_family1_product.toml and two fugacities,
// z = 1.5 (sigma = -0.263, J = 0.387) left and z = 0.2 (sigma = 0.774, J = 0.174) right: the
// shock moves left at -0.205 and the right reservoir's density fills the chain.
TEST(KmcAgainstContinuum, Family1SteadyProfile) {
  const auto m =
      load("kmc_family1_product.toml",
           {"kmc.length=1000", "kmc.fugacity=[1.5,0.2]", "kmc.initial={kind=\"shock\",site=500}",
            "kmc.warmup=4000.0", "kmc.time=2000.0", "kmc.replicas=24"});
  steady_profile(m, 31);
}

// Family 2 of run/kmc_family2_shock.toml (z = 0.2 | 1.0, rho = 0.231 | 0.6): the shock moves
// right at 0.135 and the left reservoir's density fills the chain.
TEST(KmcAgainstContinuum, Family2SteadyProfile) {
  const auto m =
      load("kmc_family2_shock.toml", {"kmc.length=1000", "kmc.initial={kind=\"shock\",site=500}",
                                      "kmc.warmup=6000.0", "kmc.time=2000.0", "kmc.replicas=24"});
  steady_profile(m, 32);
}

TEST(KmcAgainstContinuum, Family1ShockPosition) {
  const auto m =
      load("kmc_family1_shock.toml", {"kmc.length=1000", "kmc.initial={kind=\"shock\",site=800}",
                                      "kmc.time=1600.0", "kmc.samples=10", "kmc.replicas=128"});
  shock_against_time(m, 33);
}

TEST(KmcAgainstContinuum, Family2ShockPosition) {
  const auto m =
      load("kmc_family2_shock.toml", {"kmc.length=1000", "kmc.initial={kind=\"shock\",site=200}",
                                      "kmc.time=4000.0", "kmc.samples=10", "kmc.replicas=256"});
  shock_against_time(m, 34);
}
