// The pseudo-spectral solver of the jamming model (continuum/jamming_model.hpp) on a periodic
// grid of N points x_i = i L / N. One step of dt is a Strang splitting:
//   1. dt/2 of the local relaxation v_t = sigma - xi(phi) v at frozen phi, solved exactly
//      (v -> v_ss + (v - v_ss) exp(-xi dt/2)), so the stiff friction of jams (xi up to ~1e4)
//      sets no time step;
//   2. dt of transport phi_t = -(phi v)_x + D phi_xx, v_t = -(v^2/2)_x in Fourier space (FFTW):
//      the diffusion exactly by an integrating factor, the rest by fourth-order Runge-Kutta
//      (Lawson's IF-RK4), derivatives spectral, the 2/3 rule against aliasing;
//   3. dt/2 of relaxation again.
// Second order in time, spectral in space for the modes kept (|n| < N/3); the mean of phi (the
// mass) is conserved to rounding. Plans are FFTW_ESTIMATE on buffers it owns, so the same input
// gives the same bits in every run (bitwise restarts).
#pragma once

#include "narrows/engines/continuum/jamming_model.hpp"

#include <complex>
#include <cstddef>
#include <vector>

namespace narrows::continuum {

class JammingSolver {
public:
  JammingSolver(const JammingModel &model, std::size_t points, double length);
  ~JammingSolver();
  JammingSolver(const JammingSolver &) = delete;
  JammingSolver &operator=(const JammingSolver &) = delete;

  // Advances phi and v (values at the grid points) by dt.
  void step(std::vector<double> &phi, std::vector<double> &v, double dt);
  // The highest wave number kept by the 2/3 rule (2 pi n_max / L).
  double k_max() const;

private:
  using Spectrum = std::vector<std::complex<double>>;
  void relax(const std::vector<double> &phi, std::vector<double> &v, double h) const;
  // (d phi^/dt, d v^/dt) of the transport part without diffusion.
  void nonlinear(const Spectrum &phi_hat, const Spectrum &v_hat, Spectrum &dphi, Spectrum &dv);
  void forward(const std::vector<double> &x, Spectrum &out); // with the 2/3 truncation
  void backward(const Spectrum &in, std::vector<double> &x);

  JammingModel model_;
  std::size_t n_ = 0, modes_ = 0, kept_ = 0; // points, N/2+1 modes, modes below the 2/3 cut
  double length_ = 1.0;
  std::vector<double> k_;           // wave numbers of the modes
  std::vector<double> half_, full_; // exp(-D k^2 h/2), exp(-D k^2 h) for the last h
  double last_h_ = -1.0;
  double *real_ = nullptr; // FFTW buffers
  void *complex_ = nullptr;
  void *plan_r2c_ = nullptr, *plan_c2r_ = nullptr;
  std::vector<double> a_, b_, prod_; // real-space work arrays
  Spectrum p0_, v0_, p1_, v1_, ka_p_, ka_v_, kb_p_, kb_v_, kc_p_, kc_v_, kd_p_, kd_v_, tmp_;
};

} // namespace narrows::continuum
