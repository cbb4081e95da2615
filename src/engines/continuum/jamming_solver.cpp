// Strang-split pseudo-spectral steps of the jamming model (see continuum/jamming_solver.hpp).
#include "narrows/engines/continuum/jamming_solver.hpp"

#include <fftw3.h>

#include <cmath>
#include <cstring>
#include <numbers>

namespace narrows::continuum {

namespace {

fftw_complex *as_fftw(void *p) { return static_cast<fftw_complex *>(p); }

} // namespace

JammingSolver::JammingSolver(const JammingModel &model, std::size_t points, double length)
    : model_(model), n_(points), modes_(points / 2 + 1), length_(length) {
  // Mode m is kept when m < N/3 (the 2/3 rule: products of kept modes alias only onto
  // dropped ones).
  kept_ = 0;
  while (kept_ < modes_ && 3 * kept_ < n_)
    ++kept_;
  k_.resize(modes_);
  for (std::size_t m = 0; m < modes_; ++m)
    k_[m] = 2.0 * std::numbers::pi * static_cast<double>(m) / length;
  real_ = fftw_alloc_real(n_);
  complex_ = fftw_alloc_complex(modes_);
  plan_r2c_ = fftw_plan_dft_r2c_1d(static_cast<int>(n_), real_, as_fftw(complex_), FFTW_ESTIMATE);
  plan_c2r_ = fftw_plan_dft_c2r_1d(static_cast<int>(n_), as_fftw(complex_), real_, FFTW_ESTIMATE);
  a_.resize(n_);
  b_.resize(n_);
  prod_.resize(n_);
  for (Spectrum *s : {&p0_, &v0_, &p1_, &v1_, &ka_p_, &ka_v_, &kb_p_, &kb_v_, &kc_p_, &kc_v_,
                      &kd_p_, &kd_v_, &tmp_})
    s->assign(modes_, 0.0);
  half_.resize(modes_);
  full_.resize(modes_);
}

JammingSolver::~JammingSolver() {
  fftw_destroy_plan(static_cast<fftw_plan>(plan_r2c_));
  fftw_destroy_plan(static_cast<fftw_plan>(plan_c2r_));
  fftw_free(real_);
  fftw_free(complex_);
}

double JammingSolver::k_max() const { return k_[kept_ - 1]; }

void JammingSolver::forward(const std::vector<double> &x, Spectrum &out) {
  std::memcpy(real_, x.data(), n_ * sizeof(double));
  fftw_execute(static_cast<fftw_plan>(plan_r2c_));
  const fftw_complex *c = as_fftw(complex_);
  const double norm = 1.0 / static_cast<double>(n_);
  for (std::size_t m = 0; m < modes_; ++m)
    out[m] = m < kept_ ? std::complex<double>(c[m][0] * norm, c[m][1] * norm) : 0.0;
}

void JammingSolver::backward(const Spectrum &in, std::vector<double> &x) {
  fftw_complex *c = as_fftw(complex_);
  for (std::size_t m = 0; m < modes_; ++m) {
    c[m][0] = in[m].real();
    c[m][1] = in[m].imag();
  }
  fftw_execute(static_cast<fftw_plan>(plan_c2r_));
  std::memcpy(x.data(), real_, n_ * sizeof(double));
}

void JammingSolver::relax(const std::vector<double> &phi, std::vector<double> &v, double h) const {
  const double sigma = model_.drive();
  for (std::size_t i = 0; i < n_; ++i) {
    const double vs = model_.vss(phi[i]);
    // v_ss = 0 (phi at phi_q of the fit): infinite friction, v stops.
    v[i] = vs > 0.0 ? vs + (v[i] - vs) * std::exp(-sigma * h / vs) : vs;
  }
}

void JammingSolver::nonlinear(const Spectrum &phi_hat, const Spectrum &v_hat, Spectrum &dphi,
                              Spectrum &dv) {
  backward(phi_hat, a_);
  backward(v_hat, b_);
  for (std::size_t i = 0; i < n_; ++i)
    prod_[i] = a_[i] * b_[i];
  forward(prod_, dphi);
  for (std::size_t i = 0; i < n_; ++i)
    prod_[i] = 0.5 * b_[i] * b_[i];
  forward(prod_, dv);
  for (std::size_t m = 0; m < modes_; ++m) {
    const std::complex<double> minus_ik(0.0, -k_[m]);
    dphi[m] *= minus_ik;
    dv[m] *= minus_ik;
  }
}

void JammingSolver::step(std::vector<double> &phi, std::vector<double> &v, double dt) {
  relax(phi, v, 0.5 * dt);
  if (dt != last_h_) {
    const double D = model_.diffusion();
    for (std::size_t m = 0; m < modes_; ++m) {
      half_[m] = std::exp(-D * k_[m] * k_[m] * 0.5 * dt);
      full_[m] = half_[m] * half_[m];
    }
    last_h_ = dt;
  }
  forward(phi, p0_);
  forward(v, v0_);
  // Lawson IF-RK4: phi^ carries the integrating factor exp(-D k^2 t), v^ none.
  const double h = dt;
  nonlinear(p0_, v0_, ka_p_, ka_v_);
  for (std::size_t m = 0; m < modes_; ++m) {
    p1_[m] = half_[m] * (p0_[m] + 0.5 * h * ka_p_[m]);
    v1_[m] = v0_[m] + 0.5 * h * ka_v_[m];
  }
  nonlinear(p1_, v1_, kb_p_, kb_v_);
  for (std::size_t m = 0; m < modes_; ++m) {
    p1_[m] = half_[m] * p0_[m] + 0.5 * h * kb_p_[m];
    v1_[m] = v0_[m] + 0.5 * h * kb_v_[m];
  }
  nonlinear(p1_, v1_, kc_p_, kc_v_);
  for (std::size_t m = 0; m < modes_; ++m) {
    p1_[m] = full_[m] * p0_[m] + h * half_[m] * kc_p_[m];
    v1_[m] = v0_[m] + h * kc_v_[m];
  }
  nonlinear(p1_, v1_, kd_p_, kd_v_);
  for (std::size_t m = 0; m < modes_; ++m) {
    p0_[m] = full_[m] * p0_[m] +
             h / 6.0 * (full_[m] * ka_p_[m] + 2.0 * half_[m] * (kb_p_[m] + kc_p_[m]) + kd_p_[m]);
    v0_[m] = v0_[m] + h / 6.0 * (ka_v_[m] + 2.0 * (kb_v_[m] + kc_v_[m]) + kd_v_[m]);
  }
  backward(p0_, phi);
  backward(v0_, v);
  relax(phi, v, 0.5 * dt);
}

} // namespace narrows::continuum
