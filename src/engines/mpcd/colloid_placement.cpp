// Placing the scene's colloids at the start of a run: radii, masses and positions.
#include "narrows/engines/mpcd/colloid_placement.hpp"

#include "narrows/colloids/packing.hpp"
#include "narrows/colloids/placement.hpp"
#include "narrows/colloids/potentials.hpp"
#include "narrows/core/error.hpp"
#include "narrows/core/rng.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

namespace narrows::mpcd {

using colloids::colloid_volume;
using colloids::Colloids;
using colloids::distance2;
using colloids::pack_colloids;
using colloids::PackingReport;
using colloids::position;
using colloids::repulsive_cutoff;
using colloids::wall_cutoff;

// The packing of rough hard spheres: radii larger by this fraction while it is made.
constexpr double hard_packing_gap = 0.01;

namespace {

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

// Refuses given positions whose cores overlap (centres closer than r_a + r_b; touching is
// allowed): the 48-24 force there is beyond what the fixed-point force sums hold. Sort-and-sweep
// along the periodic x axis, so a file of many colloids costs O(N log N).
void check_no_overlap(const Colloids &c, const mpcd::Box &box, const scene::Colloids &spec) {
  const std::size_t n = c.size();
  if (n < 2)
    return;
  const auto key = [&](std::size_t i) {
    return i < spec.position_keys.size() ? spec.position_keys[i]
                                         : "colloids.positions[" + std::to_string(i) + "]";
  };
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return c.x[0][a] < c.x[0][b] || (c.x[0][a] == c.x[0][b] && a < b);
  });
  const double cut = 2.0 * *std::max_element(c.radius.begin(), c.radius.end());
  const double L = box.length[0];
  for (std::size_t s = 0; s < n; ++s) {
    const std::size_t a = order[s];
    for (std::size_t t = 1; t < n; ++t) {
      const std::size_t b = order[(s + t) % n];
      const double ahead = std::fmod(c.x[0][b] - c.x[0][a] + L, L); // forward gap along x
      if (ahead >= cut)
        break;
      const double contact = c.radius[a] + c.radius[b];
      const double r2 = distance2(box, position(c, a), position(c, b));
      if (r2 < contact * contact) {
        const std::size_t i = std::min(a, b), j = std::max(a, b);
        throw input_error(key(i) + " and " + key(j) + ": colloids " + std::to_string(i) + " and " +
                          std::to_string(j) + " are " + number(std::sqrt(r2)) +
                          " apart, their cores overlap (r_a + r_b = " + number(contact) +
                          "); allowed: centres at least r_a + r_b apart (touching is allowed)");
      }
    }
  }
}

} // namespace

double colloid_radius(const scene::Colloids &spec, std::uint64_t seed, std::uint64_t id) {
  if (!spec.kinds.empty())
    return spec.kinds[spec.kind_of(id)].radius;
  if (spec.radius_sd == 0.0)
    return spec.radius;
  // Truncated at +-3 sd: the four deviates of a block are taken in order, a new block (the
  // next attempt) when all four fall outside. The parser allows sd <= 0.2 radius, so every
  // radius is at least 0.4 radius and at most radius + 3 sd (the size its checks assumed).
  for (std::uint64_t attempt = 0;; ++attempt)
    for (const double z :
         rng::gaussian4(rng::draw(seed, rng::Purpose::colloid_radius, attempt, id)))
      if (std::abs(z) <= 3.0)
        return spec.radius + spec.radius_sd * z;
}

void set_radii_and_masses(Colloids &c, const scene::Colloids &spec, double density,
                          std::uint64_t seed) {
  for (std::size_t i = 0; i < c.size(); ++i) {
    c.radius[i] = colloid_radius(spec, seed, i);
    c.mass[i] = spec.mass_of_id(c.dim, density, i, c.radius[i]);
  }
}

std::uint64_t fluid_count_with_colloids(const scene::Colloids &spec, const mpcd::Box &box,
                                        double density, std::uint64_t seed) {
  double volume = 1.0;
  for (int k = 0; k < box.dim; ++k)
    volume *= box.length[k];
  if (!spec.kinds.empty()) {
    for (const auto &k : spec.kinds)
      volume -= static_cast<double>(k.count) * colloid_volume(box.dim, k.radius);
  } else if (spec.radius_sd == 0.0) {
    volume -= static_cast<double>(spec.count) * colloid_volume(box.dim, spec.radius);
  } else {
    for (std::int64_t i = 0; i < spec.count; ++i)
      volume -= colloid_volume(box.dim, colloid_radius(spec, seed, static_cast<std::uint64_t>(i)));
  }
  return static_cast<std::uint64_t>(std::llround(density * volume));
}

namespace {

// The colloids placed so far, by cells at least the largest 48-24 cut-off wide: a new position
// is tested against the colloids of its own and the neighbouring cells only, so placing N
// colloids costs O(N) tries, not O(N^2) (the accepted positions are the same).
class PlacedGrid {
public:
  PlacedGrid(const mpcd::Box &box, double cut) : box_(box) {
    std::size_t total = 1;
    for (int k = 0; k < 3; ++k) {
      n_[k] = k < box.dim ? std::max(1, static_cast<int>(box.length[k] / cut)) : 1;
      total *= static_cast<std::size_t>(n_[k]);
    }
    cells_.resize(total);
  }
  void add(const std::array<double, 3> &p, std::uint32_t a) { cells_[cell_of(p)].push_back(a); }
  // Calls visit(a) for every colloid in the cells around p (each once).
  template <class Visit> bool all_of_near(const std::array<double, 3> &p, Visit visit) const {
    std::array<std::vector<int>, 3> axis;
    for (int k = 0; k < 3; ++k) {
      const int n = n_[k], home = coordinate(p, k);
      if (n < 3) {
        for (int q = 0; q < n; ++q)
          axis[k].push_back(q);
      } else {
        for (int q = home - 1; q <= home + 1; ++q)
          if (k == 1 && box_.walls_y) {
            if (q >= 0 && q < n)
              axis[k].push_back(q);
          } else {
            axis[k].push_back((q + n) % n);
          }
      }
    }
    for (const int z : axis[2])
      for (const int y : axis[1])
        for (const int x : axis[0])
          for (const std::uint32_t a : cells_[index(x, y, z)])
            if (!visit(a))
              return false;
    return true;
  }

private:
  int coordinate(const std::array<double, 3> &p, int k) const {
    if (k >= box_.dim)
      return 0;
    const int q = static_cast<int>(p[k] / box_.length[k] * n_[k]);
    return std::clamp(q, 0, n_[k] - 1);
  }
  std::size_t index(int x, int y, int z) const {
    return (static_cast<std::size_t>(z) * n_[1] + static_cast<std::size_t>(y)) * n_[0] +
           static_cast<std::size_t>(x);
  }
  std::size_t cell_of(const std::array<double, 3> &p) const {
    return index(coordinate(p, 0), coordinate(p, 1), coordinate(p, 2));
  }

  mpcd::Box box_;
  std::array<int, 3> n_{1, 1, 1};
  std::vector<std::vector<std::uint32_t>> cells_;
};

} // namespace

Colloids place_colloids(const scene::Colloids &spec, const mpcd::Box &box, double density,
                        std::uint64_t seed, PackingReport *report,
                        const std::function<void()> &poll) {
  Colloids c;
  c.dim = box.dim;
  const auto n = static_cast<std::size_t>(spec.count);
  c.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    c.id[i] = i;
  set_radii_and_masses(c, spec, density, seed);
  switch (spec.placement) {
  case scene::ColloidPlacement::packing: {
    // Refused before it starts (check and run alike): a packing of many colloids takes minutes
    // to hours, on every rank alike, before step 0.
    const double work = colloids::packing_work(n);
    if (!(work <= spec.packing_max_work)) {
      char line[400];
      std::snprintf(
          line, sizeof line,
          "colloids.packing_max_work: packing %zu colloids takes about %.3g colloid-steps "
          "(%zu colloids x about %.3g relaxation steps, 1e4 + 1 per colloid); allowed: "
          "at most colloids.packing_max_work = %.3g (raise colloids.packing_max_work to "
          "pack them: about 1e7 colloid-steps take a second, on every rank alike)",
          n, work, n, work / static_cast<double>(n), spec.packing_max_work);
      throw input_error(line);
    }
    colloids::PackingParams params;
    params.poll = poll;
    // Rough hard spheres are packed at radii larger by hard_packing_gap, then given back their
    // own: with the packing's own overlaps (up to its tolerance, 0.5 % of the smallest radius)
    // every surface starts at least 1.5 % of the smallest radius from the others and 0.5 % from
    // the walls. Touching or overlapping hard spheres would collide at once, and a cluster of
    // them passes a chain of impulses along itself within the first step, further than the
    // ghost colloids of a rank reach on two or more ranks (the run stopped there).
    const bool hard = spec.contacts == scene::ColloidContacts::hard;
    const std::vector<double> radii(c.radius.begin(), c.radius.end());
    if (hard)
      for (double &r : c.radius)
        r *= 1.0 + hard_packing_gap;
    PackingReport r = pack_colloids(
        c, box, seed, "colloids.packing_fraction = " + number(spec.packing_fraction), params);
    if (hard) {
      std::copy(radii.begin(), radii.end(), c.radius.begin());
      r.fraction /= std::pow(1.0 + hard_packing_gap, box.dim);
      r.max_overlap = colloids::max_overlap(c, box) / *std::min_element(radii.begin(), radii.end());
    }
    if (report)
      *report = r;
    break;
  }
  case scene::ColloidPlacement::list:
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < box.dim; ++k)
        c.x[k][i] = spec.positions[i][k];
    check_no_overlap(c, box, spec);
    break;
  case scene::ColloidPlacement::lattice:
    for (std::size_t i = 0; i < n; ++i) {
      c.x[0][i] = (static_cast<double>(i) + 0.5) * box.length[0] / static_cast<double>(n);
      for (int k = 1; k < box.dim; ++k)
        c.x[k][i] = 0.5 * box.length[k];
    }
    break;
  case scene::ColloidPlacement::random: {
    // One kind: every colloid keeps the largest wall cut-off from the walls (the same band for
    // all); no-slip colloids have no potentials: their largest radius, and cores apart. Several
    // kinds: each keeps its own kind's band, and the kinds are placed largest radius first (then
    // by id), which packs denser mixtures than id order: a large colloid finds room before the
    // small ones fill the gaps. The order depends on the scene alone.
    const bool no_slip = spec.coupling == scene::ColloidCoupling::no_slip;
    const auto wall_band = [&](double r) {
      return no_slip ? r : wall_cutoff(spec.wall_sigma_of(r));
    };
    const double margin = box.walls_y ? wall_band(spec.max_radius()) : 0.0;
    double r_max = 0.0;
    for (const double r : c.radius)
      r_max = std::max(r_max, r);
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t{0});
    if (!spec.kinds.empty())
      std::stable_sort(order.begin(), order.end(),
                       [&](std::size_t a, std::size_t b) { return c.radius[a] > c.radius[b]; });
    PlacedGrid grid(box, repulsive_cutoff(24, 2.0 * r_max));
    for (const std::size_t i : order) {
      const double band = !box.walls_y || spec.kinds.empty() ? margin : wall_band(c.radius[i]);
      bool placed = false;
      for (std::uint64_t attempt = 0; attempt < 100000 && !placed; ++attempt) {
        const auto r = rng::draw(seed, rng::Purpose::colloid_placement, attempt, i);
        const auto r2 = rng::draw(seed, rng::Purpose::colloid_placement, attempt + (1ull << 40), i);
        std::array<double, 3> p{rng::uniform53(r[0], r[1]), rng::uniform53(r[2], r[3]),
                                rng::uniform53(r2[0], r2[1])};
        for (int k = 0; k < box.dim; ++k)
          p[k] = k == 1 && box.walls_y ? band + p[k] * (box.length[1] - 2.0 * band)
                                       : p[k] * box.length[k];
        placed = grid.all_of_near(p, [&](std::uint32_t j) {
          const double sum = c.radius[i] + c.radius[j];
          return distance2(box, p, position(c, j)) >=
                 std::pow(no_slip ? sum : repulsive_cutoff(24, sum), 2);
        });
        if (placed) {
          for (int k = 0; k < box.dim; ++k)
            c.x[k][i] = p[k];
          grid.add(p, static_cast<std::uint32_t>(i));
        }
      }
      if (!placed)
        throw input_error((spec.kinds.empty()
                               ? "colloids.count = " + std::to_string(n)
                               : "colloids.kind[" + std::to_string(spec.kind_of(i)) + "].count = " +
                                     std::to_string(spec.kinds[spec.kind_of(i)].count)) +
                          ": colloid " + std::to_string(i) +
                          " found no free place in 100000 random tries; allowed: fewer colloids "
                          "or placement = \"lattice\"");
    }
    break;
  }
  }
  return c;
}

} // namespace narrows::mpcd
