// The jamming model of Kanehl (thesis) ch.6 (eq 6.2-6.3): the area fraction phi(x, t) and the flow
// velocity v(x, t) of colloids driven through a channel,
//   phi_t + (phi v)_x = D phi_xx,      v_t + v v_x = sigma - xi(phi) v,
// with the friction xi(phi) = sigma / v_ss(phi) taken from the fitted steady-state velocity
// v_ss (eq 6.4, the parameters of Table 6.2 for the wall friction mu). With sigma = D = 1 these
// are the normalised eq 6.5-6.6 of the thesis (time (D / sigma^2)^(1/3), length (D^2/sigma)^(1/3)).
#pragma once

#include "narrows/scene/scene.hpp"

#include <string>

namespace narrows::continuum {

// v_ss(phi) = dv [1 + tanh((phi_c - phi) / dphi)] + { e1 + e2 phi (phi < phi_c),
//                                                     e3 (phi - phi_q)^2 (phi >= phi_c) }
// with e3 = (e1 + e2 phi_c) / (phi_c - phi_q)^2 (continuous at phi_c; eq 6.4).
struct VssFit {
  double dv = 0.0, dphi = 1.0, phi_c = 0.0, e1 = 0.0, e2 = 0.0, phi_q = 0.0, e3 = 0.0;
};

// Table 6.2, one column per wall friction mu.
VssFit table_6_2(scene::JammingFit mu);
// The scene's parameters: Table 6.2's column continuum.mu, or continuum.vss, or the file of
// continuum.vss_fit (e3 from continuity, computed alike in all three cases).
VssFit vss_fit_of(const scene::Continuum &m);
// Where they came from, for the log: "Table 6.2, mu = 1", "continuum.vss" or the fit file.
std::string vss_source_text(const scene::Continuum &m);

class JammingModel {
public:
  JammingModel(const VssFit &fit, double drive, double diffusion)
      : fit_(fit), drive_(drive), diffusion_(diffusion) {}
  explicit JammingModel(const scene::Continuum &m);

  // The steady-state velocity and its derivative d v_ss / d phi (analytic).
  double vss(double phi) const;
  double dvss(double phi) const;
  // The friction xi = sigma / v_ss and d xi / d phi = -sigma v_ss' / v_ss^2.
  double xi(double phi) const { return drive_ / vss(phi); }
  double dxi(double phi) const {
    const double v = vss(phi);
    return -drive_ * dvss(phi) / (v * v);
  }
  double drive() const { return drive_; }
  double diffusion() const { return diffusion_; }
  const VssFit &fit() const { return fit_; }
  // The formula with its parameters, for check/info and the log.
  std::string describe() const;

private:
  VssFit fit_;
  double drive_ = 1.0, diffusion_ = 1.0;
};

} // namespace narrows::continuum
