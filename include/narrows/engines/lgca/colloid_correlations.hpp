// Time-origin averages of a colloid's velocity (van der Hoef & Frenkel §4.3, eq 5 and 29): the VACF
// <U(0).U(t)> for lags 0..max_lag and the virtual displacement X(t) = sum of U (one step per
// unit time), its mean square <|X(t0 + t) - X(t0)|^2> and D(t) = msd / (4 t) at lags that are
// multiples of `every`. Every step is a time origin. Errors: the run is cut into `blocks` equal
// blocks of time origins, and the error is the spread of the block means over sqrt(blocks).
//
// The velocity is taken relative to a `reference`, the centre-of-mass velocity V of fluid +
// colloid, which total-momentum conservation keeps fixed: U - V has mean zero, so neither a
// plateau |V|^2 in the VACF nor a ballistic drift |V|^2 t^2 in the mean square displacement.
// What remains is the VACF at total momentum exactly zero, which lacks the share of the
// colloid's momentum that the k = 0 mode keeps for ever. The analogue of van der Hoef & Frenkel
// eq 22 adds it back: with total momentum P = M U + P_fluid free (canonical),
// <U(0).V> = M <U^2> / M_tot, so
//   Z(t) = Z_P0(t) + M / M_tot,   D(t) = D_P0(t) + (M / M_tot) <U^2> t / 4,
// with M the mass moving with U (disc + gas inside) and M_tot that of disc + all gas (the
// `plateau` argument of vacf() and diffusion()). The derivation: given P, the colloid's mean
// velocity is V = P / M_tot (equipartition), so <U(0).U(t)> = <dU(0).dU(t)> + <V^2> and
// <V^2> / <U^2> = M / M_tot. This is the canonical VACF of the periodic box. Against the
// infinite system, for L / c_s << t << L^2 / nu, it is still about M / (2 M_tot) too high:
// the longitudinal half of the colloid's momentum leaves as sound and fills the box within
// a few L / c_s (its echoes average out), the transverse half diffuses as in the infinite
// system (mode sum = integral). So Z_infinite ~ Z - M / (2 M_tot) there.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace narrows::lgca {

class ColloidCorrelations {
public:
  ColloidCorrelations(int max_lag, int displacement_lag, int every, std::int64_t steps,
                      std::array<double, 2> reference = {0.0, 0.0}, int blocks = 10);

  void add(const std::array<double, 2> &u); // the velocity after each step, in order

  struct Curve {
    std::vector<double> lags, value, error;
    // The block means, row-major [block][lag], with the same normalisation and plateau: for
    // errors of derived quantities (local exponents, fits) from the spread over blocks.
    std::vector<double> blocks;
  };
  int blocks() const { return blocks_; }
  // Normalised by <(U - V)^2> (lag 0); plus `plateau` (M / M_tot for the eq 22 analogue).
  Curve vacf(double plateau = 0.0) const;
  // D(t) = msd / (4 t) of the displacement of U - V; plus plateau <(U - V)^2> t / 4.
  Curve diffusion(double plateau = 0.0) const;
  double mean_square_velocity() const; // <(U - V)^2>

  // Everything add() has accumulated, for a checkpoint: `layout` = {max_lag, displacement_lag,
  // every, blocks, block_steps, t}, `values` = reference, displacement, the two ring buffers
  // and the block sums and counts, flattened. restore() takes them back (a continued run then
  // averages as if it had not stopped) and returns false, changing nothing, if the layout's
  // lags and blocks are not this object's.
  struct State {
    std::vector<std::int64_t> layout;
    std::vector<double> values;
  };
  State state() const;
  bool restore(const State &s);

private:
  Curve finish(const std::vector<std::vector<double>> &sums,
               const std::vector<std::vector<double>> &counts, const std::vector<double> &lags,
               double scale_by_lag) const;

  int max_lag_, dlag_, every_, blocks_;
  std::array<double, 2> reference_;
  std::int64_t block_steps_, t_ = 0;
  std::vector<std::array<double, 2>> u_hist_, x_hist_; // ring buffers
  std::array<double, 2> x_{0.0, 0.0};
  std::vector<std::vector<double>> vacf_sum_, vacf_n_, msd_sum_, msd_n_; // [block][lag]
};

} // namespace narrows::lgca
