// The windowed colloid profiles of the segregation observables on synthetic data with known
// answers: the window schedule, the window's density against the whole-run KernelDensity, the
// kernel-weighted velocity of colloids with known v_x(y), Delta of Kanehl (thesis) eq 5.31 for
// known profiles, and the steady-state criterion on synthetic Delta series.
#include "narrows/analysis/kernel_density.hpp"
#include "narrows/analysis/kernel_windows.hpp"
#include "narrows/analysis/segregation_evolution.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

using namespace narrows;

// Windows of 500 steps sampled every 100: from step 0 the samples 100..500 are window 0, which
// closes at 500; from 250 (not a multiple of the cadence) window 0 is (250, 750] (the sample at
// 250 itself too) and closes with the sample at 700.
TEST(WindowSchedule, SplitsTheSamplesIntoConsecutiveWindows) {
  const analysis::WindowSchedule a{0, 500, 100};
  for (std::int64_t t = 100; t <= 2000; t += 100) {
    EXPECT_EQ(a.index(t), (t - 1) / 500) << t;
    EXPECT_EQ(a.closes(t), t % 500 == 0) << t;
  }
  EXPECT_EQ(a.end(0), 500);
  EXPECT_EQ(a.end(3), 2000);
  const analysis::WindowSchedule b{250, 500, 100};
  EXPECT_EQ(b.index(250), 0);
  EXPECT_EQ(b.index(300), 0);
  EXPECT_EQ(b.index(700), 0);
  EXPECT_EQ(b.index(800), 1);
  EXPECT_EQ(b.index(1200), 1);
  EXPECT_EQ(b.index(1300), 2);
  EXPECT_FALSE(b.closes(600));
  EXPECT_TRUE(b.closes(700));
  EXPECT_TRUE(b.closes(1200));
  EXPECT_EQ(b.end(0), 750);
  // Every sample from the start on lies in exactly one window, and each window closes once.
  const analysis::WindowSchedule c{0, 300, 100};
  std::vector<int> closes(10, 0), held(10, 0);
  for (std::int64_t t = 100; t <= 3000; t += 100) {
    ++held[static_cast<std::size_t>(c.index(t))];
    closes[static_cast<std::size_t>(c.index(t))] += c.closes(t) ? 1 : 0;
  }
  for (std::size_t w = 0; w < 10; ++w) {
    EXPECT_EQ(held[w], 3) << w;
    EXPECT_EQ(closes[w], 1) << w;
  }
}

// A window's density is the mean F_k over its samples: a window of the samples 5..9 equals a
// KernelDensity fed the same samples (bitwise: the same sums in the same order), and clear()
// forgets the previous window. The state of an open window restores bitwise.
TEST(KernelWindow, DensityOfAWindowIsTheKdeOfItsSamples) {
  const std::size_t kinds = 2, bins = 40;
  std::mt19937_64 gen(3);
  std::uniform_real_distribution<double> u(0.0, 8.0);
  analysis::KernelWindow win(kinds, 8.0, false, 0.6, bins);
  analysis::KernelDensity kde(kinds, 8.0, false, 0.6, bins, 5, 1);
  std::vector<double> y(7), vx(7, 0.0);
  const std::vector<std::size_t> kind{0, 0, 1, 0, 1, 1, 0};
  std::vector<double> saved;
  for (int t = 0; t < 10; ++t) {
    for (double &v : y)
      v = u(gen);
    if (t == 5) {
      win.clear();
      EXPECT_EQ(win.samples(), 0u);
    }
    win.add(y, vx, kind);
    if (t >= 5)
      kde.add(y, kind);
    if (t == 7)
      saved = win.state();
  }
  EXPECT_EQ(win.samples(), 5u);
  const auto f = win.density(), g = kde.value();
  ASSERT_EQ(f.size(), g.size());
  for (std::size_t i = 0; i < f.size(); ++i)
    EXPECT_EQ(f[i], g[i]) << i;
  analysis::KernelWindow again(kinds, 8.0, false, 0.6, bins);
  ASSERT_TRUE(again.restore(saved));
  EXPECT_EQ(again.samples(), 3u);
  EXPECT_FALSE(again.restore(std::vector<double>(saved.begin(), saved.end() - 1)));
}

// Colloids on a lattice of spacing h/2 (h the bin width) with v_x = y: around every bin centre
// further than eps from the ends of the lattice the colloids lie symmetrically, so the kernel
// mean of v_x is y exactly (to rounding); kind 1 with v_x = -2 everywhere gives -2 wherever its
// weight is positive; bins no colloid of a kind reaches have weight 0 and NaN.
TEST(KernelWindow, VelocityProfileRecoversAKnownVx) {
  const double length = 10.0, eps = 0.4;
  const std::size_t bins = 100;
  const double h = length / bins;
  analysis::KernelWindow win(2, length, false, eps, bins);
  std::vector<double> y, vx;
  std::vector<std::size_t> kind;
  for (int m = 40; m <= 160; ++m) { // y from 2 to 8
    y.push_back(m * h / 2);
    vx.push_back(m * h / 2);
    kind.push_back(0);
  }
  for (int m = 100; m <= 110; ++m) { // kind 1 from 5 to 5.5
    y.push_back(m * h / 2);
    vx.push_back(-2.0);
    kind.push_back(1);
  }
  win.add(y, vx, kind);
  win.add(y, vx, kind); // a second sample changes no mean
  const auto v = win.velocity(), w = win.weight(), yc = win.centres();
  int interior = 0;
  for (std::size_t j = 0; j < bins; ++j) {
    if (yc[j] > 2.0 + eps && yc[j] < 8.0 - eps) {
      EXPECT_NEAR(v[j], yc[j], 1e-12) << yc[j];
      ++interior;
    }
    if (yc[j] < 2.0 - eps || yc[j] > 8.0 + eps) {
      EXPECT_EQ(w[j], 0.0) << yc[j];
      EXPECT_TRUE(std::isnan(v[j])) << yc[j];
    }
    if (w[bins + j] > 0.0) {
      EXPECT_NEAR(v[bins + j], -2.0, 1e-12) << yc[j];
    } else {
      EXPECT_TRUE(std::isnan(v[bins + j])) << yc[j];
    }
  }
  EXPECT_GT(interior, 40);
  EXPECT_GT(w[bins + 52], 0.0); // y = 5.25: inside kind 1's range
}

// Delta (eq 5.31) of known profiles: 0 for the reference itself, 1 for the doubled reference,
// a^2 / 2 for a uniform reference perturbed by a sin(2 pi y / L) (over N equal bins the midpoint
// sum of sin^2 is exactly N / 2), NaN against an empty reference.
TEST(SegregationEvolution, DeltaOfKnownProfiles) {
  const std::size_t n = 64;
  std::vector<double> c0(n), twice(n), uniform(n, 3.0), wave(n), zero(n, 0.0);
  const double a = 0.3;
  for (std::size_t j = 0; j < n; ++j) {
    const double y = (static_cast<double>(j) + 0.5) / static_cast<double>(n);
    c0[j] = 1.0 + std::exp(-20.0 * (y - 0.5) * (y - 0.5));
    twice[j] = 2.0 * c0[j];
    wave[j] = 3.0 * (1.0 + a * std::sin(2.0 * std::numbers::pi * y));
  }
  EXPECT_EQ(analysis::evolution_parameter(c0, c0), 0.0);
  EXPECT_NEAR(analysis::evolution_parameter(twice, c0), 1.0, 1e-14);
  EXPECT_NEAR(analysis::evolution_parameter(wave, uniform), a * a / 2.0, 1e-14);
  EXPECT_TRUE(std::isnan(analysis::evolution_parameter(c0, zero)));
}

// The steady-state criterion: an exact line gives its slope and sigma 0; fewer than 4 values are
// not judged; K = max(4, ceil(n/4)) windows. A rising Delta (slope 0.01 per time unit, noise
// 0.002) is never steady; flat noise is steady in the fraction P(|t_{K-2}| <= 2) of series
// (0.9195 for K = 10: 2000 series, the fraction within 5 of its standard errors, 0.006).
TEST(SegregationEvolution, SteadyCriterionOnSyntheticSeries) {
  std::vector<double> t(40), d(40);
  for (std::size_t i = 0; i < 40; ++i) {
    t[i] = 10.0 * static_cast<double>(i + 1);
    d[i] = 0.5 + 0.003 * t[i];
  }
  const auto line = analysis::steady_check(t, d);
  EXPECT_TRUE(line.judged);
  EXPECT_EQ(line.points, 10u);
  EXPECT_NEAR(line.slope, 0.003, 1e-12);
  EXPECT_LT(line.sigma, 1e-12);
  EXPECT_FALSE(line.steady);
  EXPECT_FALSE(analysis::steady_check(std::span(t).first(3), std::span(d).first(3)).judged);
  EXPECT_EQ(analysis::steady_check(std::span(t).first(9), std::span(d).first(9)).points, 4u);
  std::mt19937_64 gen(11);
  std::normal_distribution<double> noise(0.0, 0.002);
  int steady_rising = 0, steady_flat = 0;
  const int series = 2000;
  for (int s = 0; s < series; ++s) {
    std::vector<double> rising(40), flat(40);
    for (std::size_t i = 0; i < 40; ++i) {
      rising[i] = 0.01 * t[i] + noise(gen);
      flat[i] = 0.4 + noise(gen);
    }
    steady_rising += analysis::steady_check(t, rising).steady ? 1 : 0;
    steady_flat += analysis::steady_check(t, flat).steady ? 1 : 0;
  }
  EXPECT_EQ(steady_rising, 0);
  EXPECT_NEAR(static_cast<double>(steady_flat) / series, 0.9195, 5 * 0.006);
}
