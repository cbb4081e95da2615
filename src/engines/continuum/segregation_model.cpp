// The segregation theory's currents (see continuum/segregation_model.hpp).
#include "narrows/engines/continuum/segregation_model.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::continuum {

SegregationModel::SegregationModel(const scene::Segregation &s)
    : p_(s), n_(s.kinds.size()), w_(s.half_width) {
  const double d = s.dimensions;
  for (std::size_t i = 0; i < n_; ++i) {
    mean_ += s.kinds[i].fraction;
    volume_[i] = std::pow(s.kinds[i].radius, d);
    for (std::size_t j = 0; j < n_; ++j) {
      const double ai = s.kinds[i].radius, aj = s.kinds[j].radius, r = ai / aj;
      a_[i][j] = (ai + aj) * (ai + aj) / std::pow(2.0, d + 1.0) * std::pow(1.0 + r, d) /
                 (1.0 + std::pow(r, d));
    }
  }
  eta_mean_ = viscosity(mean_);
}

double SegregationModel::viscosity(double total) const {
  const double u = 1.0 - total / p_.max_packing;
  return 1.0 / (u * u);
}

double SegregationModel::structure_factor(const double *phi) const {
  double total = 0.0, c[max_segregation_kinds]{}, csum = 0.0;
  for (std::size_t i = 0; i < n_; ++i) {
    total += phi[i];
    c[i] = phi[i] / volume_[i]; // number density up to a constant factor
    csum += c[i];
  }
  if (p_.dimensions == 2) {
    // Boublik: gamma = (sum x_i a_i)^2 / sum x_i a_i^2 with the number fractions x_i (1 for one
    // kind); S = (1 - phi)^2 / (1 - phi (1 - gamma)).
    double gamma = 1.0;
    if (n_ > 1 && csum > 0.0) {
      double s1 = 0.0, s2 = 0.0;
      for (std::size_t i = 0; i < n_; ++i) {
        const double x = c[i] / csum, a = p_.kinds[i].radius;
        s1 += x * a;
        s2 += x * a * a;
      }
      gamma = s1 * s1 / s2;
    }
    return (1.0 - total) * (1.0 - total) / (1.0 - total * (1.0 - gamma));
  }
  // 3D: S = (1 - phi)^4 / ((1 + 2 phi)^2 - Delta), Delta of eq 5.22 (0 for one kind).
  double delta = 0.0;
  if (n_ > 1 && csum > 0.0) {
    const std::size_t s = p_.kinds[0].radius <= p_.kinds[1].radius ? 0 : 1, l = 1 - s;
    const double alpha = p_.kinds[s].radius / p_.kinds[l].radius, x = c[s] / csum;
    const double q = x + (1.0 - x) * alpha * alpha * alpha;
    delta =
        3.0 * x * (1.0 - x) * total * (1.0 - alpha) * (1.0 - alpha) / q *
        ((2.0 + total) * (1.0 + alpha) + 3.0 * total * alpha / q * ((1.0 - x) * alpha * alpha + x));
  }
  const double u = 1.0 - total, v = 1.0 + 2.0 * total;
  return u * u * u * u / (v * v - delta);
}

void SegregationModel::collective_diffusivity(const double *phi, double *dc) const {
  const double diag = p_.k_d / structure_factor(phi);
  for (std::size_t i = 0; i < n_; ++i) {
    const double dii = diag * p_.kinds[i].diffusivity;
    for (std::size_t k = 0; k < n_; ++k)
      dc[i * n_ + k] = k == i ? dii : dii * phi[i] / ((1.0 - phi[k]) * (1.0 - phi[k]));
  }
}

double SegregationModel::shear_rate(const double *phi, double y) const {
  const double base = 2.0 * p_.centre_speed * std::abs(y) / (w_ * w_);
  if (p_.shear == scene::SegregationShear::poiseuille)
    return base;
  double total = 0.0;
  for (std::size_t i = 0; i < n_; ++i)
    total += phi[i];
  return base * eta_mean_ / viscosity(total);
}

void SegregationModel::coefficients(const double *phi, double y, double *m, double *b) const {
  double total = 0.0;
  for (std::size_t i = 0; i < n_; ++i)
    total += phi[i];
  const double sign = y > 0.0 ? 1.0 : (y < 0.0 ? -1.0 : 0.0);
  const double log_eta = 2.0 / (p_.max_packing - total); // eta' / eta
  const double gdot = shear_rate(phi, y);
  // d gdot / dy = g_y + g_phi sum_k phi_k'
  double g_y = 2.0 * p_.centre_speed / (w_ * w_) * sign, g_phi = 0.0;
  if (p_.shear == scene::SegregationShear::viscous) {
    g_y *= eta_mean_ / viscosity(total);
    g_phi = -gdot * log_eta;
  }
  const double common = p_.k_c * g_phi + p_.k_eta * gdot * log_eta;
  double dc[max_segregation_kinds * max_segregation_kinds];
  collective_diffusivity(phi, dc);
  for (std::size_t i = 0; i < n_; ++i) {
    double s = 0.0;
    for (std::size_t j = 0; j < n_; ++j)
      s += a_[i][j] * phi[j];
    for (std::size_t k = 0; k < n_; ++k)
      m[i * n_ + k] = phi[i] * p_.k_c * gdot * a_[i][k] + phi[i] * s * common + dc[i * n_ + k];
    b[i] = phi[i] * s * p_.k_c * g_y;
  }
}

void SegregationModel::rates(const double *phi, double y, double &diffusive, double &drift) const {
  double m[max_segregation_kinds * max_segregation_kinds], b[max_segregation_kinds];
  coefficients(phi, y, m, b);
  diffusive = 0.0;
  drift = 0.0;
  for (std::size_t i = 0; i < n_; ++i) {
    double row = 0.0;
    for (std::size_t k = 0; k < n_; ++k)
      row += std::abs(m[i * n_ + k]);
    diffusive = std::max(diffusive, row);
    if (phi[i] > 0.0)
      drift = std::max(drift, std::abs(b[i] / phi[i]));
  }
}

bool SegregationModel::admissible(const double *phi) const {
  double total = 0.0;
  for (std::size_t i = 0; i < n_; ++i) {
    if (!(phi[i] >= 0.0))
      return false;
    total += phi[i];
  }
  return total < p_.max_packing;
}

double SegregationModel::peclet(std::size_t i) const {
  const double a = p_.kinds[i].radius;
  return a * a * a * p_.centre_speed / (w_ * w_ * p_.kinds[i].diffusivity);
}

double SegregationModel::migration_ratio(std::size_t i, const double *phi, double y) const {
  const double a = p_.kinds[i].radius;
  return p_.k_c * a * a * shear_rate(phi, y) * phi[i] / (p_.k_d * p_.kinds[i].diffusivity);
}

} // namespace narrows::continuum
