// Time correlations of colloids: VACF, D(t), MSD, angular VACF (see the header).
#include "narrows/analysis/colloid_time_correlations.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace narrows::analysis {

ColloidTimeCorrelations::ColloidTimeCorrelations(std::vector<std::size_t> kind, std::size_t kinds,
                                                 int dim, std::size_t max_lag, double interval,
                                                 std::size_t expected_samples, std::size_t blocks)
    : kind_(std::move(kind)), kinds_(kinds), n_(kind_.size()), dim_(dim), rdim_(dim == 2 ? 1 : 3),
      max_lag_(max_lag), blocks_(std::max<std::size_t>(1, blocks)),
      block_len_(std::max<std::size_t>(1, expected_samples / std::max<std::size_t>(1, blocks))),
      interval_(interval) {
  const std::size_t slots = max_lag_ + 1;
  unwrapped_.assign(n_ * dim_, 0.0);
  last_ = unwrapped_;
  v_hist_.assign(slots * n_ * dim_, 0.0);
  x_hist_ = v_hist_;
  w_hist_.assign(slots * n_ * rdim_, 0.0);
  const std::size_t table = blocks_ * (kinds_ + 1) * slots;
  for (auto &s : sums_)
    s.assign(table, 0.0);
  counts_.assign(table, 0.0);
}

void ColloidTimeCorrelations::add(const colloids::Colloids &c,
                                  const std::array<double, 3> &period) {
  const std::size_t slots = max_lag_ + 1, slot = t_ % slots;
  const int d = dim_, rd = rdim_;
  for (std::size_t i = 0; i < n_; ++i)
    for (int k = 0; k < d; ++k) {
      const double x = c.x[k][i];
      double step = t_ == 0 ? 0.0 : x - last_[i * d + k];
      if (period[k] > 0.0)
        step -= period[k] * std::round(step / period[k]);
      unwrapped_[i * d + k] = t_ == 0 ? x : unwrapped_[i * d + k] + step;
      last_[i * d + k] = x;
      v_hist_[(slot * n_ + i) * d + k] = c.v[k][i];
      x_hist_[(slot * n_ + i) * d + k] = unwrapped_[i * d + k];
    }
  for (std::size_t i = 0; i < n_; ++i)
    for (int k = 0; k < rd; ++k)
      w_hist_[(slot * n_ + i) * rd + k] = c.omega[rd == 1 ? 2 : k][i];
  const std::size_t b = std::min(t_ / block_len_, blocks_ - 1);
  const std::size_t top = std::min(t_, max_lag_);
  for (std::size_t lag = 0; lag <= top; ++lag) {
    const std::size_t s0 = (t_ - lag) % slots;
    for (std::size_t i = 0; i < n_; ++i) {
      double vv = 0.0, xx = 0.0, ww = 0.0;
      for (int k = 0; k < d; ++k) {
        vv += v_hist_[(s0 * n_ + i) * d + k] * v_hist_[(slot * n_ + i) * d + k];
        const double dx = x_hist_[(slot * n_ + i) * d + k] - x_hist_[(s0 * n_ + i) * d + k];
        xx += dx * dx;
      }
      for (int k = 0; k < rd; ++k)
        ww += w_hist_[(s0 * n_ + i) * rd + k] * w_hist_[(slot * n_ + i) * rd + k];
      for (const std::size_t g : {kind_[i], kinds_}) {
        const std::size_t at = (b * (kinds_ + 1) + g) * slots + lag;
        sums_[velocity][at] += vv;
        sums_[displacement][at] += xx;
        sums_[angular][at] += ww;
        counts_[at] += 1.0;
      }
    }
  }
  ++t_;
}

ColloidTimeCorrelations::Result ColloidTimeCorrelations::finish(Quantity q,
                                                                double integral_scale) const {
  const std::size_t slots = max_lag_ + 1;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Result r;
  for (std::size_t lag = 0; lag < slots; ++lag)
    r.lags.push_back(static_cast<double>(lag) * interval_);
  const auto trapezoid = [&](std::vector<double> &f) { // f becomes its running integral
    double acc = 0.0, prev = f.empty() ? 0.0 : f[0];
    for (std::size_t l = 0; l < f.size(); ++l) {
      if (l > 0)
        acc += 0.5 * (prev + f[l]) * interval_;
      prev = f[l];
      f[l] = acc * integral_scale;
    }
  };
  for (std::size_t g = 0; g <= kinds_; ++g) {
    std::vector<double> total(slots, 0.0), count(slots, 0.0);
    std::vector<std::vector<double>> means; // per block with data, the prefix it covers
    for (std::size_t b = 0; b < blocks_; ++b) {
      std::vector<double> m;
      for (std::size_t lag = 0; lag < slots; ++lag) {
        const std::size_t at = (b * (kinds_ + 1) + g) * slots + lag;
        total[lag] += sums_[q][at];
        count[lag] += counts_[at];
        if (counts_[at] > 0.0 && m.size() == lag) // a contiguous prefix of lags
          m.push_back(sums_[q][at] / counts_[at]);
      }
      if (!m.empty()) {
        if (integral_scale > 0.0)
          trapezoid(m);
        means.push_back(std::move(m));
      }
    }
    std::vector<double> value(slots), error(slots);
    for (std::size_t lag = 0; lag < slots; ++lag)
      value[lag] = count[lag] > 0.0 ? total[lag] / count[lag] : nan;
    if (integral_scale > 0.0)
      trapezoid(value);
    for (std::size_t lag = 0; lag < slots; ++lag) {
      double mean = 0.0, var = 0.0, n = 0.0;
      for (const auto &m : means)
        if (m.size() > lag) {
          mean += m[lag];
          n += 1.0;
        }
      mean /= std::max(n, 1.0);
      for (const auto &m : means)
        if (m.size() > lag)
          var += (m[lag] - mean) * (m[lag] - mean);
      error[lag] = n > 1.0 ? std::sqrt(var / (n - 1.0) / n) : nan;
    }
    if (g == kinds_) {
      r.value = value;
      r.error = error;
    } else {
      r.by_kind.insert(r.by_kind.end(), value.begin(), value.end());
      r.error_by_kind.insert(r.error_by_kind.end(), error.begin(), error.end());
    }
  }
  return r;
}

ColloidTimeCorrelations::Result ColloidTimeCorrelations::vacf() const {
  return finish(velocity, 0.0);
}
ColloidTimeCorrelations::Result ColloidTimeCorrelations::diffusion() const {
  return finish(velocity, 1.0 / dim_);
}
ColloidTimeCorrelations::Result ColloidTimeCorrelations::msd() const {
  return finish(displacement, 0.0);
}
ColloidTimeCorrelations::Result ColloidTimeCorrelations::angular_vacf() const {
  return finish(angular, 0.0);
}
ColloidTimeCorrelations::Result ColloidTimeCorrelations::rotational_diffusion() const {
  return finish(angular, 1.0 / rdim_);
}

std::vector<double> ColloidTimeCorrelations::state() const {
  std::vector<double> s{static_cast<double>(t_), static_cast<double>(block_len_)};
  for (const auto *v : {&unwrapped_, &last_, &v_hist_, &x_hist_, &w_hist_, &sums_[0], &sums_[1],
                        &sums_[2], &counts_})
    s.insert(s.end(), v->begin(), v->end());
  return s;
}

bool ColloidTimeCorrelations::restore(const std::vector<double> &s) {
  if (s.size() != state().size() || !(s[0] >= 0.0 && s[1] >= 1.0) || s[0] != std::floor(s[0]) ||
      s[1] != std::floor(s[1]))
    return false;
  t_ = static_cast<std::size_t>(s[0]);
  block_len_ = static_cast<std::size_t>(s[1]);
  std::size_t at = 2;
  for (auto *v : {&unwrapped_, &last_, &v_hist_, &x_hist_, &w_hist_, &sums_[0], &sums_[1],
                  &sums_[2], &counts_}) {
    std::copy(s.begin() + static_cast<std::ptrdiff_t>(at),
              s.begin() + static_cast<std::ptrdiff_t>(at + v->size()), v->begin());
    at += v->size();
  }
  return true;
}

} // namespace narrows::analysis
