// Steady profiles of the segregation model by shooting (see continuum/segregation_steady.hpp).
#include "narrows/engines/continuum/segregation_steady.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace narrows::continuum {

namespace {

using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, max_segregation_kinds, 1>;
using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor,
                          max_segregation_kinds, max_segregation_kinds>;

// phi' = -M^-1 b at (phi, y); false outside the model's domain or where M is singular.
bool slope(const SegregationModel &model, const double *phi, double y, double *out) {
  const std::size_t n = model.kinds();
  if (!model.admissible(phi))
    return false;
  Mat m(n, n);
  Vec b(n);
  model.coefficients(phi, y, m.data(), b.data());
  const Eigen::FullPivLU<Mat> lu(m);
  if (!lu.isInvertible())
    return false;
  const Vec s = -lu.solve(b);
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = s[static_cast<Eigen::Index>(i)];
    if (!std::isfinite(out[i]))
      return false;
  }
  return true;
}

// RK4 from y = 0 (phi = centre) to w, accumulating the means; false if it leaves the domain.
bool shoot(const SegregationModel &model, const double *centre, std::size_t steps,
           SteadyProfile *keep, double *mean) {
  const std::size_t n = model.kinds(), m = 2 * n;
  const double w = model.half_width(), h = w / static_cast<double>(steps);
  double u[2 * max_segregation_kinds], k[4][2 * max_segregation_kinds],
      t[2 * max_segregation_kinds];
  for (std::size_t i = 0; i < n; ++i) {
    u[i] = centre[i];
    u[n + i] = 0.0; // integral of phi_i from 0 to y
  }
  // The state's derivative: (phi', phi). At y = 0 the shear rate's slope is that of y -> 0+.
  const auto rhs = [&](const double *s, double y, double *d) {
    if (!slope(model, s, y > 0.0 ? y : 1e-300, d))
      return false;
    for (std::size_t i = 0; i < n; ++i)
      d[n + i] = s[i];
    return true;
  };
  if (keep != nullptr) {
    keep->phi.assign((steps + 1) * n, 0.0);
    keep->dphi.assign((steps + 1) * n, 0.0);
  }
  for (std::size_t s = 0; s <= steps; ++s) {
    const double y = static_cast<double>(s) * h;
    if (!rhs(u, y, k[0]))
      return false;
    if (keep != nullptr)
      for (std::size_t i = 0; i < n; ++i) {
        keep->phi[s * n + i] = u[i];
        keep->dphi[s * n + i] = k[0][i];
      }
    if (s == steps)
      break;
    for (std::size_t i = 0; i < m; ++i)
      t[i] = u[i] + 0.5 * h * k[0][i];
    if (!rhs(t, y + 0.5 * h, k[1]))
      return false;
    for (std::size_t i = 0; i < m; ++i)
      t[i] = u[i] + 0.5 * h * k[1][i];
    if (!rhs(t, y + 0.5 * h, k[2]))
      return false;
    for (std::size_t i = 0; i < m; ++i)
      t[i] = u[i] + h * k[2][i];
    if (!rhs(t, y + h, k[3]))
      return false;
    for (std::size_t i = 0; i < m; ++i)
      u[i] += h / 6.0 * (k[0][i] + 2.0 * k[1][i] + 2.0 * k[2][i] + k[3][i]);
  }
  for (std::size_t i = 0; i < n; ++i)
    mean[i] = u[n + i] / w;
  return true;
}

} // namespace

SteadyProfile steady_profile(const SegregationModel &model, std::size_t steps) {
  const std::size_t n = model.kinds();
  const auto &kinds = model.parameters().kinds;
  SteadyProfile out;
  out.kinds = n;
  out.step = model.half_width() / static_cast<double>(steps);
  double u[max_segregation_kinds], f[max_segregation_kinds], g[max_segregation_kinds];
  for (std::size_t i = 0; i < n; ++i)
    u[i] = kinds[i].fraction;
  const auto residual = [&](const double *c, double *r) {
    double mean[max_segregation_kinds];
    if (!shoot(model, c, steps, nullptr, mean))
      return false;
    for (std::size_t i = 0; i < n; ++i)
      r[i] = mean[i] - kinds[i].fraction;
    return true;
  };
  const auto size = [&](const double *r) {
    double s = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      s = std::max(s, std::abs(r[i]));
    return s;
  };
  if (!residual(u, f)) {
    out.failure = "the profile from the uniform centre values leaves the model's domain";
    return out;
  }
  for (out.iterations = 0; out.iterations < 100 && size(f) > 1e-13; ++out.iterations) {
    Mat jac(n, n);
    for (std::size_t j = 0; j < n; ++j) {
      double v[max_segregation_kinds];
      std::copy(u, u + n, v);
      const double d = 1e-7 * std::max(u[j], 1e-3);
      v[j] += d;
      if (!residual(v, g)) {
        v[j] = u[j] - d;
        if (!residual(v, g)) {
          out.failure = "no Jacobian: the profile leaves the model's domain";
          return out;
        }
        for (std::size_t i = 0; i < n; ++i)
          jac(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = (f[i] - g[i]) / d;
      } else {
        for (std::size_t i = 0; i < n; ++i)
          jac(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = (g[i] - f[i]) / d;
      }
    }
    Vec r(n);
    for (std::size_t i = 0; i < n; ++i)
      r[static_cast<Eigen::Index>(i)] = f[i];
    const Vec du = -jac.fullPivLu().solve(r);
    // Backtracking: halve the step until the profile stays in the domain and the residual falls.
    double lambda = 1.0;
    bool moved = false;
    for (int tries = 0; tries < 40 && !moved; ++tries, lambda *= 0.5) {
      double v[max_segregation_kinds];
      for (std::size_t i = 0; i < n; ++i)
        v[i] = u[i] + lambda * du[static_cast<Eigen::Index>(i)];
      if (residual(v, g) && size(g) < size(f)) {
        std::copy(v, v + n, u);
        std::copy(g, g + n, f);
        moved = true;
      }
    }
    if (!moved)
      break;
  }
  out.mass_error = size(f);
  if (out.mass_error > 1e-10) {
    out.failure = "Newton's method stalls at a mean off by " + std::to_string(out.mass_error);
    return out;
  }
  double mean[max_segregation_kinds];
  shoot(model, u, steps, &out, mean);
  out.ok = true;
  return out;
}

std::vector<double> steady_at(const SteadyProfile &p, const std::vector<double> &ys) {
  const std::size_t n = p.kinds, last = p.phi.size() / n - 1;
  std::vector<double> out(ys.size() * n);
  for (std::size_t q = 0; q < ys.size(); ++q) {
    const double x = std::abs(ys[q]) / p.step;
    const std::size_t k = std::min(static_cast<std::size_t>(x), last - 1);
    const double s = x - static_cast<double>(k), h = p.step;
    const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s);
    const double h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
    for (std::size_t i = 0; i < n; ++i)
      out[q * n + i] = h00 * p.phi[k * n + i] + h10 * h * p.dphi[k * n + i] +
                       h01 * p.phi[(k + 1) * n + i] + h11 * h * p.dphi[(k + 1) * n + i];
  }
  return out;
}

} // namespace narrows::continuum
