// Time-origin averages of a held colloid's velocity (seed 002 §4.3, eq 5 and 29): the VACF
// <U(0).U(t)> for lags 0..max_lag and the virtual displacement X(t) = sum of U (one step per
// unit time), its mean square <|X(t0 + t) - X(t0)|^2> and D(t) = msd / (4 t) at lags that are
// multiples of `every`. Every step is a time origin. Errors: the run is cut into `blocks` equal
// blocks of time origins, and the error is the spread of the block means over sqrt(blocks).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace narrows::lattice {

class ColloidCorrelations {
public:
  ColloidCorrelations(int max_lag, int displacement_lag, int every, std::int64_t steps,
                      int blocks = 10);

  void add(const std::array<double, 2> &u); // the velocity after each step, in order

  struct Curve {
    std::vector<double> lags, value, error;
  };
  Curve vacf() const;      // normalised by <U^2> (lag 0)
  Curve diffusion() const; // D(t) = msd / (4 t)
  double mean_square_velocity() const;

private:
  Curve finish(const std::vector<std::vector<double>> &sums,
               const std::vector<std::vector<double>> &counts, const std::vector<double> &lags,
               double scale_by_lag) const;

  int max_lag_, dlag_, every_, blocks_;
  std::int64_t block_steps_, t_ = 0;
  std::vector<std::array<double, 2>> u_hist_, x_hist_; // ring buffers
  std::array<double, 2> x_{0.0, 0.0};
  std::vector<std::vector<double>> vacf_sum_, vacf_n_, msd_sum_, msd_n_; // [block][lag]
};

} // namespace narrows::lattice
