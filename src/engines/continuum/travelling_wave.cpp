// Travelling-wave ODEs of the jamming model (see continuum/travelling_wave.hpp).
#include "narrows/engines/continuum/travelling_wave.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace narrows::continuum {

const char *to_string(FixedPointType t) {
  switch (t) {
  case FixedPointType::saddle:
    return "saddle";
  case FixedPointType::node_sink:
    return "node sink";
  case FixedPointType::node_source:
    return "node source";
  case FixedPointType::focus_sink:
    return "focus sink";
  case FixedPointType::focus_source:
    return "focus source";
  case FixedPointType::centre:
    return "centre";
  }
  return "";
}

std::array<double, 2> wave_rhs(const JammingModel &m, double c, double q, double phi, double v) {
  return {((v - c) * phi - q) / m.diffusion(), (m.drive() - m.xi(phi) * v) / (v - c)};
}

Eigen::Matrix2d wave_jacobian(const JammingModel &m, double c, double phi0) {
  const double v0 = m.vss(phi0), D = m.diffusion();
  Eigen::Matrix2d j;
  j << (v0 - c) / D, phi0 / D, -m.dxi(phi0) * v0 / (v0 - c), -m.xi(phi0) / (v0 - c);
  return j;
}

FixedPoint classify(const JammingModel &m, double c, double phi0) {
  FixedPoint f;
  f.phi = phi0;
  f.v = m.vss(phi0);
  const Eigen::EigenSolver<Eigen::Matrix2d> es(wave_jacobian(m, c, phi0));
  f.lambda = {es.eigenvalues()[0], es.eigenvalues()[1]};
  const double r0 = f.lambda[0].real(), r1 = f.lambda[1].real();
  const bool complex_pair = std::abs(f.lambda[0].imag()) > 0.0;
  if (r0 * r1 < 0.0 && !complex_pair)
    f.type = FixedPointType::saddle;
  else if (complex_pair)
    f.type = r0 < 0.0   ? FixedPointType::focus_sink
             : r0 > 0.0 ? FixedPointType::focus_source
                        : FixedPointType::centre;
  else
    f.type = r0 < 0.0 ? FixedPointType::node_sink : FixedPointType::node_source;
  return f;
}

std::vector<FixedPoint> fixed_points(const JammingModel &m, double c, double q, double lo,
                                     double hi, int samples) {
  const auto g = [&](double phi) { return phi * (m.vss(phi) - c) - q; };
  std::vector<FixedPoint> out;
  double a = lo, ga = g(lo);
  for (int i = 1; i <= samples; ++i) {
    const double b = lo + (hi - lo) * i / samples, gb = g(b);
    if (ga == 0.0 || ga * gb < 0.0) {
      double x = a, y = b;
      for (int it = 0; it < 200 && y - x > 1e-15; ++it) {
        const double mid = 0.5 * (x + y);
        (g(mid) * g(x) <= 0.0 ? y : x) = mid;
      }
      out.push_back(classify(m, c, 0.5 * (x + y)));
    }
    a = b;
    ga = gb;
  }
  return out;
}

double hopf_speed(const JammingModel &m, double phi0, bool *valid) {
  const double v0 = m.vss(phi0);
  const double c = v0 - std::sqrt(m.diffusion() * m.xi(phi0));
  if (valid != nullptr)
    *valid = wave_jacobian(m, c, phi0).determinant() > 0.0;
  return c;
}

LimitCycle limit_cycle(const JammingModel &m, double c, double q, const FixedPoint &centre,
                       double dz, double tol, int max_turns) {
  const bool repels = centre.lambda[0].real() > 0.0; // integrate away from the fixed point
  return limit_cycle_from(m, c, q, centre.phi, centre.v * (1.0 + 1e-4) + 1e-6, centre.phi, repels,
                          dz, tol, max_turns);
}

LimitCycle limit_cycle_from(const JammingModel &m, double c, double q, double phi_start,
                            double v_start, double section, bool forward, double dz, double tol,
                            int max_turns) {
  LimitCycle lc;
  const double h = forward ? dz : -dz;
  lc.attracting_forward = forward;
  const auto f = [&](double p, double v) { return wave_rhs(m, c, q, p, v); };
  const auto rk4 = [&](double &p, double &v, double hh) {
    const auto k1 = f(p, v);
    const auto k2 = f(p + 0.5 * hh * k1[0], v + 0.5 * hh * k1[1]);
    const auto k3 = f(p + 0.5 * hh * k2[0], v + 0.5 * hh * k2[1]);
    const auto k4 = f(p + hh * k3[0], v + hh * k3[1]);
    p += hh / 6.0 * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0]);
    v += hh / 6.0 * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1]);
  };
  double p = phi_start, v = v_start;
  // Crossings of phi = section upwards in the direction of integration (v above v0 there).
  double last_v = 0.0, last_s = 0.0, s = 0.0;
  int crossings = 0;
  const std::int64_t max_steps = static_cast<std::int64_t>(max_turns) * 200000;
  for (std::int64_t step = 0; step < max_steps; ++step) {
    const double p_old = p, v_old = v;
    rk4(p, v, h);
    s += dz;
    if (!(p > 0.0 && p < 1.0) || !std::isfinite(v) || std::abs(v - c) < 1e-9)
      return lc; // left the physical range: no cycle
    if ((p_old - section) * (p - section) <= 0.0 && p != p_old &&
        (p - p_old) * (h > 0 ? 1.0 : -1.0) > 0.0) {
      const double w = (section - p_old) / (p - p_old);
      const double vc = v_old + w * (v - v_old), sc = s - dz + w * dz;
      if (crossings > 0 && std::abs(vc - last_v) < tol) {
        lc.found = true;
        lc.period = sc - last_s;
        break;
      }
      last_v = vc;
      last_s = sc;
      ++crossings;
      if (crossings > max_turns)
        return lc;
    }
  }
  if (!lc.found)
    return lc;
  // One more period from the section in n steps of exactly period / n, recorded with z
  // increasing (the profile closes on itself: a periodic initial condition for the PDE).
  const std::int64_t n = static_cast<std::int64_t>(std::ceil(lc.period / dz));
  const double dz_n = lc.period / static_cast<double>(n);
  std::vector<double> zs, ps, vs;
  p = section;
  v = last_v;
  for (std::int64_t i = 0; i < n; ++i) {
    zs.push_back(static_cast<double>(i) * dz_n);
    ps.push_back(p);
    vs.push_back(v);
    rk4(p, v, h > 0.0 ? dz_n : -dz_n);
  }
  if (h < 0.0) { // recorded backwards in z: reverse so that z increases
    std::reverse(ps.begin() + 1, ps.end());
    std::reverse(vs.begin() + 1, vs.end());
  }
  lc.z = zs;
  lc.phi = ps;
  lc.v = vs;
  double sum = 0.0;
  lc.phi_min = ps[0];
  lc.phi_max = ps[0];
  for (double x : ps) {
    sum += x;
    lc.phi_min = std::min(lc.phi_min, x);
    lc.phi_max = std::max(lc.phi_max, x);
  }
  lc.phi_mean = sum / static_cast<double>(ps.size());
  if (lc.phi_max - lc.phi_min < 1e-6) // converged onto a fixed point, not a cycle
    lc = LimitCycle{};
  return lc;
}

} // namespace narrows::continuum
