// The continuum engine's conservation-law scheme against exact solutions (issue 22, acceptance
// 1), for Burgers, each lattice-gas flux of the kmc presets (TASEP, family 1, family 2) and the
// colloid chain: Riemann problems (shock speed against Rankine-Hugoniot within 0.5 %,
// rarefaction fans against the self-similar solution within 1 % in L1), and the order of
// convergence on a smooth solution before the shock forms (L1 against the characteristic
// solution; a second-order scheme must reach 2). Each run takes a fraction of a second.
// The exact solutions of Burgers, TASEP and the colloid chain are closed forms written here
// (issue 33 item 2), independent of the product's Flux and continuum::riemann, so a wrong
// coefficient in the product's flux fails; family 1 and 2 (no closed form) still use
// continuum::riemann with the product's flux, i.e. they test the scheme, not the flux.
#include "narrows/engines/continuum/exact.hpp"
#include "narrows/engines/continuum/flux.hpp"
#include "narrows/engines/continuum/plan.hpp"
#include "narrows/engines/continuum/scheme.hpp"
#include "narrows/engines/continuum/shock.hpp"
#include "narrows/scene/parse.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <optional>
#include <ostream>
#include <string>

using namespace narrows;

namespace {

struct Case {
  const char *name;
  std::string flux; // the flux lines of [continuum]
  double shock_l, shock_r, fan_l, fan_r, mean, amplitude;
};

// Tabatabaei's family 1 and family 2 rates of run/kmc_family1_shock.toml and
// run/kmc_family2_shock.toml; the colloid chain with Tabatabaei (2008) fig 5.1's c, c'.
const Case cases[] = {
    {"burgers", "flux = \"burgers\"\n", 1.0, 0.0, 0.2, 1.0, 0.5, 0.3},
    {"tasep", "flux = \"tasep\"\n", 0.2, 0.7, 0.9, 0.1, 0.5, 0.2},
    {"family1",
     "flux = \"family1\"\nrates = { w42 = 1.0, w73 = 0.6, w53 = 0.4, w75 = 0.3, w86 = 0.5, "
     "w68 = 0.5 }\n",
     0.1, 0.9, 0.9, 0.1, 0.5, 0.2},
    {"family2",
     "flux = \"family2\"\nparameters = { c = 0.5, h1 = 0.15, h2 = 0.1, h3 = 0.9, h4 = 0.5, h5 "
     "= 0.5, h6 = 0.8, r1 = 0.1, r2 = 0.1, r3 = 0.1, r4 = 0.2, r5 = 0.2, r6 = 0.2, r7 = 0.1, "
     "r8 = 0.1, r9 = 0.1 }\n",
     0.2, 0.7, 0.9, 0.1, 0.5, 0.2},
    {"colloid-chain", "flux = \"colloid-chain\"\nc = 5.71\nc_prime = 0.019\n", 0.15, 0.05, 0.05,
     0.15, 0.1, 0.03},
};

// The closed-form flux J, its speed J' and the inverse of J' (the fan's rho = (J')^{-1}(x/t)),
// written out independently of continuum::Flux: Burgers J = u^2/2; TASEP (right hop rate 1)
// J = rho (1 - rho); the colloid chain J = rho (c rho + c' - v_cm) of Tabatabaei (2008) eq 5.3
// with fig 5.1's c = 5.71, c' = 0.019 and v_cm = 0 (the cases above).
struct ClosedForm {
  std::function<double(double)> J, speed, inverse_speed;
};

std::optional<ClosedForm> closed_form(const Case &k) {
  const std::string n = k.name;
  if (n == "burgers")
    return ClosedForm{[](double u) { return 0.5 * u * u; }, [](double u) { return u; },
                      [](double xi) { return xi; }};
  if (n == "tasep")
    return ClosedForm{[](double r) { return r * (1.0 - r); },
                      [](double r) { return 1.0 - 2.0 * r; },
                      [](double xi) { return 0.5 * (1.0 - xi); }};
  if (n == "colloid-chain") {
    const double c = 5.71, cp = 0.019;
    return ClosedForm{[=](double r) { return r * (c * r + cp); },
                      [=](double r) { return 2.0 * c * r + cp; },
                      [=](double xi) { return (xi - cp) / (2.0 * c); }};
  }
  return std::nullopt;
}

// The exact Riemann solution l | r: for a convex or concave J a shock iff the characteristics
// converge (J'(l) > J'(r), Lax), moving at the Rankine-Hugoniot speed (J(l) - J(r)) / (l - r);
// otherwise the fan rho = (J')^{-1}(x/t) between J'(l) and J'(r).
struct Exact {
  bool shock = false;
  double speed = 0.0, fan_lo = 0.0, fan_hi = 0.0;
  std::function<double(double)> density; // of x/t
};

Exact exact_riemann(const Case &k, const continuum::Flux &flux, double l, double r) {
  Exact e;
  if (const auto f = closed_form(k)) {
    e.shock = f->speed(l) > f->speed(r);
    e.speed = (f->J(l) - f->J(r)) / (l - r);
    e.fan_lo = f->speed(l);
    e.fan_hi = f->speed(r);
    const ClosedForm g = *f;
    e.density = [=](double xi) {
      if (e.shock)
        return xi < e.speed ? l : r;
      return xi <= e.fan_lo ? l : xi >= e.fan_hi ? r : g.inverse_speed(xi);
    };
    return e;
  }
  const continuum::Riemann rp = continuum::riemann(flux, l, r);
  e.shock = rp.shock;
  e.speed = rp.speed;
  e.fan_lo = rp.fan_lo;
  e.fan_hi = rp.fan_hi;
  e.density = [&flux, l, r](double xi) { return continuum::riemann_density(flux, l, r, xi); };
  return e;
}

// J' of the case: the closed form when there is one, else the product's.
std::function<double(double)> speed_of(const Case &k, const continuum::Flux &flux) {
  if (const auto f = closed_form(k))
    return f->speed;
  return [&flux](double r) { return flux.speed(r); };
}

// gtest prints the case by its name.
void PrintTo(const Case &k, std::ostream *os) { *os << k.name; }

scene::Continuum load(const Case &k, const std::string &rest) {
  const std::string text = "[run]\nengine = \"continuum\"\n[continuum]\nmodel = "
                           "\"conservation-law\"\n" +
                           k.flux + rest;
  return *scene::parse_scene(text, std::string(k.name) + ".toml").continuum;
}

std::string num(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  std::string s = buf;
  if (s.find_first_of(".e") == std::string::npos)
    s += ".0";
  return s;
}

std::string riemann_text(double l, double r, double position) {
  return "initial = { kind = \"riemann\", left = " + num(l) + ", right = " + num(r) +
         ", position = " + num(position) + " }\n";
}

// Runs the plan of m to its end from u (default: the scene's initial cells), calling
// at(step, u, plan) after every sample.
template <class F> void run(const scene::Continuum &m, F at, std::vector<double> u = {}) {
  const continuum::Plan p = continuum::make_plan(m);
  const continuum::Flux flux(m);
  continuum::Scheme scheme(flux, p.grid, m.diffusion, m.limiter);
  if (u.empty())
    u = continuum::initial_cells(m);
  for (std::int64_t s = 1; s <= p.steps; ++s) {
    scheme.step(u, p.dt);
    if (s % p.per_sample == 0)
      at(s, u, p);
  }
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

class ContinuumRiemann : public ::testing::TestWithParam<Case> {};

// A shock travels 300 cells of 600; its speed is measured between t = T/2 and T (the profile
// has settled into its travelling shape by T/2).
TEST_P(ContinuumRiemann, ShockSpeedIsRankineHugoniot) {
  const Case &k = GetParam();
  const double L = 600.0;
  const scene::Continuum probe = load(k, "length = 600.0\ncells = 600\ntime = 1.0\n" +
                                             riemann_text(k.shock_l, k.shock_r, 300.0));
  const continuum::Flux flux(probe);
  const Exact rp = exact_riemann(k, flux, k.shock_l, k.shock_r);
  ASSERT_TRUE(rp.shock) << k.name;
  const double T = 0.5 * L / std::abs(rp.speed);
  const double x0 = rp.speed > 0.0 ? 0.25 * L : 0.75 * L;
  const scene::Continuum m = load(k, "length = 600.0\ncells = 600\nsamples = 2\ntime = " + num(T) +
                                         "\n" + riemann_text(k.shock_l, k.shock_r, x0));
  const auto t0 = std::chrono::steady_clock::now();
  double x_half = 0.0, x_end = 0.0, t_half = 0.0, t_end = 0.0;
  run(m, [&](std::int64_t s, const std::vector<double> &u, const continuum::Plan &p) {
    const double x = continuum::shock_position(u, p.grid.dx, false);
    const double t = static_cast<double>(s) * p.dt;
    (s == p.steps ? x_end : x_half) = x;
    (s == p.steps ? t_end : t_half) = t;
  });
  const double speed = (x_end - x_half) / (t_end - t_half);
  const double err = (speed - rp.speed) / rp.speed;
  std::printf("[continuum %s] shock %g | %g: speed %.6g, Rankine-Hugoniot %.6g, error %+.2e %% "
              "(600 cells, %.2f s)\n",
              k.name, k.shock_l, k.shock_r, speed, rp.speed, 100.0 * err, seconds_since(t0));
  EXPECT_LT(std::abs(err), 0.005) << k.name;
  // And it is where mass conservation puts it.
  EXPECT_NEAR(x_end, x0 + rp.speed * t_end, 2.0) << k.name;
}

// A fan filling up to 80 % of 600 cells, against the self-similar solution: L1 error over the
// domain relative to |l - r| times the fan width.
TEST_P(ContinuumRiemann, RarefactionFanIsSelfSimilar) {
  const Case &k = GetParam();
  const double L = 600.0;
  const scene::Continuum probe =
      load(k, "length = 600.0\ncells = 600\ntime = 1.0\n" + riemann_text(k.fan_l, k.fan_r, 300.0));
  const continuum::Flux flux(probe);
  const Exact rp = exact_riemann(k, flux, k.fan_l, k.fan_r);
  ASSERT_FALSE(rp.shock) << k.name;
  // The fan and its start x0 fill [0.1 L, 0.9 L].
  const double T = 0.8 * L / (std::max(rp.fan_hi, 0.0) - std::min(rp.fan_lo, 0.0));
  const double x0 = 0.1 * L - std::min(rp.fan_lo, 0.0) * T;
  const scene::Continuum m = load(k, "length = 600.0\ncells = 600\nsamples = 1\ntime = " + num(T) +
                                         "\n" + riemann_text(k.fan_l, k.fan_r, x0));
  const auto t0 = std::chrono::steady_clock::now();
  double rel = 0.0;
  run(m, [&](std::int64_t s, const std::vector<double> &u, const continuum::Plan &p) {
    const double t = static_cast<double>(s) * p.dt;
    double l1 = 0.0;
    for (std::size_t i = 0; i < u.size(); ++i) {
      const double x = (static_cast<double>(i) + 0.5) * p.grid.dx;
      l1 += std::abs(u[i] - rp.density((x - x0) / t)) * p.grid.dx;
    }
    rel = l1 / (std::abs(k.fan_l - k.fan_r) * (rp.fan_hi - rp.fan_lo) * t);
  });
  std::printf("[continuum %s] fan %g | %g (x/t from %.4g to %.4g): L1 error %.4f %% (600 "
              "cells, %.2f s)\n",
              k.name, k.fan_l, k.fan_r, rp.fan_lo, rp.fan_hi, 100.0 * rel, seconds_since(t0));
  EXPECT_LT(rel, 0.01) << k.name;
}

// The characteristic solution rho(x, t) = rho0(x - J'(rho) t) before characteristics cross:
// g(rho) = rho - rho0(x - J'(rho) t) is increasing, bisect it on [lo, hi].
double characteristic(const std::function<double(double)> &speed,
                      const std::function<double(double)> &rho0, double lo, double hi, double x,
                      double t) {
  const auto g = [&](double rho) { return rho - rho0(x - speed(rho) * t); };
  double a = lo, b = hi;
  EXPECT_LE(g(a), 0.0);
  EXPECT_GE(g(b), 0.0);
  for (int it = 0; it < 200 && b - a > 1e-15; ++it) {
    const double m = 0.5 * (a + b);
    (g(m) < 0.0 ? a : b) = m;
  }
  return 0.5 * (a + b);
}

// L1 error of the cell averages u at time t against the exact averages of the characteristic
// solution (3-point Gauss per cell).
double l1_error(const std::function<double(double)> &speed,
                const std::function<double(double)> &rho0, double lo, double hi,
                const std::vector<double> &u, double dx, double t) {
  const double g = std::sqrt(0.6) / 2.0, w[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};
  double l1 = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    const double c = (static_cast<double>(i) + 0.5) * dx;
    double avg = 0.0;
    for (int q = 0; q < 3; ++q)
      avg += w[q] * characteristic(speed, rho0, lo, hi, c + (q - 1) * g * dx, t);
    l1 += std::abs(u[i] - avg) * dx;
  }
  return l1;
}

// Half the time at which the first characteristics of rho0 on [a, b] cross.
double half_breaking_time(const std::function<double(double)> &speed,
                          const std::function<double(double)> &rho0, double a, double b) {
  double steepest = 0.0;
  for (int i = 0; i <= 4000; ++i) {
    const double x = a + (b - a) * i / 4000.0, h = 1e-4;
    steepest = std::max(steepest, -(speed(rho0(x + h)) - speed(rho0(x - h))) / (2 * h));
  }
  return steepest > 0.0 ? 0.5 / steepest : 0.0;
}

// mean + amplitude sin(2 pi x) on a periodic unit interval up to half its breaking time, on
// 200 ... 1600 cells. The TVD limiter flattens the slope at the two smooth extrema, which costs
// a little of the order there (measured 1.98-2.00 from 800 to 1600 cells); a first-order
// scheme gives 1: at least 1.95.
TEST_P(ContinuumRiemann, NearlySecondOrderThroughSmoothExtrema) {
  const Case &k = GetParam();
  const std::string sine =
      "boundary = \"periodic\"\ninitial = { kind = \"sine\", mean = " + num(k.mean) +
      ", amplitude = " + num(k.amplitude) + " }\n";
  const scene::Continuum probe = load(k, "length = 1.0\ncells = 100\ntime = 1.0\n" + sine);
  const continuum::Flux flux(probe);
  const auto rho0 = [&](double x) {
    return k.mean + k.amplitude * std::sin(2.0 * std::numbers::pi * x);
  };
  const auto speed = speed_of(k, flux);
  const double T = half_breaking_time(speed, rho0, 0.0, 1.0);
  ASSERT_GT(T, 0.0);
  const double lo = k.mean - std::abs(k.amplitude), hi = k.mean + std::abs(k.amplitude);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<double> errors;
  std::string line;
  for (int cells : {200, 400, 800, 1600}) {
    const scene::Continuum m = load(k, "length = 1.0\ncells = " + std::to_string(cells) +
                                           "\nsamples = 1\ntime = " + num(T) + "\n" + sine);
    run(m, [&](std::int64_t s, const std::vector<double> &u, const continuum::Plan &p) {
      errors.push_back(l1_error(speed, rho0, lo, hi, u, p.grid.dx, static_cast<double>(s) * p.dt));
    });
    char buf[64];
    std::snprintf(buf, sizeof buf, " %d: %.3e", cells, errors.back());
    line += buf;
  }
  const double order_mid = std::log2(errors[1] / errors[2]);
  const double order = std::log2(errors[2] / errors[3]);
  std::printf("[continuum %s] smooth, t = %.4g (half the breaking time): L1 error%s; order "
              "%.3f (400->800), %.3f (800->1600) (%.2f s)\n",
              k.name, T, line.c_str(), order_mid, order, seconds_since(t0));
  EXPECT_GE(order, 1.95) << k.name;
}

INSTANTIATE_TEST_SUITE_P(Fluxes, ContinuumRiemann, ::testing::ValuesIn(cases),
                         [](const ::testing::TestParamInfo<Case> &info) {
                           std::string n = info.param.name;
                           for (char &ch : n)
                             if (ch == '-')
                               ch = '_';
                           return n;
                         });

} // namespace
