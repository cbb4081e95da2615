// `narrows bench --dem N`: the spring contacts alone on a dense packing (issue 21 acceptance 6).
#include "narrows/colloids/dem_bench.hpp"

#include "narrows/colloids/contact_history.hpp"
#include "narrows/colloids/packing.hpp"
#include "narrows/colloids/springs.hpp"
#include "narrows/core/error.hpp"
#include "narrows/core/rng.hpp"
#include "narrows/core/timer.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>

namespace narrows::colloids {

namespace {

constexpr double rho = 25.0, kT = 1.0, width = 50.0, fraction = 0.8;
constexpr double radii[2] = {2.1, 2.94};
constexpr std::size_t tile_disks = 1000;
constexpr std::uint64_t seed = 21;

void write_lammps(const std::string &path, const Colloids &c, double length) {
  std::ofstream f(path);
  if (!f)
    throw input_error("command line: --dem-data '" + path +
                      "' cannot be written; allowed: a writable file path");
  char line[256];
  f << "narrows bench --dem packing: Kanehl (thesis) Table 6.1 mixture, phi = 0.8, "
       "walls at y = 0, "
    << width << "\n\n"
    << c.size() << " atoms\n2 atom types\n\n";
  std::snprintf(line, sizeof line, "0 %.17g xlo xhi\n0 %.17g ylo yhi\n-0.5 0.5 zlo zhi\n\n", length,
                width);
  f << line << "Atoms # sphere\n\n";
  // Density 1 here; the script sets each type's mass to the density-matched n pi a^2.
  for (std::size_t a = 0; a < c.size(); ++a) {
    std::snprintf(line, sizeof line, "%zu %d %.17g 1 %.17g %.17g 0\n", a + 1,
                  c.radius[a] == radii[0] ? 1 : 2, 2.0 * c.radius[a], c.x[0][a], c.x[1][a]);
    f << line;
  }
  f << "\nVelocities\n\n";
  for (std::size_t a = 0; a < c.size(); ++a) {
    std::snprintf(line, sizeof line, "%zu %.17g %.17g 0 0 0 %.17g\n", a + 1, c.v[0][a], c.v[1][a],
                  c.omega[2][a]);
    f << line;
  }
  if (!f)
    throw input_error("command line: --dem-data '" + path + "': writing failed");
}

} // namespace

void run_dem_bench(const DemBenchOptions &o, std::ostream &out) {
  if (!(o.disks >= 1.0 && o.disks <= 1e8)) // (~100 GB beyond: refused, not a failed allocation)
    throw input_error("command line: --dem " + std::to_string(o.disks) +
                      "; allowed: a number of disks from 1 to 1e8");
  // One tile: half the disks of each radius, in a channel of the length that gives phi.
  double area = 0.0;
  for (const double r : radii)
    area += 0.5 * static_cast<double>(tile_disks) * M_PI * r * r;
  const double tile_length = area / (fraction * width);
  mpcd::Box tile_box;
  tile_box.dim = 2;
  tile_box.walls_y = true;
  tile_box.length = {tile_length, width, 1.0};
  tile_box.cells = {static_cast<int>(std::ceil(tile_length)), static_cast<int>(width), 1};
  Colloids tile;
  tile.dim = 2;
  tile.resize(tile_disks);
  for (std::size_t a = 0; a < tile_disks; ++a) {
    tile.id[a] = a;
    tile.radius[a] = radii[a % 2];
  }
  Stopwatch packing_clock;
  const PackingReport packed = pack_colloids(tile, tile_box, seed, "bench --dem");
  const double packing_seconds = packing_clock.seconds();

  const auto tiles = static_cast<std::size_t>(std::ceil(o.disks / tile_disks));
  const std::size_t n = tiles * tile_disks;
  mpcd::Box box = tile_box;
  box.length[0] = tile_length * static_cast<double>(tiles);
  box.cells[0] = static_cast<int>(std::ceil(box.length[0]));
  Colloids c;
  c.dim = 2;
  c.resize(n);
  for (std::size_t t = 0; t < tiles; ++t)
    for (std::size_t a = 0; a < tile_disks; ++a) {
      const std::size_t i = t * tile_disks + a;
      c.id[i] = i;
      c.radius[i] = tile.radius[a];
      c.mass[i] = rho * M_PI * tile.radius[a] * tile.radius[a];
      c.x[0][i] = tile.x[0][a] + tile_length * static_cast<double>(t);
      c.x[1][i] = tile.x[1][a];
      const auto g = rng::gaussian4(rng::draw(seed, rng::Purpose::init_velocity, 0, i));
      c.v[0][i] = std::sqrt(kT / c.mass[i]) * g[0];
      c.v[1][i] = std::sqrt(kT / c.mass[i]) * g[1];
      c.omega[2][i] = std::sqrt(kT / (0.5 * c.mass[i] * c.radius[i] * c.radius[i])) * g[2];
    }
  if (!o.lammps_data.empty())
    write_lammps(o.lammps_data, c, box.length[0]);

  SpringParams p; // Table 6.1: k_n = k_t = 2500, 10 sub-steps
  p.kn = p.kt = 2500.0;
  p.mu_cc = p.mu_cw = 1.0;
  p.substeps = 10;
  const double dt = 0.02;
  SpringContacts springs(p, box);
  ContactHistory history;
  history.dim = 2;
  springs.advance(c, n, history, dt); // warm-up: the contacts' springs exist
  const std::uint64_t before = springs.contact_updates();
  const double kernel_before = springs.force_seconds();
  Stopwatch clock;
  for (int s = 0; s < o.steps; ++s)
    springs.advance(c, n, history, dt);
  const double seconds = clock.seconds();
  const double kernel = springs.force_seconds() - kernel_before;
  const double substeps = static_cast<double>(o.steps) * p.substeps;
  const double updates = static_cast<double>(springs.contact_updates() - before);
  std::size_t pairs = 0; // the pair contacts (not the walls') the last sub-step left
  for (std::size_t j = 0; j < history.size(); ++j)
    pairs += history.partner[j] != wall_low_id && history.partner[j] != wall_high_id;
  const double rate = updates / seconds, disk_rate = static_cast<double>(n) * substeps / seconds;
  char text[512];
  if (o.json)
    std::snprintf(text, sizeof text,
                  "{\n  \"dem\": {\"disks\": %zu, \"length\": %.6g, \"packing_fraction\": %.4f, "
                  "\"substeps\": %.0f, \"contacts_per_substep\": %.6g, \"pair_contacts_end\": %zu, "
                  "\"contact_updates_per_s\": %.6g, \"disk_substeps_per_s\": %.6g, "
                  "\"seconds\": %.4g, \"force_seconds\": %.4g, \"tile_packing_seconds\": "
                  "%.3g}\n}\n",
                  n, box.length[0], packed.fraction, substeps, updates / substeps, pairs, rate,
                  disk_rate, seconds, kernel, packing_seconds);
  else
    std::snprintf(
        text, sizeof text,
        "dem: %zu disks (a = 2.1, 2.94) at phi = %.4f in %.6g x %.0f (a %zu-disk packing "
        "tile grown in %.3g s, repeated %zu times), k_n = k_t = 2500, mu = 1\n"
        "dem: %.0f sub-steps in %.4g s: %.6g contacts per sub-step (pairs and walls; %zu "
        "pairs at the end), "
        "%.4g contact updates/s, %.4g disk sub-steps/s (one core); the contact forces alone "
        "%.4g s\n",
        n, packed.fraction, box.length[0], width, tile_disks, packing_seconds, tiles, substeps,
        seconds, updates / substeps, pairs, rate, disk_rate, kernel);
  out << text;
}

} // namespace narrows::colloids
