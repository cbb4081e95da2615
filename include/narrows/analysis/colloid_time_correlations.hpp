// Time correlations of colloids (Kanehl (thesis) §4.4.2): the velocity autocorrelation
// C(tau) = <v(t).v(t+tau)> (eq 4.50), its running integral D(t) = (1/d) int_0^t C (eq 4.51), the
// mean-square displacement <|r(t+tau) - r(t)|^2> and the angular VACF <w(t).w(t+tau)> with its
// integral D_rot(t) = (1/d_rot) int_0^t C_w (d_rot = 1 in 2D, 3 in 3D), per kind of colloid and
// over all colloids. Every sample is a time origin, every colloid of a kind adds to its average.
// Errors: the samples are cut into `blocks` equal blocks of time (by the sample that closes the
// lag), and an error is the spread of the block means over sqrt(blocks with data); an integral's
// error is the spread of the integrals of the block means.
#pragma once

#include "narrows/colloids/colloids.hpp"

#include <array>
#include <cstddef>
#include <vector>

namespace narrows::analysis {

class ColloidTimeCorrelations {
public:
  // kind[i]: the kind (0..kinds-1) of colloid i of every sample (id order); lags 0..max_lag
  // samples, `interval` the time between samples; `expected_samples` sets the block length
  // (at least 1 sample).
  ColloidTimeCorrelations(std::vector<std::size_t> kind, std::size_t kinds, int dim,
                          std::size_t max_lag, double interval, std::size_t expected_samples,
                          std::size_t blocks = 10);

  // One sample of all colloids in id order. Positions are unwrapped here: along an axis k with
  // period[k] > 0 each step between samples is taken as its minimum image.
  void add(const colloids::Colloids &c, const std::array<double, 3> &period);

  struct Result {
    std::vector<double> lags;                   // tau (time units), [lags]
    std::vector<double> value, error;           // over all colloids, [lags]
    std::vector<double> by_kind, error_by_kind; // [kinds][lags], row-major
  };
  Result vacf() const;
  Result diffusion() const; // (1/d) int_0^tau C, trapezoid rule over the lags
  Result msd() const;
  Result angular_vacf() const;
  Result rotational_diffusion() const; // (1/d_rot) int_0^tau C_w
  std::size_t samples() const { return t_; }
  std::size_t kinds() const { return kinds_; }

  // Everything add() accumulated (sample count, block length, unwrapped and last positions, the
  // history and the sums), flat, for a checkpoint; restore() takes it back (a continued run then
  // averages as if it had not stopped) and returns false, changing nothing, if its size is not
  // this object's or its counts are not whole numbers >= 0.
  std::vector<double> state() const;
  bool restore(const std::vector<double> &state);

private:
  enum Quantity { velocity = 0, displacement = 1, angular = 2 };
  Result finish(Quantity q, double integral_scale) const; // integral_scale 0: no integral

  std::vector<std::size_t> kind_;
  std::size_t kinds_, n_;
  int dim_, rdim_;
  std::size_t max_lag_, blocks_, block_len_;
  double interval_;
  std::size_t t_ = 0;
  std::vector<double> unwrapped_, last_;         // [n][dim]
  std::vector<double> v_hist_, x_hist_, w_hist_; // [(max_lag+1)][n][dim or rdim]
  // sums_[q][(block * (kinds + 1) + group) * (max_lag + 1) + lag]; group kinds = all colloids
  std::array<std::vector<double>, 3> sums_;
  std::vector<double> counts_;
};

} // namespace narrows::analysis
