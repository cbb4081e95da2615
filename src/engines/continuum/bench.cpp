// The continuum engine's benchmark (see continuum/bench.hpp).
#include "narrows/engines/continuum/bench.hpp"

#include "narrows/core/timer.hpp"
#include "narrows/engines/continuum/flux.hpp"
#include "narrows/engines/continuum/jamming_model.hpp"
#include "narrows/engines/continuum/jamming_solver.hpp"
#include "narrows/engines/continuum/plan.hpp"
#include "narrows/engines/continuum/scheme.hpp"
#include "narrows/engines/continuum/segregation_model.hpp"
#include "narrows/engines/continuum/segregation_solver.hpp"
#include "narrows/models/three_state/rates.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

namespace narrows::continuum {

namespace {

// Steps for at least a second (and 3 steps); returns the steps and their seconds.
template <class Step> std::int64_t timed(Step step, double &seconds) {
  Stopwatch clock;
  std::int64_t steps = 0;
  while (clock.seconds() < 1.0 || steps < 3) {
    step();
    ++steps;
  }
  seconds = clock.seconds();
  return steps;
}

// One case's line (or JSON object): `what` = "cell" or "point", `size` of them per step.
void report(std::ostream &out, bool json, bool &first, const std::string &name, const char *what,
            double size, double rate, std::int64_t steps, const char *how) {
  char buf[300];
  if (json)
    std::snprintf(buf, sizeof buf,
                  "%s{\"case\": \"%s\", \"%ss\": %.17g, \"%s_steps_per_s\": %.17g}",
                  first ? "" : ", ", name.c_str(), what, size, what, rate);
  else
    std::snprintf(buf, sizeof buf,
                  "continuum %s %.6g %ss: %.3g %s-steps/s on one core (%lld steps, %s)\n",
                  name.c_str(), size, what, rate, what, static_cast<long long>(steps), how);
  out << buf;
  first = false;
}

} // namespace

void run_bench(std::ostream &out, double cells, bool json) {
  struct Case {
    const char *name;
    scene::Continuum model;
  };
  scene::Continuum base;
  base.cells = static_cast<std::int64_t>(cells);
  base.length = 1.0;
  base.boundary = scene::ContinuumBoundary::periodic;
  base.initial = scene::ContinuumInitial::sine;
  base.mean = 0.5;
  base.amplitude = 0.2;
  base.time = 1.0;
  base.samples = 1;
  std::vector<Case> cases{{"burgers", base}, {"family1", base}};
  cases[1].model.flux = scene::ContinuumFlux::family1;
  cases[1].model.lattice_gas.preset = scene::KmcPreset::family1;
  auto &rates = cases[1].model.lattice_gas.rates;
  rates[three_state::pair_code(0, 1) * 9 + three_state::pair_code(1, 0)] = 1.0; // w42: A hops right
  rates[three_state::pair_code(1, 2) * 9 + three_state::pair_code(2, 1)] =
      0.5; // w86, w68: B and vacancy
  rates[three_state::pair_code(2, 1) * 9 + three_state::pair_code(1, 2)] = 0.5;
  if (json)
    out << "{\"continuum\": [";
  bool first = true;
  for (const auto &c : cases) {
    const Plan p = make_plan(c.model);
    const Flux flux(c.model);
    Scheme scheme(flux, p.grid, 0.0, c.model.limiter);
    std::vector<double> u = initial_cells(c.model);
    scheme.step(u, p.dt); // warm-up
    double seconds = 0.0;
    const std::int64_t steps = timed([&] { scheme.step(u, p.dt); }, seconds);
    const double rate = static_cast<double>(steps) * cells / seconds;
    report(out, json, first, c.name, "cell", cells, rate, steps, "SSP-RK2: two flux sweeps each");
  }
  // The jamming model (pseudo-spectral, Strang splitting) on an even number of points, dx = 0.2,
  // unstable flow at phi = 0.75 with a small sine (the state stays smooth for the timing).
  {
    const std::size_t n = std::max<std::size_t>(8, static_cast<std::size_t>(cells) / 2 * 2);
    const JammingModel model(table_6_2(scene::JammingFit::mu_1), 1.0, 1.0);
    const double length = 0.2 * static_cast<double>(n), dt = 0.1 * 0.2 / 2.64;
    std::vector<double> phi(n), v(n);
    for (std::size_t i = 0; i < n; ++i) {
      phi[i] =
          0.75 + 1e-3 * std::sin(2.0 * std::numbers::pi * static_cast<double>(i) * 0.2 / length);
      v[i] = model.vss(phi[i]);
    }
    JammingSolver solver(model, n, length);
    solver.step(phi, v, dt); // warm-up
    double seconds = 0.0;
    const std::int64_t steps = timed([&] { solver.step(phi, v, dt); }, seconds);
    report(out, json, first, "jamming", "point", static_cast<double>(n),
           static_cast<double>(steps) * static_cast<double>(n) / seconds, steps,
           "Strang splitting, IF-RK4: 20 real FFTs of n points each");
  }
  // The segregation model: two kinds (Kanehl (thesis) fig 5.6, 2D, phi = 0.5) on an even number of
  // cells across the channel, from the uniform start at a stable dt.
  {
    const std::size_t n = std::max<std::size_t>(4, static_cast<std::size_t>(cells) / 2 * 2);
    scene::Segregation s;
    s.half_width = 40.0;
    s.centre_speed = 0.274;
    s.kinds = {{2.0, 0.25, 0.00137}, {4.0, 0.25, 0.000973}};
    const SegregationModel model(s);
    SegregationSolver solver(model, n);
    const double h = solver.cell(), dt = 0.4 * h * h;
    std::vector<std::vector<double>> phi{std::vector<double>(n, 0.25),
                                         std::vector<double>(n, 0.25)};
    solver.step(phi, dt); // warm-up
    double seconds = 0.0;
    const std::int64_t steps = timed([&] { solver.step(phi, dt); }, seconds);
    report(out, json, first, "segregation", "cell", static_cast<double>(n),
           static_cast<double>(steps) * static_cast<double>(n) / seconds, steps,
           "two kinds, RK4: four current sweeps each");
  }
  if (json)
    out << "]}\n";
}

} // namespace narrows::continuum
