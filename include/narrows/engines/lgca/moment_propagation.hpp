// Moment propagation (van der Hoef & Frenkel eq 11, 13, 14): the velocity autocorrelation of a
// tagged particle averaged over all its trajectories and over all particles as starting points, for
// any lattice gas whose node state is a byte of link occupations. The kernel needs only the
// post-collision occupation of every site each step, the link velocities and a neighbour table.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace narrows::lgca {

// Link velocities of a model: link i is bit i of the occupation byte (at most 8 links).
// dims = 1 (cy empty) or 2; a rest particle is a link with zero velocity.
struct Links {
  std::vector<double> cx, cy;
  int count() const { return static_cast<int>(cx.size()); }
  int dims() const { return cy.empty() ? 1 : 2; }
};

// Neighbour table nb[site * links + i] = the site a particle on link i reaches in one step.
using NeighbourTable = std::vector<std::int32_t>;
NeighbourTable neighbour_table(std::int64_t sites, int links,
                               const std::function<std::int64_t(std::int64_t, int)> &neighbour);

// Periodic ring of L sites with integer link displacements (1D models).
NeighbourTable ring_neighbours(std::int64_t L, std::span<const int> displacement);

// Triangular lattice of size[0] x size[1] sites (size[1] even), periodic; site (x, y) has index
// y * size[0] + x and sits at (x + (y mod 2) / 2, y * sqrt(3) / 2). Links 0..5 point along
// c_i = (cos(pi i / 3), sin(pi i / 3)); link 6 (if links == 7) is the rest particle.
std::int64_t triangular_neighbour(std::int64_t nx, std::int64_t ny, std::int64_t site, int link);
NeighbourTable triangular_neighbours(std::int64_t nx, std::int64_t ny, int links);
Links triangular_links(bool rest_particle);

// One propagation step of eq 11 for each velocity component k: the tagged weight a[r * dims + k]
// that arrived at site r is split equally over the occupied outgoing links of the
// post-collision occupation occ[r] and moved along them into a_next (overwritten). This equal
// split is the rule for which the one-step VACF (eq 18/19) is exact. Weight arriving at an
// empty site would be lost: that breaks an invariant and throws.
void propagate_tagged(std::span<const std::uint8_t> occ, const NeighbourTable &nb, int links,
                      int dims, std::span<const double> a, std::span<double> a_next);

// Eq 14 without the 1/N: sum over sites of a[r] . u(r), u = sum_i s_i c_i / rho.
double tagged_correlation(std::span<const std::uint8_t> occ, const Links &links,
                          std::span<const double> a);

// VACF of all particles of one lattice, over successive time origins. Feed the post-collision
// occupation of every step in order; the first call (and the call after a curve is complete)
// starts a new origin from that state with eq 13, the others propagate with eq 11 and record
// eq 14. A curve has lags 0..max_lag; its end state is the start of the next curve.
class MomentPropagation {
public:
  MomentPropagation(Links links, NeighbourTable nb, int max_lag);

  void feed(std::span<const std::uint8_t> occ);

  // Completed curves and their sum of C(t) = (1/N) sum_r a(r) . u(r) (= <v(0).v(t)>, not
  // normalised; per-curve N is the particle count of the origin state).
  int curves() const { return curves_; }
  const std::vector<double> &sum() const { return sum_; }
  // Mean over completed curves of C(t) (empty if none).
  std::vector<double> mean() const;
  // The curve in progress (lags 0..lag()).
  const std::vector<double> &current() const { return current_; }
  int lag() const { return lag_; }
  int max_lag() const { return max_lag_; }

private:
  void start(std::span<const std::uint8_t> occ);

  Links links_;
  NeighbourTable nb_;
  int max_lag_;
  std::int64_t sites_;
  std::vector<double> a_, a_next_;
  std::vector<double> current_, sum_;
  double particles_ = 0.0;
  int lag_ = -1; // -1: no curve in progress
  int curves_ = 0;
};

} // namespace narrows::lgca
