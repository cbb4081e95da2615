// Benchmarks: MPCD particle-steps/s on one core next to the STREAM-triad bandwidth measured on
// arrays as large as the case's working set, and the coupled Table 6.1 channel with its
// no-slip coupling's share of the loop.
#include "narrows/engines/mpcd/bench.hpp"

#include "narrows/core/error.hpp"
#include "narrows/core/timer.hpp"
#include "narrows/engines/mpcd/simulation.hpp"
#include "narrows/scene/parse.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace narrows::mpcd {

namespace {

constexpr double kMiB = 1048576.0;

struct LastLevelCache {
  std::size_t bytes = 0; // 0: not found
  int level = 0;
  const char *source = "unknown";
};

// CPU seconds (user + system) of this process so far: on a shared machine the wall time of a
// loop includes the time other processes held the core.
double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Bytes of a size in sysfs notation ("32K", "480M", "1024").
std::size_t sysfs_bytes(std::string text) {
  std::size_t scale = 1;
  if (!text.empty() && (text.back() == 'K' || text.back() == 'M' || text.back() == 'G')) {
    scale = text.back() == 'K' ? 1024 : text.back() == 'M' ? 1024 * 1024 : 1024 * 1024 * 1024;
    text.pop_back();
  }
  try {
    return static_cast<std::size_t>(std::stoull(text)) * scale;
  } catch (...) {
    return 0;
  }
}

// The cache the arrays of a case compete for. Read where glibc has it (sysconf, from CPUID),
// else from the kernel's description of cpu0's caches (the highest level listed).
LastLevelCache last_level_cache() {
  for (const auto &[name, level] :
       {std::pair{_SC_LEVEL3_CACHE_SIZE, 3}, std::pair{_SC_LEVEL2_CACHE_SIZE, 2}}) {
    const long bytes = sysconf(name);
    if (bytes > 0)
      return {static_cast<std::size_t>(bytes), level, "sysconf"};
  }
  LastLevelCache best{0, 0, "unknown"};
  for (int i = 0; i < 16; ++i) {
    const std::string dir = "/sys/devices/system/cpu/cpu0/cache/index" + std::to_string(i) + "/";
    std::ifstream level_file(dir + "level"), size_file(dir + "size");
    int level = 0;
    std::string size;
    if (!(level_file >> level) || !(size_file >> size))
      continue;
    if (level >= best.level)
      best = {sysfs_bytes(size), level, "sysfs"};
  }
  return best;
}

// Best-of-5 triad a = b + s c over three arrays that together hold `bytes`; bytes moved counted
// as STREAM does (two reads, one write). Small arrays are swept several times per repetition,
// so that each repetition lasts long enough to time. The barrier after each sweep makes every
// sweep's stores happen: without it GCC kept only the last sweep's and ran that as a scalar
// loop around a loop over the sweeps, whose speed (20-27 GB/s beyond the cache here, by where
// the code fell) was not the memory's.
double triad_bandwidth(double bytes) {
  const auto n = static_cast<std::size_t>(std::max(bytes / 24.0, 4096.0));
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  const int sweeps =
      static_cast<int>(std::clamp(std::ceil(3.0e7 / static_cast<double>(n)), 1.0, 1.0e4));
  double best = 1e30;
  for (int rep = 0; rep < 5; ++rep) {
    Stopwatch t;
    for (int sweep = 0; sweep < sweeps; ++sweep) {
      const double s = 3.0 + rep + 1e-3 * sweep;
      double *__restrict pa = a.data();
      const double *__restrict pb = b.data(), *__restrict pc = c.data();
      for (std::size_t i = 0; i < n; ++i)
        pa[i] = pb[i] + s * pc[i];
      asm volatile("" : : "r"(pa) : "memory");
    }
    best = std::min(best, t.seconds());
  }
  volatile double sink = a[n / 2];
  (void)sink;
  return 3.0 * 8.0 * static_cast<double>(n) * sweeps / best;
}

struct Case {
  std::string name;
  int dim;
  scene::Collision rule;
  double bytes_per_particle_step; // streamed by the kernels, counted from their loops (0: coupled)
};

// The fluid-only box of a case: n = 10 per cell, 2D a 4:1 rectangle, 3D a 2:1:1 prism.
scene::Scene fluid_scene(const Case &c, double particles, double angle_deg) {
  scene::Scene s;
  s.file = "(bench)";
  s.run.dimensions = c.dim;
  s.run.seed = 1;
  s.fluid.collision = c.rule;
  s.fluid.density = 10.0;
  s.fluid.dt = 1.0;
  s.fluid.angle_deg = angle_deg;
  const double cells = particles / s.fluid.density;
  if (c.dim == 2) {
    const double ly = std::max(1.0, std::round(std::sqrt(cells / 4.0)));
    s.domain.size = {std::ceil(cells / ly), ly, 0.0};
  } else {
    const double side = std::max(1.0, std::round(std::cbrt(cells / 2.0)));
    s.domain.size = {std::ceil(cells / (side * side)), side, side};
  }
  return s;
}

// The smallest fluid box whose working set is at least `bytes` (and at least 1e6 particles).
scene::Scene beyond(const Case &c, double bytes, double angle_deg) {
  double n = 1.0e6;
  scene::Scene s = fluid_scene(c, n, angle_deg);
  for (int i = 0; i < 20 && static_cast<double>(estimate_memory(s)) < bytes; ++i) {
    n *= 1.02 * bytes / static_cast<double>(estimate_memory(s));
    s = fluid_scene(c, n, angle_deg);
  }
  return s;
}

// Kanehl (thesis) Table 6.1, ch.6 (run/pulses_table6_1.toml, which says where each value comes
// from): MPC-AT+a 2D, rho = 25, dt = 0.02, walls 2w = 50 apart, sigma/rho = 0.05 on the fluid and
// the colloids, no-slip disks a = 2.1 and 2.94 (1 : 1) with spring contacts packed to phi =
// 0.75. The channel is `length` long (the scene file's l = 600 b: 1098 disks, 187150 fluid
// particles).
constexpr const char *kTable61 = R"(
[run]
dimensions = 2
seed = 601
steps = 1000
[domain]
size = [600.0, 50.0]
[fluid]
collision = "at+a"
density = 25
dt = 0.02
[body_force]
value = [0.05, 0.0]
acts_on = "fluid+colloids"
[walls]
virtual_particles = true
[colloids]
coupling = "no-slip"
contacts = "spring"
placement = "packing"
packing_fraction = 0.75
[colloids.spring]
kn = 2500
kt = 2500
mu_cc = 1.0
mu_cw = 1.0
substeps = 10
[[colloids.kind]]
radius = 2.1
count = 1
[[colloids.kind]]
radius = 2.94
count = 1
)";
constexpr double kTable61Length = 600.0, kTable61Particles = 187150.0;

scene::Scene table61_scene(double particles) {
  const double length = std::max(30.0, std::round(kTable61Length * particles / kTable61Particles));
  char size[80];
  std::snprintf(size, sizeof size, "domain.size=[%.1f, 50.0]", length);
  return scene::parse_scene(kTable61, "(bench pulses-2d: Kanehl (thesis) Table 6.1)", {size});
}

struct Result {
  double rate = 0.0;     // (fluid) particle-steps/s, wall time
  double cpu_rate = 0.0; // the same per CPU second of this process
  double particles = 0.0;
  double working_set = 0.0; // bytes of the fluid arrays and the cell grid
  double triad = 0.0;       // bytes/s of the triad on arrays of the working set's size
  double bandwidth_ratio = 0.0;
  double coupling_seconds = 0.0, loop_seconds = 0.0;
  std::size_t colloids = 0;
  double length = 0.0;
  std::array<double, 3> box{};
};

Result time_simulation(MpcdSimulation &sim, const BenchOptions &o, Result r) {
  for (int i = 0; i < 20; ++i) // warm-up: reach the sorted steady state
    sim.advance();
  const auto *ns = sim.no_slip();
  const double coupling0 = ns ? ns->seconds() : 0.0;
  const double cpu0 = cpu_seconds();
  Stopwatch t;
  for (int i = 0; i < o.steps; ++i)
    sim.advance();
  const double sec = t.seconds(), cpu = cpu_seconds() - cpu0;
  r.particles = static_cast<double>(sim.fluid().size());
  r.rate = r.particles * o.steps / sec;
  r.cpu_rate = cpu > 0.0 ? r.particles * o.steps / cpu : 0.0;
  r.loop_seconds = sec;
  r.coupling_seconds = ns ? ns->seconds() - coupling0 : 0.0;
  return r;
}

Result time_case(const Case &c, const BenchOptions &o, const LastLevelCache &llc) {
  Result r;
  if (c.name == "pulses-2d") {
    const scene::Scene s = table61_scene(o.particles > 0.0 ? o.particles : kTable61Particles);
    MpcdSimulation sim(s, MPI_COMM_SELF);
    r.working_set = static_cast<double>(estimate_memory(s, sim.fluid().size()));
    r.colloids = sim.colloids().size();
    r.length = s.domain.size[0];
    r.box = s.domain.size;
    return time_simulation(sim, o, r);
  }
  const scene::Scene s =
      o.particles > 0.0
          ? fluid_scene(c, o.particles, o.angle_deg)
          : beyond(c, 4.0 * static_cast<double>(llc.bytes > 0 ? llc.bytes : 64 * 1048576),
                   o.angle_deg);
  r.working_set = static_cast<double>(estimate_memory(s));
  r.box = s.domain.size;
  r.triad = triad_bandwidth(r.working_set); // before the case's own arrays exist
  MpcdSimulation sim(s, MPI_COMM_SELF);
  r = time_simulation(sim, o, r);
  r.bandwidth_ratio = r.rate * c.bytes_per_particle_step / r.triad;
  return r;
}

// Where a working set lies: "in cache", "beyond cache" (>= 4 x LLC) or "near the cache size".
const char *where(double working_set, const LastLevelCache &llc) {
  if (llc.bytes == 0)
    return "cache size unknown";
  const double x = working_set / static_cast<double>(llc.bytes);
  return x >= 4.0 ? "beyond cache" : x <= 0.5 ? "in cache" : "near the cache size";
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
      {"pulses-2d", 2, scene::Collision::at_a, 0.0},
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
  const LastLevelCache llc = last_level_cache();
  const double llc_bytes = static_cast<double>(llc.bytes > 0 ? llc.bytes : 64 * 1048576);
  // The triad in the cache (three arrays of a quarter of it); beyond it, each case measures its
  // own at its working set's size.
  const double in_cache = triad_bandwidth(0.25 * llc_bytes);
  char buf[512];
  if (o.json) {
    std::snprintf(buf, sizeof buf,
                  "{\n  \"last_level_cache_bytes\": %zu,\n  \"last_level_cache_level\": %d,\n"
                  "  \"triad_in_cache_bytes_per_s\": %.6g,\n  \"cases\": [\n",
                  llc.bytes, llc.level, in_cache);
    out << buf;
  } else {
    std::snprintf(buf, sizeof buf,
                  "last-level cache: %.0f MiB (L%d, %s); memory bandwidth (STREAM triad, one "
                  "core): %.3g GB/s in the cache (arrays of 1/4 of it); each case below: the "
                  "triad on arrays of its working set\n",
                  static_cast<double>(llc.bytes) / kMiB, llc.level, llc.source, in_cache / 1e9);
    out << buf;
  }
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case &c = cases[i];
    const Result r = time_case(c, o, llc);
    const double x_llc = r.working_set / llc_bytes;
    const double share = r.loop_seconds > 0.0 ? r.coupling_seconds / r.loop_seconds : 0.0;
    const char *comma = i + 1 < cases.size() ? "," : "";
    if (o.json && c.bytes_per_particle_step == 0.0) {
      std::snprintf(buf, sizeof buf,
                    "    {\"name\": \"%s\", \"fluid_particles\": %.0f, \"colloids\": %zu, "
                    "\"length\": %.0f, \"steps\": %d, \"working_set_bytes\": %.0f, "
                    "\"fluid_particle_steps_per_s\": %.4g, \"per_cpu_second\": %.4g, "
                    "\"loop_seconds\": %.4g, \"coupling_seconds\": %.4g, "
                    "\"coupling_share\": %.4f}%s\n",
                    c.name.c_str(), r.particles, r.colloids, r.length, o.steps, r.working_set,
                    r.rate, r.cpu_rate, r.loop_seconds, r.coupling_seconds, share, comma);
    } else if (o.json) {
      std::snprintf(buf, sizeof buf,
                    "    {\"name\": \"%s\", \"particles\": %.0f, \"box\": [%.0f, %.0f, %.0f], "
                    "\"angle_deg\": %g, \"steps\": %d, \"working_set_bytes\": %.0f, "
                    "\"working_set_over_cache\": %.3g, \"triad_bytes_per_s\": %.6g, "
                    "\"particle_steps_per_s\": %.4g, \"per_cpu_second\": %.4g, "
                    "\"loop_seconds\": %.4g, \"bytes_per_particle_step\": %.0f, "
                    "\"fraction_of_triad\": %.3f}%s\n",
                    c.name.c_str(), r.particles, r.box[0], r.box[1], r.box[2], o.angle_deg, o.steps,
                    r.working_set, x_llc, r.triad, r.rate, r.cpu_rate, r.loop_seconds,
                    c.bytes_per_particle_step, r.bandwidth_ratio, comma);
    } else if (c.bytes_per_particle_step == 0.0) {
      std::snprintf(buf, sizeof buf,
                    "%-9s Kanehl (thesis) Table 6.1 channel, l = %.0f b, %zu disks, %.6g fluid "
                    "particles, working set %.3g MiB = %.3g x LLC (%s), one core, %d steps: "
                    "%.4g fluid particle-steps/s (%.4g per CPU second)\n"
                    "%-9s no-slip coupling: %.4g s of the loop (%.1f %%)\n",
                    c.name.c_str(), r.length, r.colloids, r.particles, r.working_set / kMiB, x_llc,
                    where(r.working_set, llc), o.steps, r.rate, r.cpu_rate, c.name.c_str(),
                    r.coupling_seconds, 100.0 * share);
    } else {
      std::snprintf(buf, sizeof buf,
                    "%-9s n=10, %.3g particles, working set %.3g MiB = %.3g x LLC (%s), one "
                    "core: %.4g particle-steps/s (%.4g per CPU second; %.0f B/particle-step = "
                    "%.2f of the triad at this size, %.3g GB/s)\n",
                    c.name.c_str(), r.particles, r.working_set / kMiB, x_llc,
                    where(r.working_set, llc), r.rate, r.cpu_rate, c.bytes_per_particle_step,
                    r.bandwidth_ratio, r.triad / 1e9);
    }
    out << buf << std::flush;
  }
  if (o.json)
    out << "  ]\n}\n";
  else
    out << "a cluster node (~2 MB of L3 per core) sees the beyond-cache figures: a case of more "
           "than ~1e5 particles (~10 MB) outgrows its share of the cache\n";
}

} // namespace narrows::mpcd
