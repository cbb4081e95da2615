// Moment propagation on the slabs of the FHP lattice (see lattice/fhp_tagged.hpp).
#include "narrows/engines/lgca/fhp_tagged.hpp"

#include "narrows/core/error.hpp"
#include "narrows/engines/lgca/column_halo.hpp"
#include "narrows/engines/lgca/moment_propagation.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

namespace narrows::lgca {

namespace {

// Column offset of the source r - c_i of link i for a site in a row of parity o (the row
// offset is dy[i]); link 6 (rest) stays.
constexpr int dy[7] = {0, -1, -1, 0, 1, 1, 0};
int source_dx(int i, int o) {
  constexpr int base[7] = {-1, -1, 0, 1, 0, -1, 0};
  constexpr int odd[7] = {0, 1, 1, 0, 1, 1, 0};
  return base[i] + odd[i] * o;
}

} // namespace

FhpTagged::FhpTagged(const FhpLattice &lattice, int max_lag)
    : slabs_(lattice.slabs()), links_(links(lattice.params().model)), nx_(lattice.local_columns()),
      ny_(lattice.size_y()), max_lag_(max_lag),
      stride_(static_cast<std::size_t>(lattice.local_columns()) + 2) {
  if (max_lag < 1)
    throw input_error("tagged.max_lag = " + std::to_string(max_lag) + " not allowed; need >= 1");
  const std::size_t n = stride_ * static_cast<std::size_t>(ny_);
  occ_.assign(n, 0);
  a_.assign(n, {0.0, 0.0});
  q_.assign(n, {0.0, 0.0});
  const Links l = triangular_links(links_ == 7);
  for (unsigned s = 1; s < (1u << links_); ++s) {
    for (int i = 0; i < links_; ++i)
      if ((s >> i) & 1u) {
        ux_[s] += l.cx[i];
        uy_[s] += l.cy[i];
      }
    ux_[s] /= std::popcount(s);
    uy_[s] /= std::popcount(s);
  }
  sum_.assign(static_cast<std::size_t>(max_lag_) + 1, 0.0);
  sum2_ = sum_;
  rank_ = slabs_.rank();
  for (int r = 0; r < slabs_.ranks(); ++r) {
    counts_.push_back(slabs_.first_column_of(r + 1) - slabs_.first_column_of(r));
    displs_.push_back(slabs_.first_column_of(r));
  }
}

void FhpTagged::load(const FhpLattice &lattice) {
  for (int y = 0; y < ny_; ++y) {
    const std::uint8_t *row = lattice.row(y);
    for (int x = 0; x < nx_; ++x)
      occ_[at(x, y)] = row[x];
  }
  exchange_column_halos(slabs_, occ_.data(), stride_, ny_, nx_, 60);
}

// Eq 13: every particle starts with weight its velocity, arriving at its neighbour.
void FhpTagged::start() {
  const Links l = triangular_links(links_ == 7);
  std::int64_t counts[2] = {0, 0}; // particles, moving particles (c^2 = 1)
  for (int y = 0; y < ny_; ++y) {
    const int o = y % 2;
    for (int x = 0; x < nx_; ++x) {
      const unsigned s = occ_[at(x, y)];
      counts[0] += std::popcount(s);
      counts[1] += std::popcount(s & 0x3Fu);
      std::array<double, 2> w{0.0, 0.0};
      for (int i = 0; i < links_; ++i) {
        const int sy = (y + dy[i] + ny_) % ny_;
        const unsigned src = occ_[at(x + source_dx(i, o), sy)];
        const double bit = static_cast<double>((src >> i) & 1u);
        w[0] += bit * l.cx[i];
        w[1] += bit * l.cy[i];
      }
      a_[at(x, y)] = w;
    }
  }
  std::int64_t total[2] = {0, 0};
  MPI_Allreduce(counts, total, 2, MPI_INT64_T, MPI_SUM, slabs_.comm());
  if (total[0] == 0)
    throw input_error("tagged VACF: the lattice has no particles");
  particles_ = static_cast<double>(total[0]);
  current_.assign(1, static_cast<double>(total[1]) / particles_);
  lag_ = 0;
}

// Eq 14 without the 1/N, summed per global column (y in order), the columns in order on rank 0.
double FhpTagged::correlation() const {
  std::vector<double> cols(static_cast<std::size_t>(nx_), 0.0);
  for (int y = 0; y < ny_; ++y)
    for (int x = 0; x < nx_; ++x) {
      const std::size_t k = at(x, y);
      const unsigned s = occ_[k];
      cols[x] += a_[k][0] * ux_[s] + a_[k][1] * uy_[s];
    }
  std::vector<double> all(rank_ == 0 ? static_cast<std::size_t>(slabs_.columns()) : 0);
  MPI_Gatherv(cols.data(), nx_, MPI_DOUBLE, all.data(), counts_.data(), displs_.data(), MPI_DOUBLE,
              0, slabs_.comm());
  double sum = 0.0;
  for (double c : all)
    sum += c;
  return sum;
}

void FhpTagged::feed(const FhpLattice &lattice) {
  load(lattice);
  if (lag_ < 0) {
    start();
    return;
  }
  current_.push_back(correlation() / particles_);
  ++lag_;
  if (lag_ == max_lag_) {
    if (rank_ == 0)
      for (int t = 0; t <= max_lag_; ++t) {
        const double z = current_[t] / current_[0];
        sum_[t] += z;
        sum2_[t] += z * z;
      }
    particle_sum_ += particles_;
    ++curves_;
    start();
    return;
  }
  // Eq 11, pull form: q = a / rho at every site (halos from the neighbours), then gather.
  for (int y = 0; y < ny_; ++y)
    for (int x = 0; x < nx_; ++x) {
      const std::size_t k = at(x, y);
      const int rho = std::popcount(static_cast<unsigned>(occ_[k]));
      if (rho == 0) {
        if (a_[k][0] != 0.0 || a_[k][1] != 0.0)
          throw invariant_error("moment propagation: tagged weight at the empty site (" +
                                std::to_string(slabs_.first_column() + x) + ", " +
                                std::to_string(y) + ")");
        q_[k] = {0.0, 0.0};
        continue;
      }
      const double inv = 1.0 / rho;
      q_[k] = {a_[k][0] * inv, a_[k][1] * inv};
    }
  exchange_column_halos(slabs_, q_.data(), stride_, ny_, nx_, 62);
  for (int y = 0; y < ny_; ++y) {
    const int o = y % 2;
    for (int x = 0; x < nx_; ++x) {
      std::array<double, 2> w{0.0, 0.0};
      for (int i = 0; i < links_; ++i) {
        const std::size_t src = at(x + source_dx(i, o), (y + dy[i] + ny_) % ny_);
        const double bit = static_cast<double>((occ_[src] >> i) & 1u);
        w[0] += bit * q_[src][0];
        w[1] += bit * q_[src][1];
      }
      a_[at(x, y)] = w;
    }
  }
}

std::vector<double> FhpTagged::mean() const {
  std::vector<double> m;
  if (rank_ != 0 || curves_ == 0)
    return m;
  for (double s : sum_)
    m.push_back(s / curves_);
  return m;
}

std::vector<double> FhpTagged::error() const {
  std::vector<double> e;
  if (rank_ != 0 || curves_ == 0)
    return e;
  for (std::size_t t = 0; t < sum_.size(); ++t) {
    if (curves_ < 2) {
      e.push_back(0.0);
      continue;
    }
    const double m = sum_[t] / curves_;
    const double var = std::max(0.0, (sum2_[t] - curves_ * m * m) / (curves_ - 1));
    e.push_back(std::sqrt(var / curves_));
  }
  return e;
}

} // namespace narrows::lgca
