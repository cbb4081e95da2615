// The fitted steady-state velocity and friction of the jamming model (see
// continuum/jamming_model.hpp).
#include "narrows/engines/continuum/jamming_model.hpp"

#include <cmath>
#include <cstdio>

namespace narrows::continuum {

VssFit table_6_2(scene::JammingFit mu) {
  VssFit f;
  switch (mu) {
  case scene::JammingFit::mu_infinity:
    f = {0.0489, 0.00247, 0.744, 2.82, -3.68, 0.819, 0.0};
    break;
  case scene::JammingFit::mu_1:
    f = {0.0413, 0.0025, 0.762, 2.56, -3.24, 0.845, 0.0};
    break;
  case scene::JammingFit::mu_half:
    f = {0.0247, 0.00312, 0.778, 2.78, -3.45, 0.854, 0.0};
    break;
  case scene::JammingFit::mu_0:
    f = {0.0005, 0.00233, 0.808, 2.90, -3.53, 0.846, 0.0};
    break;
  }
  f.e3 = (f.e1 + f.e2 * f.phi_c) / ((f.phi_c - f.phi_q) * (f.phi_c - f.phi_q));
  return f;
}

VssFit vss_fit_of(const scene::Continuum &m) {
  if (m.vss_source == scene::JammingVss::preset)
    return table_6_2(m.fit);
  const auto &p = m.vss;
  VssFit f{p[0], p[1], p[2], p[3], p[4], p[5], 0.0};
  f.e3 = (f.e1 + f.e2 * f.phi_c) / ((f.phi_c - f.phi_q) * (f.phi_c - f.phi_q));
  return f;
}

std::string vss_source_text(const scene::Continuum &m) {
  switch (m.vss_source) {
  case scene::JammingVss::given:
    return "continuum.vss";
  case scene::JammingVss::file:
    return "continuum.vss_fit = " + m.vss_path;
  default:
    break;
  }
  static const char *const mu[] = {"infinity", "1", "1/2", "0"};
  return std::string("Table 6.2, mu = ") + mu[static_cast<int>(m.fit)];
}

JammingModel::JammingModel(const scene::Continuum &m)
    : fit_(vss_fit_of(m)), drive_(m.drive), diffusion_(m.diffusion) {}

double JammingModel::vss(double phi) const {
  const VssFit &f = fit_;
  const double step = f.dv * (1.0 + std::tanh((f.phi_c - phi) / f.dphi));
  if (phi < f.phi_c)
    return step + f.e1 + f.e2 * phi;
  return step + f.e3 * (phi - f.phi_q) * (phi - f.phi_q);
}

double JammingModel::dvss(double phi) const {
  const VssFit &f = fit_;
  const double t = std::tanh((f.phi_c - phi) / f.dphi);
  const double step = -f.dv * (1.0 - t * t) / f.dphi;
  if (phi < f.phi_c)
    return step + f.e2;
  return step + 2.0 * f.e3 * (phi - f.phi_q);
}

std::string JammingModel::describe() const {
  const VssFit &f = fit_;
  char buf[600];
  std::snprintf(buf, sizeof buf,
                "xi(phi) = sigma / v_ss(phi), sigma = %g; v_ss = %g [1 + tanh((%g - phi) / %g)] "
                "+ { %g %+g phi below phi_c = %g; %.6g (phi - %g)^2 above } (eq 6.4)",
                drive_, f.dv, f.phi_c, f.dphi, f.e1, f.e2, f.phi_c, f.e3, f.phi_q);
  return buf;
}

} // namespace narrows::continuum
