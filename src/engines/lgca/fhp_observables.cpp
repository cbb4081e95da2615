// Observables of the FHP lattice from integer per-row sums reduced over ranks.
#include "narrows/engines/lgca/fhp_observables.hpp"

#include <bit>
#include <cmath>

namespace narrows::lgca {

namespace {

// 2 c_ix of the six links, and c_iy in units of sqrt(3)/2.
constexpr int cx2[6] = {2, 1, -1, -2, -1, 1}, cy2[6] = {0, 1, 1, 0, -1, -1};

// 2 j_x of each state, as a table.
struct MomentumTable {
  std::array<std::int8_t, 128> x{}, y{};
  MomentumTable() {
    for (int s = 0; s < 128; ++s)
      for (int i = 0; i < 6; ++i)
        if (s >> i & 1) {
          x[s] = static_cast<std::int8_t>(x[s] + cx2[i]);
          y[s] = static_cast<std::int8_t>(y[s] + cy2[i]);
        }
  }
};
const MomentumTable momentum;

std::int64_t row_sum(const FhpLattice &l, int y, bool mass) {
  std::int64_t sum = 0;
  const std::uint8_t *r = l.row(y);
  for (int x = 0; x < l.local_columns(); ++x)
    sum += mass ? std::popcount(static_cast<unsigned>(r[x])) : momentum.x[r[x] & 0x7F];
  return sum;
}

std::int64_t reduce(std::int64_t local, MPI_Comm comm) {
  std::int64_t total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_INT64_T, MPI_SUM, comm);
  return total;
}

} // namespace

std::int64_t total_mass(const FhpLattice &l) {
  std::int64_t m = 0;
  for (int y = 0; y < l.size_y(); ++y)
    m += row_sum(l, y, true);
  return reduce(m, l.comm());
}

std::int64_t total_momentum_x2(const FhpLattice &l) {
  std::int64_t p = 0;
  for (int y = 0; y < l.size_y(); ++y)
    p += row_sum(l, y, false);
  return reduce(p, l.comm());
}

double shear_wave_amplitude(const FhpLattice &l) {
  const int Y = l.size_y();
  std::vector<std::int64_t> local(static_cast<std::size_t>(Y) + 1), total(local.size());
  for (int y = 0; y < Y; ++y) {
    local[y] = row_sum(l, y, false);
    local[Y] += row_sum(l, y, true);
  }
  MPI_Allreduce(local.data(), total.data(), Y + 1, MPI_INT64_T, MPI_SUM, l.comm());
  const double sites = static_cast<double>(l.size_x()) * Y;
  const double rho = static_cast<double>(total[Y]) / sites;
  double s = 0.0;
  for (int y = 0; y < Y; ++y)
    s += 0.5 * static_cast<double>(total[y]) * std::sin(6.283185307179586 * y / Y);
  return 2.0 * s / (sites * rho);
}

FieldAccumulator::FieldAccumulator(const FhpLattice &l, int block)
    : block_(block), bx_(l.size_x() / block), by_(l.size_y() / block) {
  const std::size_t n = static_cast<std::size_t>(bx_) * static_cast<std::size_t>(by_);
  mass_.assign(n, 0);
  jx2_.assign(n, 0);
  jy2_.assign(n, 0);
}

void FieldAccumulator::add(const FhpLattice &l) {
  const int x0 = l.first_column();
  for (int y = 0; y < l.size_y(); ++y) {
    const std::uint8_t *r = l.row(y);
    const std::size_t base = static_cast<std::size_t>(y / block_) * static_cast<std::size_t>(bx_);
    for (int x = 0; x < l.local_columns(); ++x) {
      const std::size_t b = base + static_cast<std::size_t>((x0 + x) / block_);
      const unsigned s = r[x] & 0x7Fu;
      mass_[b] += std::popcount(s);
      jx2_[b] += momentum.x[s];
      jy2_[b] += momentum.y[s];
    }
  }
  ++samples_;
}

bool FieldAccumulator::finish(MPI_Comm comm, std::vector<double> &density,
                              std::vector<double> &velocity) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  density.clear();
  velocity.clear();
  if (samples_ == 0)
    return false;
  const int n = static_cast<int>(mass_.size());
  std::vector<std::int64_t> all(3 * mass_.size()), sum(rank == 0 ? all.size() : 0);
  std::copy(mass_.begin(), mass_.end(), all.begin());
  std::copy(jx2_.begin(), jx2_.end(), all.begin() + n);
  std::copy(jy2_.begin(), jy2_.end(), all.begin() + 2 * n);
  MPI_Reduce(all.data(), sum.data(), 3 * n, MPI_INT64_T, MPI_SUM, 0, comm);
  if (rank == 0) {
    const double per = static_cast<double>(samples_) * block_ * block_;
    density.resize(mass_.size());
    velocity.resize(2 * mass_.size());
    for (int b = 0; b < n; ++b) {
      const double m = static_cast<double>(sum[b]);
      density[b] = m / per;
      velocity[2 * b] = m > 0 ? 0.5 * static_cast<double>(sum[n + b]) / m : 0.0;
      velocity[2 * b + 1] =
          m > 0 ? 0.8660254037844386 * static_cast<double>(sum[2 * n + b]) / m : 0.0;
    }
  }
  std::fill(mass_.begin(), mass_.end(), 0);
  std::fill(jx2_.begin(), jx2_.end(), 0);
  std::fill(jy2_.begin(), jy2_.end(), 0);
  samples_ = 0;
  return rank == 0;
}

} // namespace narrows::lgca
