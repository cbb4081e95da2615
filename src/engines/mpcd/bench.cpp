// Benchmarks: MPCD particle-steps/s on one core and the STREAM-triad bandwidth bound.
#include "narrows/engines/mpcd/bench.hpp"

#include "narrows/core/error.hpp"
#include "narrows/core/timer.hpp"
#include "narrows/engines/mpcd/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace narrows::mpcd {

namespace {

// Best-of-5 triad a = b + s c over arrays far larger than the caches; bytes moved counted as
// STREAM does (two reads, one write).
double triad_bandwidth() {
  const std::size_t n = std::size_t(1) << 25; // 3 x 256 MiB
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  double best = 1e30;
  for (int rep = 0; rep < 5; ++rep) {
    Stopwatch t;
    const double s = 3.0 + rep;
    for (std::size_t i = 0; i < n; ++i)
      a[i] = b[i] + s * c[i];
    best = std::min(best, t.seconds());
  }
  volatile double sink = a[n / 2];
  (void)sink;
  return 3.0 * 8.0 * static_cast<double>(n) / best;
}

struct Case {
  std::string name;
  int dim;
  scene::Collision rule;
  double bytes_per_particle_step; // streamed by the kernels, counted from their loops
};

struct Result {
  double rate, bandwidth_ratio, particles;
};

Result time_case(const Case &c, const BenchOptions &o, double triad) {
  scene::Scene s;
  s.file = "(bench)";
  s.run.dimensions = c.dim;
  s.run.seed = 1;
  s.fluid.collision = c.rule;
  s.fluid.density = 10.0;
  s.fluid.dt = 1.0;
  s.fluid.angle_deg = 130.0;
  const double cells = o.particles / s.fluid.density;
  if (c.dim == 2) {
    const double ly = std::round(std::sqrt(cells / 4.0));
    s.domain.size = {std::ceil(cells / ly), ly, 0.0};
  } else {
    const double side = std::round(std::cbrt(cells / 2.0));
    s.domain.size = {std::ceil(cells / (side * side)), side, side};
  }
  MpcdSimulation sim(s, MPI_COMM_SELF);
  for (int i = 0; i < 20; ++i) // warm-up: reach the sorted steady state
    sim.advance();
  Stopwatch t;
  for (int i = 0; i < o.steps; ++i)
    sim.advance();
  const double sec = t.seconds();
  const double n = static_cast<double>(sim.fluid().size());
  const double rate = n * o.steps / sec;
  return {rate, rate * c.bytes_per_particle_step / triad, n};
}

} // namespace

void run_bench(const BenchOptions &o, std::ostream &out) {
  // Bytes per particle-step: stream reads x, v and writes x per axis (24 d); binning reads
  // x, v (16 d) and writes the cell (4); the collision reads the cell (4) and v, writes v
  // (16 d); the sort every 20 steps moves every array twice (~ (32 d + 24) / 20 * 2). AT
  // writes and reads its noise (2 x 8 d); AT+a reads positions and velocities once more for
  // its angular-momentum sums (16 d). The model is fixed per case, so its ratio to the triad
  // bound is proportional to the rate whatever the kernels' own traffic is.
  auto bytes = [](int d) { return 24.0 * d + 16.0 * d + 4 + 4 + 16.0 * d + (32.0 * d + 24) / 10; };
  const std::vector<Case> all = {
      {"srd-2d", 2, scene::Collision::srd, bytes(2)},
      {"srd-3d", 3, scene::Collision::srd, bytes(3)},
      {"at-2d", 2, scene::Collision::at, bytes(2) + 2 * 8.0 * 2},
      {"at+a-2d", 2, scene::Collision::at_a, bytes(2) + 2 * 8.0 * 2 + 16.0 * 2},
      {"at+a-3d", 3, scene::Collision::at_a, bytes(3) + 2 * 8.0 * 3 + 16.0 * 3},
  };
  std::vector<Case> cases;
  for (const Case &c : all)
    if (o.cases.empty() || std::find(o.cases.begin(), o.cases.end(), c.name) != o.cases.end())
      cases.push_back(c);
  for (const std::string &want : o.cases)
    if (std::none_of(all.begin(), all.end(), [&](const Case &c) { return c.name == want; })) {
      std::string allowed;
      for (const Case &c : all)
        allowed += (allowed.empty() ? "" : ", ") + c.name;
      throw input_error("command line: --case '" + want + "'; allowed: " + allowed);
    }
  const double triad = triad_bandwidth();
  char buf[256];
  if (o.json)
    out << "{\n  \"triad_bytes_per_s\": " << triad << ",\n  \"cases\": [\n";
  else {
    std::snprintf(buf, sizeof buf, "memory bandwidth (STREAM triad, one core): %.3g GB/s\n",
                  triad / 1e9);
    out << buf;
  }
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Result r = time_case(cases[i], o, triad);
    if (o.json) {
      std::snprintf(buf, sizeof buf,
                    "    {\"name\": \"%s\", \"particles\": %.0f, \"particle_steps_per_s\": %.4g, "
                    "\"bytes_per_particle_step\": %.0f, \"fraction_of_triad\": %.3f}%s\n",
                    cases[i].name.c_str(), r.particles, r.rate, cases[i].bytes_per_particle_step,
                    r.bandwidth_ratio, i + 1 < cases.size() ? "," : "");
    } else {
      std::snprintf(buf, sizeof buf,
                    "%-8s n=10, %.3g particles, one core: %.4g particle-steps/s "
                    "(%.0f B/particle-step = %.2f of the triad bound)\n",
                    cases[i].name.c_str(), r.particles, r.rate, cases[i].bytes_per_particle_step,
                    r.bandwidth_ratio);
    }
    out << buf << std::flush;
  }
  if (o.json)
    out << "  ]\n}\n";
}

} // namespace narrows::mpcd
