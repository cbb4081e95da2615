// Kernel density profiles across the channel (Kanehl (thesis) eq 5.2): per kind k,
//   F_k(y) = (1/N_k) sum_{i in k} 3/(4 eps^3) (eps^2 - (y - y_i)^2) H(eps - |y - y_i|),
// the Epanechnikov kernel of half-width eps (it integrates to 1, so F_k is the probability
// density of a k colloid's y), evaluated at the centres of `bins` equal bins of [0, length),
// averaged over samples. Along a periodic axis distances are minimum images. Errors: the samples
// are cut into `blocks` equal blocks of time, the error is the spread of the block means over
// sqrt(blocks with data).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace narrows::analysis {

// The Epanechnikov kernel 3/(4 eps^3) (eps^2 - u^2) for |u| < eps, else 0 (eq 5.2).
double epanechnikov(double u, double eps);

// The centres (j + 1/2) length / bins of `bins` equal bins of [0, length).
std::vector<double> bin_centres(double length, std::size_t bins);

// One sample's kernel sums at the centres of `bins` equal bins of [0, length): for every
// colloid i, density[kind_i][j] += K(y_j - y_i) and, when `vx` is given,
// velocity[kind_i][j] += K(y_j - y_i) vx_i (minimum images along a periodic axis).
void kernel_sums(std::span<const double> y, std::span<const std::size_t> kind, double length,
                 bool periodic, double eps, std::size_t bins, std::span<double> density,
                 std::span<const double> vx = {}, std::span<double> velocity = {});

class KernelDensity {
public:
  KernelDensity(std::size_t kinds, double length, bool periodic, double width, std::size_t bins,
                std::size_t expected_samples, std::size_t blocks = 10);

  // One sample: y[i] and kind[i] of every colloid.
  void add(std::span<const double> y, std::span<const std::size_t> kind);

  std::vector<double> centres() const;
  // [kinds][bins], row-major: the mean over samples and its error.
  std::vector<double> value() const;
  std::vector<double> error() const;
  std::size_t samples() const { return t_; }
  std::size_t bins() const { return bins_; }
  double width() const { return eps_; }

  // Sample count, block length and the sums, flat, for a checkpoint; restore() as in
  // ColloidTimeCorrelations.
  std::vector<double> state() const;
  bool restore(const std::vector<double> &state);

private:
  std::size_t kinds_, bins_, blocks_, block_len_;
  double length_, eps_;
  bool periodic_;
  std::size_t t_ = 0;
  std::vector<double> sums_;   // [block][kind][bin]
  std::vector<double> counts_; // [block][kind]: samples in which the kind had colloids
  std::vector<double> one_;    // scratch: one sample's profile [kind][bin]
};

} // namespace narrows::analysis
