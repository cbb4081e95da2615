// Time-origin averages of the colloid velocity (see lattice/colloid_correlations.hpp).
#include "narrows/engines/lgca/colloid_correlations.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::lgca {

ColloidCorrelations::ColloidCorrelations(int max_lag, int displacement_lag, int every,
                                         std::int64_t steps, std::array<double, 2> reference,
                                         int blocks)
    : max_lag_(max_lag), dlag_(displacement_lag), every_(every), blocks_(blocks),
      reference_(reference), block_steps_(std::max<std::int64_t>(1, steps / blocks)) {
  u_hist_.assign(static_cast<std::size_t>(max_lag_) + 1, {0.0, 0.0});
  x_hist_.assign(static_cast<std::size_t>(dlag_) + 1, {0.0, 0.0});
  const std::size_t nd = static_cast<std::size_t>(dlag_ / every_) + 1;
  vacf_sum_.assign(blocks_, std::vector<double>(max_lag_ + 1, 0.0));
  vacf_n_ = vacf_sum_;
  msd_sum_.assign(blocks_, std::vector<double>(nd, 0.0));
  msd_n_ = msd_sum_;
}

void ColloidCorrelations::add(const std::array<double, 2> &velocity) {
  const std::array<double, 2> u{velocity[0] - reference_[0], velocity[1] - reference_[1]};
  const int b = static_cast<int>(std::min<std::int64_t>(t_ / block_steps_, blocks_ - 1));
  const std::size_t nu = u_hist_.size(), nx = x_hist_.size();
  u_hist_[t_ % nu] = u;
  x_[0] += u[0];
  x_[1] += u[1];
  x_hist_[t_ % nx] = x_;
  // this step closes the lags that end here
  const int lu = static_cast<int>(std::min<std::int64_t>(t_, max_lag_));
  for (int lag = 0; lag <= lu; ++lag) {
    const auto &v = u_hist_[(t_ - lag) % nu];
    vacf_sum_[b][lag] += v[0] * u[0] + v[1] * u[1];
    vacf_n_[b][lag] += 1.0;
  }
  const int lx = static_cast<int>(std::min<std::int64_t>(t_, dlag_));
  for (int lag = every_; lag <= lx; lag += every_) {
    const auto &x0 = x_hist_[(t_ - lag) % nx];
    const double dx = x_[0] - x0[0], dy = x_[1] - x0[1];
    msd_sum_[b][lag / every_] += dx * dx + dy * dy;
    msd_n_[b][lag / every_] += 1.0;
  }
  ++t_;
}

ColloidCorrelations::Curve
ColloidCorrelations::finish(const std::vector<std::vector<double>> &sums,
                            const std::vector<std::vector<double>> &counts,
                            const std::vector<double> &lags, double scale_by_lag) const {
  Curve c;
  c.lags = lags;
  c.blocks.assign(static_cast<std::size_t>(blocks_) * lags.size(), 0.0);
  for (std::size_t k = 0; k < lags.size(); ++k) {
    double s = 0.0, n = 0.0;
    std::vector<double> means;
    for (int b = 0; b < blocks_; ++b) {
      s += sums[b][k];
      n += counts[b][k];
      if (counts[b][k] > 0)
        means.push_back(sums[b][k] / counts[b][k]);
    }
    const double scale = scale_by_lag > 0.0 && lags[k] > 0 ? 1.0 / (scale_by_lag * lags[k]) : 1.0;
    for (int b = 0; b < blocks_; ++b)
      c.blocks[static_cast<std::size_t>(b) * lags.size() + k] =
          counts[b][k] > 0 ? sums[b][k] / counts[b][k] * scale : std::nan("");
    c.value.push_back(n > 0 ? s / n * scale : 0.0);
    double v = 0.0, m = 0.0;
    for (double x : means)
      m += x / means.size();
    for (double x : means)
      v += (x - m) * (x - m);
    c.error.push_back(means.size() > 1 ? std::sqrt(v / (means.size() - 1) / means.size()) * scale
                                       : 0.0);
  }
  return c;
}

ColloidCorrelations::Curve ColloidCorrelations::vacf(double plateau) const {
  std::vector<double> lags;
  for (int t = 0; t <= max_lag_; ++t)
    lags.push_back(t);
  Curve c = finish(vacf_sum_, vacf_n_, lags, 0.0);
  const double u2 = c.value[0];
  if (u2 > 0.0)
    for (std::size_t k = 0; k < c.value.size(); ++k) {
      c.value[k] = c.value[k] / u2 + plateau;
      c.error[k] /= u2;
    }
  for (double &x : c.blocks)
    x = u2 > 0.0 ? x / u2 + plateau : x;
  return c;
}

double ColloidCorrelations::mean_square_velocity() const {
  return finish(vacf_sum_, vacf_n_, {0.0}, 0.0).value[0];
}

ColloidCorrelations::Curve ColloidCorrelations::diffusion(double plateau) const {
  std::vector<double> lags;
  for (int t = 0; t <= dlag_; t += every_)
    lags.push_back(t);
  Curve c = finish(msd_sum_, msd_n_, lags, 4.0);
  const double u2 = mean_square_velocity();
  for (std::size_t k = 0; k < c.value.size(); ++k) {
    c.value[k] += plateau * u2 * lags[k] / 4.0;
    for (int b = 0; b < blocks_; ++b)
      c.blocks[static_cast<std::size_t>(b) * lags.size() + k] += plateau * u2 * lags[k] / 4.0;
  }
  return c;
}

ColloidCorrelations::State ColloidCorrelations::state() const {
  State s;
  s.layout = {max_lag_, dlag_, every_, blocks_, block_steps_, t_};
  const auto put = [&s](const double *p, std::size_t n) {
    s.values.insert(s.values.end(), p, p + n);
  };
  put(reference_.data(), 2);
  put(x_.data(), 2);
  for (const auto &v : u_hist_)
    put(v.data(), 2);
  for (const auto &v : x_hist_)
    put(v.data(), 2);
  for (const auto *table : {&vacf_sum_, &vacf_n_, &msd_sum_, &msd_n_})
    for (const auto &row : *table)
      put(row.data(), row.size());
  return s;
}

bool ColloidCorrelations::restore(const State &s) {
  if (s.layout.size() != 6 || s.layout[0] != max_lag_ || s.layout[1] != dlag_ ||
      s.layout[2] != every_ || s.layout[3] != blocks_ || s.layout[4] < 1 || s.layout[5] < 0 ||
      s.values.size() != state().values.size())
    return false;
  block_steps_ = s.layout[4];
  t_ = s.layout[5];
  std::size_t at = 0;
  const auto take = [&](double *p, std::size_t n) {
    std::copy(s.values.begin() + static_cast<std::ptrdiff_t>(at),
              s.values.begin() + static_cast<std::ptrdiff_t>(at + n), p);
    at += n;
  };
  take(reference_.data(), 2);
  take(x_.data(), 2);
  for (auto &v : u_hist_)
    take(v.data(), 2);
  for (auto &v : x_hist_)
    take(v.data(), 2);
  for (auto *table : {&vacf_sum_, &vacf_n_, &msd_sum_, &msd_n_})
    for (auto &row : *table)
      take(row.data(), row.size());
  return true;
}

} // namespace narrows::lgca
