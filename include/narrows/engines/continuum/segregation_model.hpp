// The segregation theory of Kanehl (thesis) ch.5 (sec 5.2): one or two colloid kinds across a
// channel y in [-w, w] in pressure-driven flow. Kind i (radius a_i, single-colloid diffusivity
// D_0^i) has the area (volume) fraction phi_i(y, t) and the current (eq 5.14)
//   J_i = -phi_i A_ij [K_c (phi_j gdot)' + K_eta phi_j gdot eta'/eta] - D_C^ij phi_j',
// with the coupling matrix A of eq 5.13, the collective diffusion D_C^ii = K_d D_0^i / S(phi)
// (eq 5.23-5.24, S of eq 5.19-5.20 in 2D, 5.21-5.22 in 3D), D_C^ij = D_C^ii phi_i / (1 -
// phi_j)^2 (eq 5.28), the viscosity eta = eta_0 (1 - phi / phi_M)^-2 (eq 5.29) of the total
// phi = sum phi_i, and the shear rate gdot = 2 v0 |y| / w^2 (Poiseuille flow of centre speed v0)
// or, with shear "viscous", that of a constant pressure gradient in the local viscosity,
// gdot = 2 v0 |y| eta(phi_mean) / (w^2 eta(phi)) (the same flow rate scale for a uniform
// suspension). Written as J = -(M phi' + b), M and b depending on phi and y only.
#pragma once

#include "narrows/scene/scene.hpp"

#include <array>
#include <cstddef>
#include <string>

namespace narrows::continuum {

inline constexpr std::size_t max_segregation_kinds = 2;

class SegregationModel {
public:
  explicit SegregationModel(const scene::Segregation &s);

  std::size_t kinds() const { return n_; }
  double half_width() const { return w_; }
  const scene::Segregation &parameters() const { return p_; }
  // A_ij of eq 5.13 (A_ii = a_i^2).
  double coupling(std::size_t i, std::size_t j) const { return a_[i][j]; }
  // S(phi) of eq 5.19-5.20 (2D, Boublik) or 5.21-5.22 (3D); phi = the fractions of the kinds.
  double structure_factor(const double *phi) const;
  // eta / eta_0 of eq 5.29 at the total fraction.
  double viscosity(double total) const;
  // D_C (row-major n x n) at the fractions phi: D_C^ii = K_d D_0^i / S(phi) (eq 5.23-5.24),
  // D_C^ij = D_C^ii phi_i / (1 - phi_j)^2 (eq 5.28); the diffusive part of M.
  void collective_diffusivity(const double *phi, double *dc) const;
  // The shear rate at y (its sign-free size |dv/dy|).
  double shear_rate(const double *phi, double y) const;
  // M (row-major n x n) and b of J = -(M phi' + b) at the fractions phi and position y.
  void coefficients(const double *phi, double y, double *m, double *b) const;
  // Largest row sum of |M| (a bound on its eigenvalues, the diffusive time-step limit) and the
  // largest drift speed |b_i / phi_i| at (phi, y).
  void rates(const double *phi, double y, double &diffusive, double &drift) const;
  // Whether phi is inside the model's domain: every phi_i >= 0, total < phi_M.
  bool admissible(const double *phi) const;
  // Peclet number a^3 v0 / (w^2 D_0) of kind i (eq 5.1).
  double peclet(std::size_t i) const;
  // The thesis' ratio of shear migration to diffusion K_c a_i^2 gdot phi_i / (K_d D_0^i) (sec
  // 5.3.3) at the fractions phi and position y.
  double migration_ratio(std::size_t i, const double *phi, double y) const;

private:
  scene::Segregation p_;
  std::size_t n_ = 1;
  double w_ = 1.0, mean_ = 0.0, eta_mean_ = 1.0;
  std::array<std::array<double, max_segregation_kinds>, max_segregation_kinds> a_{};
  std::array<double, max_segregation_kinds> volume_{}; // a_i^d (number density c_i ~ phi_i / a_i^d)
};

} // namespace narrows::continuum
