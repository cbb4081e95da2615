// Fluid observables and their reductions over ranks.
#include "narrows/analysis/fluid_observables.hpp"

#include "narrows/core/fixed_point.hpp"

namespace narrows::analysis {

std::array<double, 3> MomentumSum::value() const {
  return {fixed::to_double(fixed[0]), fixed::to_double(fixed[1]), fixed::to_double(fixed[2])};
}

MomentumSum total_momentum(const mpcd::Fluid &fluid, MPI_Comm comm) {
  std::int64_t local[4] = {0, 0, 0, static_cast<std::int64_t>(fluid.size())};
  for (int k = 0; k < fluid.dim; ++k)
    for (double v : fluid.v[k])
      local[k] += fixed::from_double(v);
  std::int64_t global[4];
  MPI_Allreduce(local, global, 4, MPI_INT64_T, MPI_SUM, comm);
  MomentumSum m;
  for (int k = 0; k < 3; ++k)
    m.fixed[k] = global[k];
  m.count = static_cast<std::uint64_t>(global[3]);
  return m;
}

double temperature(const mpcd::Fluid &fluid, MPI_Comm comm) {
  double local = 0.0;
  for (int k = 0; k < fluid.dim; ++k)
    for (double v : fluid.v[k])
      local += v * v;
  double sum_v2 = 0.0;
  MPI_Allreduce(&local, &sum_v2, 1, MPI_DOUBLE, MPI_SUM, comm);
  const MomentumSum m = total_momentum(fluid, comm);
  const auto p = m.value();
  const double n = static_cast<double>(m.count);
  if (m.count < 2)
    return 0.0;
  return (sum_v2 - (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) / n) / (fluid.dim * (n - 1.0));
}

ProfileAccumulator::ProfileAccumulator(const mpcd::Box &box)
    : dim_(box.dim), bin_width_(1.0), centres_(box.cells[1]) {
  bin_volume_ = box.length[0] * bin_width_ * (box.dim == 3 ? box.length[2] : 1.0);
  for (int b = 0; b < box.cells[1]; ++b)
    centres_[b] = (b + 0.5) * bin_width_;
  sum_v_.assign(centres_.size() * dim_, 0.0);
  count_.assign(centres_.size(), 0.0);
}

void ProfileAccumulator::add(const mpcd::Fluid &fluid) {
  const int nb = static_cast<int>(centres_.size());
  const double inv_w = 1.0 / bin_width_;
  const double *y = fluid.x[1].data();
  for (std::size_t i = 0; i < fluid.size(); ++i) {
    int b = static_cast<int>(y[i] * inv_w);
    b = b < nb ? b : nb - 1;
    count_[b] += 1.0;
    for (int k = 0; k < dim_; ++k)
      sum_v_[b * dim_ + k] += fluid.v[k][i];
  }
  ++samples_;
}

bool ProfileAccumulator::finish(MPI_Comm comm, std::vector<double> &velocity,
                                std::vector<double> &density) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<double> sv(sum_v_.size()), cnt(count_.size());
  MPI_Reduce(sum_v_.data(), sv.data(), static_cast<int>(sv.size()), MPI_DOUBLE, MPI_SUM, 0, comm);
  MPI_Reduce(count_.data(), cnt.data(), static_cast<int>(cnt.size()), MPI_DOUBLE, MPI_SUM, 0, comm);
  const double samples = static_cast<double>(samples_);
  std::fill(sum_v_.begin(), sum_v_.end(), 0.0);
  std::fill(count_.begin(), count_.end(), 0.0);
  samples_ = 0;
  if (rank != 0 || samples == 0.0)
    return false;
  velocity.assign(sv.size(), 0.0);
  density.assign(cnt.size(), 0.0);
  for (std::size_t b = 0; b < cnt.size(); ++b) {
    density[b] = cnt[b] / (samples * bin_volume_);
    for (int k = 0; k < dim_; ++k)
      velocity[b * dim_ + k] = cnt[b] > 0 ? sv[b * dim_ + k] / cnt[b] : 0.0;
  }
  return true;
}

} // namespace narrows::analysis
