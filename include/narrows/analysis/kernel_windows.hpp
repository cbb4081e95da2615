// Kernel profiles across the channel over consecutive windows of time (Kanehl (thesis) eq 5.2,
// the kernel of KernelDensity): per kind k, the window's mean of
//   F_k(y) = (1/N_k) sum_{i in k} K(y - y_i)           (density, integrates to 1)
// over its samples, and the kernel-weighted mean x velocity of the kind's colloids,
//   v_k(y) = sum_samples sum_{i in k} K(y - y_i) v_x,i / sum_samples sum_{i in k} K(y - y_i),
// with the weight (the denominator) kept so that windows can be merged exactly. One window is
// open at a time; clear() starts the next one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace narrows::analysis {

// Consecutive windows of `length` steps from step `start`, sampled every `every` steps: window w
// holds the samples at steps in (start + w length, start + (w + 1) length] (the first one also a
// sample at start itself) and closes with its last sample.
struct WindowSchedule {
  std::int64_t start = 0, length = 1, every = 1;
  std::int64_t index(std::int64_t step) const {
    return step <= start ? 0 : (step - start - 1) / length;
  }
  std::int64_t end(std::int64_t w) const { return start + (w + 1) * length; }
  // Whether the sample at `step` is the last of its window (the next falls into the next one).
  bool closes(std::int64_t step) const { return step + every > end(index(step)); }
};

class KernelWindow {
public:
  KernelWindow(std::size_t kinds, double length, bool periodic, double width, std::size_t bins);

  // One sample: y[i], the x velocity vx[i] and kind[i] of every colloid.
  void add(std::span<const double> y, std::span<const double> vx,
           std::span<const std::size_t> kind);
  // Starts a new (empty) window.
  void clear();

  std::size_t samples() const { return samples_; }
  std::size_t kinds() const { return kinds_; }
  std::size_t bins() const { return bins_; }
  double width() const { return eps_; }
  std::vector<double> centres() const;
  // [kinds][bins], row-major: the mean F_k over the window's samples (NaN for a kind that had
  // no colloids in any of them), the kernel-weighted x velocity (NaN where the weight is 0) and
  // the weight sums.
  std::vector<double> density() const;
  std::vector<double> velocity() const;
  const std::vector<double> &weight() const { return weight_; }

  // The open window's sums, flat, for a checkpoint; restore() refuses (false, nothing changed)
  // a state of another size or a sample count that is not a whole number >= 0.
  std::vector<double> state() const;
  bool restore(const std::vector<double> &state);

private:
  std::size_t kinds_, bins_;
  double length_, eps_;
  bool periodic_;
  std::size_t samples_ = 0;
  std::vector<double> density_; // [kind][bin]: sum over samples of F_k
  std::vector<double> counts_;  // [kind]: samples in which the kind had colloids
  std::vector<double> weight_;  // [kind][bin]: sum of K
  std::vector<double> moment_;  // [kind][bin]: sum of K v_x
  std::vector<double> one_;     // scratch: one sample's kernel sums [kind][bin]
};

} // namespace narrows::analysis
