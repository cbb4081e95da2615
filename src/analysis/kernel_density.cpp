// Kernel density profiles across the channel (see the header).
#include "narrows/analysis/kernel_density.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace narrows::analysis {

double epanechnikov(double u, double eps) {
  return std::abs(u) < eps ? 0.75 * (eps * eps - u * u) / (eps * eps * eps) : 0.0;
}

KernelDensity::KernelDensity(std::size_t kinds, double length, bool periodic, double width,
                             std::size_t bins, std::size_t expected_samples, std::size_t blocks)
    : kinds_(kinds), bins_(bins), blocks_(std::max<std::size_t>(1, blocks)),
      block_len_(std::max<std::size_t>(1, expected_samples / std::max<std::size_t>(1, blocks))),
      length_(length), eps_(width), periodic_(periodic) {
  sums_.assign(blocks_ * kinds_ * bins_, 0.0);
  counts_.assign(blocks_ * kinds_, 0.0);
  one_.assign(kinds_ * bins_, 0.0);
}

std::vector<double> bin_centres(double length, std::size_t bins) {
  std::vector<double> y(bins);
  for (std::size_t j = 0; j < bins; ++j)
    y[j] = (static_cast<double>(j) + 0.5) * length / static_cast<double>(bins);
  return y;
}

std::vector<double> KernelDensity::centres() const { return bin_centres(length_, bins_); }

void kernel_sums(std::span<const double> y, std::span<const std::size_t> kind, double length,
                 bool periodic, double eps, std::size_t bins, std::span<double> density,
                 std::span<const double> vx, std::span<double> velocity) {
  const double h = length / static_cast<double>(bins);
  const auto nb = static_cast<long>(bins);
  const bool with_v = !vx.empty();
  for (std::size_t i = 0; i < y.size(); ++i) {
    // The bins whose centres lie within eps of y_i (wrapped along a periodic axis).
    const long lo = static_cast<long>(std::floor((y[i] - eps) / h - 0.5));
    const long hi = static_cast<long>(std::ceil((y[i] + eps) / h - 0.5));
    for (long j = lo; j <= hi; ++j) {
      long jj = j;
      if (periodic)
        jj = ((j % nb) + nb) % nb;
      else if (j < 0 || j >= nb)
        continue;
      const double centre = (static_cast<double>(j) + 0.5) * h; // unwrapped: the right image
      const double k = epanechnikov(centre - y[i], eps);
      const std::size_t at = kind[i] * bins + static_cast<std::size_t>(jj);
      density[at] += k;
      if (with_v)
        velocity[at] += k * vx[i];
    }
  }
}

void KernelDensity::add(std::span<const double> y, std::span<const std::size_t> kind) {
  std::fill(one_.begin(), one_.end(), 0.0);
  std::vector<double> n(kinds_, 0.0);
  for (std::size_t i = 0; i < y.size(); ++i)
    n[kind[i]] += 1.0;
  kernel_sums(y, kind, length_, periodic_, eps_, bins_, one_);
  const std::size_t b = std::min(t_ / block_len_, blocks_ - 1);
  for (std::size_t k = 0; k < kinds_; ++k) {
    if (n[k] == 0.0)
      continue;
    counts_[b * kinds_ + k] += 1.0;
    for (std::size_t j = 0; j < bins_; ++j)
      sums_[(b * kinds_ + k) * bins_ + j] += one_[k * bins_ + j] / n[k];
  }
  ++t_;
}

std::vector<double> KernelDensity::value() const {
  std::vector<double> out(kinds_ * bins_, 0.0);
  for (std::size_t k = 0; k < kinds_; ++k) {
    double n = 0.0;
    for (std::size_t b = 0; b < blocks_; ++b)
      n += counts_[b * kinds_ + k];
    for (std::size_t j = 0; j < bins_; ++j) {
      double s = 0.0;
      for (std::size_t b = 0; b < blocks_; ++b)
        s += sums_[(b * kinds_ + k) * bins_ + j];
      out[k * bins_ + j] = n > 0.0 ? s / n : std::numeric_limits<double>::quiet_NaN();
    }
  }
  return out;
}

std::vector<double> KernelDensity::error() const {
  std::vector<double> out(kinds_ * bins_, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < kinds_; ++k)
    for (std::size_t j = 0; j < bins_; ++j) {
      double mean = 0.0, var = 0.0, n = 0.0;
      for (std::size_t b = 0; b < blocks_; ++b)
        if (counts_[b * kinds_ + k] > 0.0) {
          mean += sums_[(b * kinds_ + k) * bins_ + j] / counts_[b * kinds_ + k];
          n += 1.0;
        }
      if (n < 2.0)
        continue;
      mean /= n;
      for (std::size_t b = 0; b < blocks_; ++b)
        if (counts_[b * kinds_ + k] > 0.0) {
          const double m = sums_[(b * kinds_ + k) * bins_ + j] / counts_[b * kinds_ + k];
          var += (m - mean) * (m - mean);
        }
      out[k * bins_ + j] = std::sqrt(var / (n - 1.0) / n);
    }
  return out;
}

std::vector<double> KernelDensity::state() const {
  std::vector<double> s{static_cast<double>(t_), static_cast<double>(block_len_)};
  s.insert(s.end(), sums_.begin(), sums_.end());
  s.insert(s.end(), counts_.begin(), counts_.end());
  return s;
}

bool KernelDensity::restore(const std::vector<double> &s) {
  if (s.size() != 2 + sums_.size() + counts_.size() || !(s[0] >= 0.0 && s[1] >= 1.0) ||
      s[0] != std::floor(s[0]) || s[1] != std::floor(s[1]))
    return false;
  t_ = static_cast<std::size_t>(s[0]);
  block_len_ = static_cast<std::size_t>(s[1]);
  const auto sums_end = s.begin() + 2 + static_cast<std::ptrdiff_t>(sums_.size());
  std::copy(s.begin() + 2, sums_end, sums_.begin());
  std::copy(sums_end, s.end(), counts_.begin());
  return true;
}

} // namespace narrows::analysis
