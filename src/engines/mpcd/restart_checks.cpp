// A restarted fluid outside the colloids' cores: binned colloids, one pass over the fluid.
//
// Where the bound lies. A fluid particle sits inside r = sigma (the colloid's radius) now and
// then: it enters the WCA potential with its thermal kinetic energy, and over a long run the
// largest of those is about kT ln(particles x steps), some 60 kT for 1e25 particle-steps, which
// reaches phi(r) = 60 kT at r ~ 0.8 sigma; a coarse MD step or a strong flow takes it deeper.
// What no running simulation holds is a particle whose pair force has a component beyond the
// fixed-point range 2^22 (fixed::max_magnitude): the force loop refuses it with exit 3
// (colloids/pair_geometry.hpp, to_fixed) at the force evaluation that follows every MD move,
// so a checkpoint, written after a step, cannot contain one. With epsilon = kT and sigma = 2
// that is r < 0.40 sigma, a pair energy above 2.8e5 kT: far beyond anything thermal, so no
// state a run can reach is refused, and a continued run would stop at its first force
// evaluation on what is refused here (the same test, component by component).
#include "narrows/engines/mpcd/restart_checks.hpp"

#include "narrows/colloids/potentials.hpp"
#include "narrows/core/error.hpp"
#include "narrows/core/fixed_point.hpp"
#include "narrows/run/collective.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <vector>

namespace narrows::mpcd {

namespace {

// Colloids binned on a grid of boxes at least one cut-off wide (periodic along x and z, and
// along y without walls): a point is tested against the colloids of its box and the adjacent
// ones only.
class ColloidBins {
public:
  ColloidBins(const colloids::Colloids &c, const mpcd::Box &box) : c_(c), box_(box) {
    double cut = 0.0;
    for (const double r : c.radius)
      cut = std::max(cut, colloids::repulsive_cutoff(6, r));
    // At most about 4 bins per colloid (+ 64): memory O(Nc) in a large box with small colloids.
    const double most = 4.0 * static_cast<double>(c.size()) + 64.0;
    for (int k = 0; k < 3; ++k)
      n_[k] = k < box.dim && cut > 0.0
                  ? static_cast<int>(std::clamp(std::floor(box.length[k] / cut), 1.0, most))
                  : 1;
    while (static_cast<double>(n_[0]) * n_[1] * n_[2] > most) {
      int &widest = *std::max_element(n_.begin(), n_.begin() + box.dim);
      widest = std::max(1, widest / 2);
    }
    for (int k = 0; k < 3; ++k)
      inv_[k] = n_[k] / box.length[k];
    first_.assign(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2] + 1, 0);
    std::vector<std::size_t> bin_of(c.size());
    for (std::size_t a = 0; a < c.size(); ++a) {
      std::array<double, 3> x{0.0, 0.0, 0.0};
      for (int k = 0; k < box.dim; ++k)
        x[k] = c.x[k][a];
      bin_of[a] = bin(coordinates(x));
      ++first_[bin_of[a] + 1];
    }
    for (std::size_t b = 1; b < first_.size(); ++b)
      first_[b] += first_[b - 1];
    members_.resize(c.size());
    std::vector<std::size_t> fill(first_.begin(), first_.end() - 1);
    for (std::size_t a = 0; a < c.size(); ++a)
      members_[fill[bin_of[a]]++] = a;
  }

  // f(colloid index) for every colloid in the bins around point x.
  template <class F> void around(const std::array<double, 3> &x, F &&f) const {
    const std::array<int, 3> home = coordinates(x);
    std::array<int, 3> lo{0, 0, 0}, hi{0, 0, 0};
    for (int k = 0; k < box_.dim; ++k) {
      const bool periodic = !(box_.walls_y && k == 1);
      if (n_[k] < 3) { // every bin of the axis, each once
        lo[k] = -home[k];
        hi[k] = n_[k] - 1 - home[k];
      } else {
        lo[k] = periodic || home[k] > 0 ? -1 : 0;
        hi[k] = periodic || home[k] < n_[k] - 1 ? 1 : 0;
      }
    }
    std::array<int, 3> o{};
    for (o[2] = lo[2]; o[2] <= hi[2]; ++o[2])
      for (o[1] = lo[1]; o[1] <= hi[1]; ++o[1])
        for (o[0] = lo[0]; o[0] <= hi[0]; ++o[0]) {
          std::array<int, 3> b{};
          for (int k = 0; k < 3; ++k)
            b[k] = (home[k] + o[k] + n_[k]) % n_[k];
          const std::size_t at = bin(b);
          for (std::size_t i = first_[at]; i < first_[at + 1]; ++i)
            f(members_[i]);
        }
  }

private:
  std::array<int, 3> coordinates(const std::array<double, 3> &x) const {
    std::array<int, 3> b{0, 0, 0};
    for (int k = 0; k < box_.dim; ++k) {
      const double u = std::floor(x[k] * inv_[k]); // positions were checked finite and in the box
      b[k] = static_cast<int>(std::clamp(u, 0.0, static_cast<double>(n_[k] - 1)));
    }
    return b;
  }
  std::size_t bin(const std::array<int, 3> &b) const {
    return (static_cast<std::size_t>(b[2]) * n_[1] + b[1]) * n_[0] + b[0];
  }

  const colloids::Colloids &c_;
  const mpcd::Box &box_;
  std::array<int, 3> n_{1, 1, 1};
  std::array<double, 3> inv_{1.0, 1.0, 1.0};
  std::vector<std::size_t> first_, members_;
};

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

} // namespace

void check_fluid_outside_colloids(const mpcd::Fluid &f, const colloids::Colloids &c,
                                  const mpcd::Box &box, double epsilon, double kT,
                                  const std::string &file, MPI_Comm comm) {
  const int D = box.dim;
  std::optional<std::string> line;
  std::uint64_t first = std::numeric_limits<std::uint64_t>::max();
  if (c.size() > 0) {
    const ColloidBins bins(c, box);
    for (std::size_t i = 0; i < f.size(); ++i) {
      if (f.id[i] >= first)
        continue; // the smallest bad id is reported, whatever the rank count
      std::array<double, 3> x{0.0, 0.0, 0.0};
      for (int k = 0; k < D; ++k)
        x[k] = f.x[k][i];
      bins.around(x, [&](std::size_t a) {
        if (f.id[i] >= first)
          return;
        std::array<double, 3> d{0.0, 0.0, 0.0};
        double r2 = 0.0;
        for (int k = 0; k < D; ++k) {
          d[k] = x[k] - c.x[k][a];
          if (!(box.walls_y && k == 1))
            d[k] -= box.length[k] * std::nearbyint(d[k] / box.length[k]);
          r2 += d[k] * d[k];
        }
        const double sigma = c.radius[a];
        if (!(r2 < std::pow(colloids::repulsive_cutoff(6, sigma), 2)))
          return;
        const colloids::PairTerm t = colloids::repulsive_pair<6>(r2, sigma * sigma, epsilon);
        bool beyond = r2 == 0.0;
        for (int k = 0; k < D; ++k)
          beyond = beyond || !(std::abs(t.f_over_r * d[k]) < fixed::max_magnitude);
        if (!beyond)
          return;
        first = f.id[i];
        std::string at = "(";
        for (int k = 0; k < D; ++k)
          at += (k ? ", " : "") + number(x[k]);
        const double energy = r2 == 0.0 ? std::numeric_limits<double>::infinity() : t.energy;
        line = file + ": /particles/fluid/position/value: fluid particle id " +
               std::to_string(f.id[i]) + " at " + at + ") lies inside colloid id " +
               std::to_string(c.id[a]) + " at distance " + number(std::sqrt(r2)) +
               " from its centre (radius " + number(sigma) + "), pair energy " +
               number(energy / kT) +
               " kT; allowed: a state a run can reach (a WCA force component below " +
               number(fixed::max_magnitude) + ", beyond which a run stops)";
      });
    }
  }
  std::uint64_t smallest = first;
  MPI_Allreduce(&first, &smallest, 1, MPI_UINT64_T, MPI_MIN, comm);
  run::collectively(comm, [&] {
    if (line && first == smallest)
      throw input_error(*line);
  });
}

} // namespace narrows::mpcd
