// Kinematic viscosity of the FHP models from the decay of a shear wave u_x = A sin(k y),
// A(t) = A(0) exp(-nu k^2 t), k = 2 pi / (size_y sqrt(3)/2), against the Boltzmann formulas of
// PHYSICS.md. The fit is a straight line through ln of the seed-averaged amplitude over a
// window that starts after the initial transient (a few mean free times) and ends when the
// Boltzmann estimate of A has fallen by 1/e; the error is the jackknife over independent seeds.
//
// What the measurements show (lattice 524288 sites, 16 seeds, A = 0.05; see the report in the
// commit that added this file):
// - the measurement itself: a mean-field (lattice Boltzmann equation) run of the same tables,
//   geometry, initial state and fit gives the closed forms within 0.7 % (L_y = 64 rows), so
//   k, the row spacing sqrt(3)/2, amplitude and window are not the cause of deviations;
// - FHP-III at d = 1/2, where the long-time tail of the stress correlation vanishes (the
//   Galilean factor g is zero), agrees with Boltzmann within 1 % at size_y = 32, 64, 128;
// - away from d = 1/2 the FHP-III viscosity grows with size_y like ln L_y (d = 0.3: +11.7,
//   +15.1, +19.9, +23.9 % at 32, 64, 128, 256 rows): the 2D long-time tail, no k -> 0 limit;
// - FHP-II and the 6-bit saturated model at d = 1/2 hardly depend on size_y but differ from
//   Boltzmann (+11 %, -4 %), FHP-I by +6 % (d = 1/2) and +2 to +4.5 % (d = 0.2 to 0.4, growing
//   with size_y); an independent numpy implementation of FHP-II gives the same +11 %:
//   correlations the Boltzmann approximation leaves out. The half-filling values are checked
//   here against the measured values with other seeds, not against the formulas.
#include "narrows/engines/lgca/fhp_lattice.hpp"
#include "narrows/engines/lgca/fhp_observables.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

using namespace narrows::lgca;

namespace {

struct Measure {
  double nu = 0.0, error = 0.0, theory = 0.0;
};

struct WaveSetup {
  FhpModel model;
  double density;
  int size_x, size_y;
  double amplitude = 0.05;
  int seeds = 16;
  std::uint64_t seed_base = 1000; // run.seed of the first run
  double t_first = 20.0;          // steps skipped (transient)
  double decay_last = 1.0;        // fit until A has fallen by exp(-decay_last) (Boltzmann estimate)
};

// Least-squares slope of ln a over [first, last).
double slope(const std::vector<double> &a, int first, int last) {
  double st = 0, sy = 0, stt = 0, sty = 0;
  const double n = last - first;
  for (int t = first; t < last; ++t) {
    const double y = std::log(a[t]);
    st += t;
    sy += y;
    stt += double(t) * t;
    sty += t * y;
  }
  return (n * sty - st * sy) / (n * stt - st * st);
}

Measure measure(const WaveSetup &s) {
  const double k = 2.0 * M_PI / (s.size_y * std::sqrt(3.0) / 2.0);
  const double nu0 = boltzmann_viscosity(s.model, s.density);
  const int last = static_cast<int>(s.decay_last / (nu0 * k * k));
  const int first = static_cast<int>(s.t_first);
  std::vector<std::vector<double>> runs;
  for (int seed = 0; seed < s.seeds; ++seed) {
    FhpParams p;
    p.model = s.model;
    p.size_x = s.size_x;
    p.size_y = s.size_y;
    p.seed = s.seed_base + static_cast<std::uint64_t>(seed);
    FhpLattice l(p, MPI_COMM_SELF);
    l.initialise(s.density, s.amplitude);
    std::vector<double> a{shear_wave_amplitude(l)};
    for (int t = 1; t <= last; ++t) {
      l.step();
      a.push_back(shear_wave_amplitude(l));
    }
    runs.push_back(a);
  }
  const auto fit_without = [&](int skip) {
    std::vector<double> mean(runs[0].size(), 0.0);
    int n = 0;
    for (int r = 0; r < static_cast<int>(runs.size()); ++r)
      if (r != skip) {
        ++n;
        for (std::size_t t = 0; t < mean.size(); ++t)
          mean[t] += runs[r][t];
      }
    for (auto &m : mean)
      m /= n;
    return -slope(mean, first, last + 1) / (k * k);
  };
  Measure m;
  m.theory = nu0;
  m.nu = fit_without(-1);
  const int R = static_cast<int>(runs.size());
  double jm = 0, jv = 0;
  std::vector<double> j(R);
  for (int r = 0; r < R; ++r)
    jm += (j[r] = fit_without(r)) / R;
  for (int r = 0; r < R; ++r)
    jv += (j[r] - jm) * (j[r] - jm);
  m.error = std::sqrt((R - 1.0) / R * jv);
  std::printf("%s d = %.2f, %d x %d, A = %.3g, %d seeds, fit steps %d..%d: nu = %.5f +- %.5f, "
              "Boltzmann %.5f, deviation %+.2f +- %.2f %%\n",
              to_string(s.model), s.density, s.size_x, s.size_y, s.amplitude, s.seeds, first, last,
              m.nu, m.error, nu0, 100.0 * (m.nu / nu0 - 1.0), 100.0 * m.error / nu0);
  return m;
}

} // namespace

// FHP-III at half filling: the Boltzmann viscosity 0.075, within 3 %.
TEST(FhpViscosity, FhpIIIHalfFillingIsBoltzmann) {
  const Measure m = measure({FhpModel::fhp_iii, 0.5, 8192, 64});
  EXPECT_LT(m.error, 0.01 * m.theory);
  EXPECT_NEAR(m.nu, m.theory, 0.03 * m.theory);
}

// A regression test, not a validation: FHP-I, FHP-II and the saturated model at half filling
// have no theory to compare with (the Boltzmann formulas leave out correlations that move them
// by +6, +11 and -4 %, see the top of the file; only FHP-II has an independent implementation,
// numpy, which agrees with its +11 %). The reference values are this code's own earlier
// measurement (size_y 64; 16 seeds of 8192 x 64, seeds 1000..1015), so the test sees a change
// of the models, not an error in them. Tolerance 4 combined standard errors.
TEST(FhpViscosity, HalfFillingRegressionAgainstOwnEarlierRun) {
  struct Ref {
    FhpModel model;
    double nu, error;
  };
  for (const Ref r : {Ref{FhpModel::fhp_i, 1.2761, 0.0096}, Ref{FhpModel::fhp_ii, 0.7500, 0.0043},
                      Ref{FhpModel::fhp_saturated, 0.09216, 0.00076}}) {
    WaveSetup s{r.model, 0.5, 8192, 64};
    s.t_first = r.model == FhpModel::fhp_saturated ? 20 : 10;
    s.seed_base = 5000; // other seeds than the reference's (1000..1015)
    const Measure m = measure(s);
    EXPECT_NEAR(m.nu, r.nu, 4.0 * std::hypot(m.error, r.error)) << to_string(r.model);
  }
}

// A sweep by hand: NARROWS_FHP_SWEEP="model d X Y A seeds t0 decay" ./validation_tests
// --gtest_also_run_disabled_tests --gtest_filter='*Sweep*'
TEST(FhpViscosity, DISABLED_Sweep) {
  const char *env = std::getenv("NARROWS_FHP_SWEEP");
  if (env == nullptr)
    GTEST_SKIP();
  int model = 0;
  WaveSetup s{FhpModel::fhp_i, 0.3, 1024, 64};
  std::sscanf(env, "%d %lf %d %d %lf %d %lf %lf", &model, &s.density, &s.size_x, &s.size_y,
              &s.amplitude, &s.seeds, &s.t_first, &s.decay_last);
  s.model = static_cast<FhpModel>(model);
  measure(s);
}
