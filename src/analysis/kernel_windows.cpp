// Kernel profiles over windows of time (see the header).
#include "narrows/analysis/kernel_windows.hpp"

#include "narrows/analysis/kernel_density.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace narrows::analysis {

KernelWindow::KernelWindow(std::size_t kinds, double length, bool periodic, double width,
                           std::size_t bins)
    : kinds_(kinds), bins_(bins), length_(length), eps_(width), periodic_(periodic) {
  density_.assign(kinds_ * bins_, 0.0);
  counts_.assign(kinds_, 0.0);
  weight_.assign(kinds_ * bins_, 0.0);
  moment_.assign(kinds_ * bins_, 0.0);
  one_.assign(kinds_ * bins_, 0.0);
}

std::vector<double> KernelWindow::centres() const { return bin_centres(length_, bins_); }

void KernelWindow::add(std::span<const double> y, std::span<const double> vx,
                       std::span<const std::size_t> kind) {
  std::fill(one_.begin(), one_.end(), 0.0);
  std::vector<double> n(kinds_, 0.0);
  for (std::size_t i = 0; i < y.size(); ++i)
    n[kind[i]] += 1.0;
  // The weights and moments go straight into the window's sums; the density per sample is
  // normalised by the kind's count first (as in KernelDensity).
  kernel_sums(y, kind, length_, periodic_, eps_, bins_, one_, vx, moment_);
  for (std::size_t k = 0; k < kinds_; ++k) {
    if (n[k] == 0.0)
      continue;
    counts_[k] += 1.0;
    for (std::size_t j = 0; j < bins_; ++j) {
      weight_[k * bins_ + j] += one_[k * bins_ + j];
      density_[k * bins_ + j] += one_[k * bins_ + j] / n[k];
    }
  }
  ++samples_;
}

void KernelWindow::clear() {
  samples_ = 0;
  std::fill(density_.begin(), density_.end(), 0.0);
  std::fill(counts_.begin(), counts_.end(), 0.0);
  std::fill(weight_.begin(), weight_.end(), 0.0);
  std::fill(moment_.begin(), moment_.end(), 0.0);
}

std::vector<double> KernelWindow::density() const {
  std::vector<double> out(kinds_ * bins_);
  for (std::size_t k = 0; k < kinds_; ++k)
    for (std::size_t j = 0; j < bins_; ++j)
      out[k * bins_ + j] = counts_[k] > 0.0 ? density_[k * bins_ + j] / counts_[k]
                                            : std::numeric_limits<double>::quiet_NaN();
  return out;
}

std::vector<double> KernelWindow::velocity() const {
  std::vector<double> out(kinds_ * bins_);
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = weight_[i] > 0.0 ? moment_[i] / weight_[i] : std::numeric_limits<double>::quiet_NaN();
  return out;
}

std::vector<double> KernelWindow::state() const {
  std::vector<double> s{static_cast<double>(samples_)};
  for (const auto *v : {&density_, &counts_, &weight_, &moment_})
    s.insert(s.end(), v->begin(), v->end());
  return s;
}

bool KernelWindow::restore(const std::vector<double> &s) {
  if (s.size() != 1 + 3 * kinds_ * bins_ + kinds_ || !(s[0] >= 0.0) || s[0] != std::floor(s[0]))
    return false;
  samples_ = static_cast<std::size_t>(s[0]);
  auto at = s.begin() + 1;
  for (auto *v : {&density_, &counts_, &weight_, &moment_}) {
    std::copy(at, at + static_cast<std::ptrdiff_t>(v->size()), v->begin());
    at += static_cast<std::ptrdiff_t>(v->size());
  }
  return true;
}

} // namespace narrows::analysis
