// Moment propagation kernel and VACF accumulation (see lattice/moment_propagation.hpp).
#include "narrows/engines/lgca/moment_propagation.hpp"

#include "narrows/core/error.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <string>
#include <utility>

namespace narrows::lgca {

NeighbourTable neighbour_table(std::int64_t sites, int links,
                               const std::function<std::int64_t(std::int64_t, int)> &neighbour) {
  NeighbourTable nb(static_cast<std::size_t>(sites * links));
  for (std::int64_t r = 0; r < sites; ++r)
    for (int i = 0; i < links; ++i)
      nb[r * links + i] = static_cast<std::int32_t>(neighbour(r, i));
  return nb;
}

NeighbourTable ring_neighbours(std::int64_t L, std::span<const int> displacement) {
  const int links = static_cast<int>(displacement.size());
  return neighbour_table(
      L, links, [&](std::int64_t r, int i) { return ((r + displacement[i]) % L + L) % L; });
}

std::int64_t triangular_neighbour(std::int64_t nx, std::int64_t ny, std::int64_t site, int link) {
  const std::int64_t x = site % nx, y = site / nx;
  const std::int64_t odd = y & 1, even = 1 - odd;
  std::int64_t dx = 0, dy = 0;
  switch (link) {
  case 0:
    dx = 1;
    break;
  case 1:
    dx = odd, dy = 1;
    break;
  case 2:
    dx = -even, dy = 1;
    break;
  case 3:
    dx = -1;
    break;
  case 4:
    dx = -even, dy = -1;
    break;
  case 5:
    dx = odd, dy = -1;
    break;
  default:
    return site; // rest particle
  }
  const std::int64_t xn = ((x + dx) % nx + nx) % nx, yn = ((y + dy) % ny + ny) % ny;
  return yn * nx + xn;
}

NeighbourTable triangular_neighbours(std::int64_t nx, std::int64_t ny, int links) {
  if (nx < 1 || ny < 2 || ny % 2 != 0)
    throw input_error("triangular lattice: size [" + std::to_string(nx) + ", " +
                      std::to_string(ny) + "] not allowed; size[1] must be even and >= 2");
  return neighbour_table(nx * ny, links,
                         [&](std::int64_t r, int i) { return triangular_neighbour(nx, ny, r, i); });
}

Links triangular_links(bool rest_particle) {
  Links l;
  for (int i = 0; i < 6; ++i) {
    // exact zeros and halves, so that sums over links cancel exactly
    const double c = i % 3 == 0 ? (i == 0 ? 1.0 : -1.0) : (i == 1 || i == 5 ? 0.5 : -0.5);
    l.cx.push_back(c);
    const double h = std::sqrt(3.0) / 2.0; // sin(pi i / 3), with exact zeros on the x axis
    l.cy.push_back(i % 3 == 0 ? 0.0 : (i < 3 ? h : -h));
  }
  if (rest_particle) {
    l.cx.push_back(0.0);
    l.cy.push_back(0.0);
  }
  return l;
}

void propagate_tagged(std::span<const std::uint8_t> occ, const NeighbourTable &nb, int links,
                      int dims, std::span<const double> a, std::span<double> a_next) {
  const std::size_t sites = occ.size();
  for (std::size_t k = 0; k < a_next.size(); ++k)
    a_next[k] = 0.0;
  for (std::size_t r = 0; r < sites; ++r) {
    const unsigned s = occ[r];
    const int rho = std::popcount(s);
    if (rho == 0) {
      for (int k = 0; k < dims; ++k)
        if (a[r * dims + k] != 0.0)
          throw invariant_error("moment propagation: tagged weight at empty site " +
                                std::to_string(r));
      continue;
    }
    const double inv = 1.0 / rho;
    // branch-free over links (occupations are random bits): empty links add zero
    for (int i = 0; i < links; ++i) {
      const double share = static_cast<double>((s >> i) & 1u) * inv;
      const std::size_t to = static_cast<std::size_t>(nb[r * links + i]);
      for (int k = 0; k < dims; ++k)
        a_next[to * dims + k] += a[r * dims + k] * share;
    }
  }
}

double tagged_correlation(std::span<const std::uint8_t> occ, const Links &links,
                          std::span<const double> a) {
  const int b = links.count(), dims = links.dims();
  // u(s) for all 2^b node states, looked up per site
  std::array<double, 256> ux{}, uy{};
  for (unsigned s = 1; s < (1u << b); ++s) {
    for (int i = 0; i < b; ++i)
      if ((s >> i) & 1u) {
        ux[s] += links.cx[i];
        if (dims == 2)
          uy[s] += links.cy[i];
      }
    ux[s] /= std::popcount(s);
    uy[s] /= std::popcount(s);
  }
  double sum = 0.0;
  if (dims == 1) {
    for (std::size_t r = 0; r < occ.size(); ++r)
      sum += a[r] * ux[occ[r]];
  } else {
    for (std::size_t r = 0; r < occ.size(); ++r)
      sum += a[2 * r] * ux[occ[r]] + a[2 * r + 1] * uy[occ[r]];
  }
  return sum;
}

MomentPropagation::MomentPropagation(Links links, NeighbourTable nb, int max_lag)
    : links_(std::move(links)), nb_(std::move(nb)), max_lag_(max_lag) {
  const int b = links_.count();
  if (b < 1 || b > 8 || (links_.dims() == 2 && links_.cy.size() != links_.cx.size()))
    throw input_error("moment propagation: need 1 to 8 links with one velocity each");
  if (max_lag < 1)
    throw input_error("tagged.max_lag = " + std::to_string(max_lag) + " not allowed; need >= 1");
  if (nb_.empty() || nb_.size() % b != 0)
    throw input_error("moment propagation: neighbour table size is not sites x links");
  sites_ = static_cast<std::int64_t>(nb_.size()) / b;
  a_.assign(static_cast<std::size_t>(sites_ * links_.dims()), 0.0);
  a_next_ = a_;
  sum_.assign(static_cast<std::size_t>(max_lag_ + 1), 0.0);
}

// Eq 13: every particle is a starting point with weight its velocity; the weight it carries
// arrives at its neighbour one step later. Lag 0 is (1/N) sum of c^2 over particles.
void MomentPropagation::start(std::span<const std::uint8_t> occ) {
  const int b = links_.count(), dims = links_.dims();
  for (double &x : a_)
    x = 0.0;
  double n = 0.0, c2 = 0.0;
  for (std::int64_t r = 0; r < sites_; ++r) {
    const unsigned s = occ[r];
    for (int i = 0; i < b; ++i) {
      if (!((s >> i) & 1u))
        continue;
      const std::int64_t to = nb_[r * b + i];
      n += 1.0;
      a_[to * dims] += links_.cx[i];
      c2 += links_.cx[i] * links_.cx[i];
      if (dims == 2) {
        a_[to * dims + 1] += links_.cy[i];
        c2 += links_.cy[i] * links_.cy[i];
      }
    }
  }
  if (n == 0.0)
    throw input_error("moment propagation: the lattice has no particles");
  particles_ = n;
  current_.assign(1, c2 / n);
  lag_ = 0;
}

void MomentPropagation::feed(std::span<const std::uint8_t> occ) {
  if (static_cast<std::int64_t>(occ.size()) != sites_)
    throw input_error("moment propagation: occupation has " + std::to_string(occ.size()) +
                      " sites, the neighbour table " + std::to_string(sites_));
  if (lag_ < 0) {
    start(occ);
    return;
  }
  // a_ arrived at this step's sites before the collision that produced occ (eq 14, then eq 11)
  current_.push_back(tagged_correlation(occ, links_, a_) / particles_);
  ++lag_;
  if (lag_ == max_lag_) {
    for (int t = 0; t <= max_lag_; ++t)
      sum_[t] += current_[t];
    ++curves_;
    start(occ);
    return;
  }
  propagate_tagged(occ, nb_, links_.count(), links_.dims(), a_, a_next_);
  std::swap(a_, a_next_);
}

std::vector<double> MomentPropagation::mean() const {
  std::vector<double> m;
  if (curves_ == 0)
    return m;
  for (double s : sum_)
    m.push_back(s / curves_);
  return m;
}

} // namespace narrows::lgca
