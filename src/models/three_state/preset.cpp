// Presets of Tabatabaei (2008) ch.2: derived quantities and condition residuals
// (see kmc/preset.hpp).
#include "narrows/models/three_state/preset.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace narrows::three_state {

namespace {

// Tabatabaei's w_ij (i target label, j initial label, label = pair code + 1).
struct SeedRates {
  const std::array<double, 81> &r;
  double operator()(int i, int j) const { return r[(j - 1) * 9 + (i - 1)]; }
};

void set_w(std::array<double, 81> &rates, int i, int j, double v) {
  rates[(j - 1) * 9 + (i - 1)] = v;
}

std::string fmt(const char *format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

std::string fmt2(const char *format, double a, double b) {
  char buf[128];
  std::snprintf(buf, sizeof buf, format, a, b);
  return buf;
}

// Scale of the rates, for deciding whether a residual is round-off.
double rate_scale(const Model &m) {
  double s = 0.0;
  for (double x : m.rates)
    s = std::max(s, std::abs(x));
  for (double x : m.left)
    s = std::max(s, std::abs(x));
  for (double x : m.right)
    s = std::max(s, std::abs(x));
  return std::max(s, 1e-300);
}

std::array<double, 3> site_generator(const std::array<double, 9> &site,
                                     const std::array<double, 3> &p) {
  std::array<double, 3> g{};
  for (int from = 0; from < 3; ++from)
    for (int to = 0; to < 3; ++to)
      if (from != to) {
        const double flow = site[from * 3 + to] * p[from];
        g[to] += flow;
        g[from] -= flow;
      }
  return g;
}

} // namespace

std::array<double, 81> family2_rates(const std::array<double, 6> &h, const std::array<double, 9> &r,
                                     double c) {
  std::array<double, 81> w{};
  // eq 2.86: reactions r_i and their PT partners c r_i (c^2 r_7), hops h_i.
  const int pairs[9][4] = {{4, 7, 3, 2}, {4, 3, 7, 2}, {2, 3, 7, 4}, {2, 7, 3, 4}, {5, 8, 6, 5},
                           {5, 6, 8, 5}, {5, 9, 9, 5}, {8, 9, 9, 6}, {6, 9, 9, 8}};
  for (int i = 0; i < 9; ++i) {
    set_w(w, pairs[i][0], pairs[i][1], r[i]);
    set_w(w, pairs[i][2], pairs[i][3], (i == 6 ? c * c : c) * r[i]);
  }
  set_w(w, 4, 2, h[0]); // h1: 0A -> A0
  set_w(w, 7, 3, h[1]); // h2: 0B -> B0
  set_w(w, 2, 4, h[2]); // h3: A0 -> 0A
  set_w(w, 8, 6, h[3]); // h4: AB -> BA
  set_w(w, 6, 8, h[4]); // h5: BA -> AB
  set_w(w, 3, 7, h[5]); // h6: B0 -> 0B
  return w;
}

double family1_ratio(const std::array<double, 81> &rates) {
  const SeedRates w{rates};
  const double num = w(3, 5) + w(7, 5), den = w(5, 3) + w(5, 7);
  if (den > 0.0)
    return num / den;
  return 1.0;
}

std::array<double, 3> preset_marginal(Preset preset, double ratio, double z) {
  std::array<double, 3> p =
      preset == Preset::family1 ? std::array{1.0, z, ratio * z * z} : std::array{1.0, z, ratio * z};
  const double nu = p[0] + p[1] + p[2];
  for (double &x : p)
    x /= nu;
  return p;
}

std::array<int, 3> preset_charge(Preset preset) {
  if (preset == Preset::family1)
    return {1, 0, -1};
  if (preset == Preset::family2)
    return {0, 1, 1};
  return {0, 1, 2};
}

int vacancy_state(Preset preset) { return preset == Preset::family1 ? 1 : 0; }

BulkFit bulk_fit(const std::array<double, 81> &rates, const std::array<double, 3> &p, int vacancy) {
  // g = G (p x p) on the 9 pair states.
  std::array<double, 9> g{};
  for (int from = 0; from < 9; ++from)
    for (int to = 0; to < 9; ++to)
      if (from != to) {
        const double flow = rates[from * 9 + to] * p[from / 3] * p[from % 3];
        g[to] += flow;
        g[from] -= flow;
      }
  // Unknowns: d of the two charged states u. a[x][u] is the coefficient of d(u) in
  // (d(a) - d(b)) p(a) p(b); least squares by the 2 x 2 normal equations (a plain solve; Eigen
  // would do the same for two unknowns).
  int other[2], m = 0;
  for (int s = 0; s < 3; ++s)
    if (s != vacancy)
      other[m++] = s;
  double a[9][2];
  for (int x = 0; x < 9; ++x)
    for (int u = 0; u < 2; ++u)
      a[x][u] = ((x / 3 == other[u]) - (x % 3 == other[u])) * p[x / 3] * p[x % 3];
  double n00 = 0, n01 = 0, n11 = 0, b0 = 0, b1 = 0;
  for (int x = 0; x < 9; ++x) {
    n00 += a[x][0] * a[x][0];
    n01 += a[x][0] * a[x][1];
    n11 += a[x][1] * a[x][1];
    b0 += a[x][0] * g[x];
    b1 += a[x][1] * g[x];
  }
  double d0 = 0.0, d1 = 0.0;
  const double det = n00 * n11 - n01 * n01;
  if (std::abs(det) > 1e-300 && std::abs(det) > 1e-14 * n00 * n11) {
    d0 = (b0 * n11 - b1 * n01) / det;
    d1 = (b1 * n00 - b0 * n01) / det;
  } else if (n00 > 0.0) { // a charged state has zero probability: its d is free; take 0
    d0 = b0 / n00;
  } else if (n11 > 0.0) {
    d1 = b1 / n11;
  }
  BulkFit fit;
  fit.d[other[0]] = d0;
  fit.d[other[1]] = d1;
  for (int x = 0; x < 9; ++x)
    fit.residual = std::max(fit.residual, std::abs(a[x][0] * d0 + a[x][1] * d1 - g[x]));
  return fit;
}

double boundary_residual(const std::array<double, 9> &site, const std::array<double, 3> &p,
                         const std::array<double, 3> &d, bool left) {
  const auto g = site_generator(site, p);
  const double mean = d[0] * p[0] + d[1] * p[1] + d[2] * p[2];
  double res = 0.0;
  for (int n = 0; n < 3; ++n) {
    const double want = (left ? mean - d[n] : d[n] - mean) * p[n];
    res = std::max(res, std::abs(g[n] - want));
  }
  return res;
}

std::array<double, 9> boundary_rates_for(const std::array<double, 3> &p,
                                         const std::array<double, 3> &d, bool left,
                                         double coupling) {
  const double mean = d[0] * p[0] + d[1] * p[1] + d[2] * p[2];
  const int hub = static_cast<int>(std::max_element(p.begin(), p.end()) - p.begin());
  std::array<double, 9> w{};
  for (int m = 0; m < 3; ++m) {
    if (m == hub)
      continue;
    // Net flow hub -> m must equal the inflow m needs: w_hm p_hub - w_mh p_m = f.
    const double f = (left ? mean - d[m] : d[m] - mean) * p[m];
    double &hm = w[hub * 3 + m], &mh = w[m * 3 + hub];
    if (p[m] <= 0.0) { // never occupied: nothing may enter it
      hm = 0.0;
      mh = coupling;
    } else if (f >= 0.0) {
      mh = coupling;
      hm = (f + coupling * p[m]) / p[hub];
    } else {
      hm = coupling;
      mh = (coupling * p[hub] - f) / p[m];
    }
  }
  return w;
}

void apply_preset(Model &model, bool keep_charge, bool initial_given) {
  if (model.preset == Preset::none)
    return;
  if (!keep_charge)
    model.charge = preset_charge(model.preset);
  const double ratio = model.preset == Preset::family1 ? family1_ratio(model.rates) : model.c;
  const int vac = vacancy_state(model.preset);
  if (model.fugacity.empty())
    return;
  const auto p_left = preset_marginal(model.preset, ratio, model.fugacity.front());
  const auto p_right = preset_marginal(model.preset, ratio, model.fugacity.back());
  if (model.boundary_from_fugacity) {
    model.left = boundary_rates_for(p_left, bulk_fit(model.rates, p_left, vac).d, true,
                                    model.boundary_coupling);
    model.right = boundary_rates_for(p_right, bulk_fit(model.rates, p_right, vac).d, false,
                                     model.boundary_coupling);
  }
  if (!initial_given) {
    model.initial = p_left;
    model.initial_right = p_right;
  }
}

double family1_rho_star(double sigma, double r) {
  // (1 - 4r) rho^2 + 8 r rho - (sigma^2 + 4 r) = 0
  const double a = 1.0 - 4.0 * r, b = 8.0 * r, c = -(sigma * sigma + 4.0 * r);
  if (std::abs(a) < 1e-12)
    return -c / b;
  const double disc = std::sqrt(std::max(0.0, b * b - 4.0 * a * c));
  // the root in [|sigma|, 1], written without cancellation
  return b > 0.0 ? 2.0 * (-c) / (b + disc) : (-b + disc) / (2.0 * a);
}

double hydrodynamic_flux(const Model &m, double density) {
  const SeedRates w{m.rates};
  if (m.preset == Preset::family1) {
    const double sigma = density;
    const double rho = family1_rho_star(sigma, family1_ratio(m.rates));
    return 0.5 * (w(4, 2) - w(2, 4)) * (rho + sigma) * (1.0 - sigma) +
           0.5 * (w(8, 6) - w(6, 8)) * (rho - sigma) * (1.0 + sigma);
  }
  if (m.preset == Preset::family2) {
    const double c = m.c, rho = density;
    return (w(2, 4) - w(4, 2) + c * (w(3, 7) - w(7, 3)) + 2.0 * c * (w(2, 7) - w(4, 3))) /
           (1.0 + c) * rho * (1.0 - rho);
  }
  return 0.0;
}

PresetReport analyse(const Model &m) {
  PresetReport rep;
  rep.preset = m.preset;
  if (m.preset == Preset::none)
    return rep;
  const SeedRates w{m.rates};
  const double scale = rate_scale(m);
  const double tol = 1e-9 * scale;
  const auto check = [&](const std::string &what, double value) {
    rep.residuals.push_back({what, value});
    if (!(std::abs(value) <= tol))
      rep.warnings.push_back(what + " does not hold: residual " + fmt("%.6g", value));
  };
  const bool f1 = m.preset == Preset::family1;
  const int vac = vacancy_state(m.preset);

  if (f1) {
    rep.ratio = family1_ratio(m.rates);
    rep.f = w(2, 4) - w(4, 2);  // eq 2.33
    rep.fp = w(8, 6) - w(6, 8); // eq 2.34
    rep.lines.push_back("preset family 1 (eq 2.5; A = state 0, vacancy = 1, B = 2; charge "
                        "C = 1 - n): r = " +
                        fmt("%.6g", rep.ratio) + " (eq 2.35), F = " + fmt("%.6g", rep.f) +
                        ", F' = " + fmt("%.6g", rep.fp) + " (eq 2.33-2.34)");
    if (w(5, 3) + w(5, 7) <= 0.0)
      rep.warnings.push_back("family 1: w53 + w57 = 0, so r of eq 2.35 is undefined; r = 1 used");
    // eq 2.36, multiplied by (w35 + w75) so that it stays finite.
    const double lhs = w(2, 4) - w(4, 2) + w(6, 8) - w(8, 6) + w(7, 3) - w(3, 7);
    check("stationarity condition (eq 2.36, times w35 + w75)",
          lhs * (w(3, 5) + w(7, 5)) - (w(3, 5) * w(5, 7) - w(5, 3) * w(7, 5)));
  } else {
    const double c = m.c;
    rep.ratio = c;
    const double h1 = w(4, 2), h2 = w(7, 3), h3 = w(2, 4), h4 = w(8, 6), h5 = w(6, 8), h6 = w(3, 7);
    const double r1 = w(4, 7), r2 = w(4, 3), r3 = w(2, 3), r4 = w(2, 7), r5 = w(5, 8), r6 = w(5, 6),
                 r8 = w(8, 9), r9 = w(6, 9);
    rep.f = h3 - h1 + c * (r3 + r4 - r1 - r2); // E, eq 2.93
    rep.fp = h6 - h2 + r1 + r4 - r2 - r3;      // E'
    rep.lines.push_back("preset family 2 (eq 2.79, PT relations 2.86; vacancy = state 0, A = 1, "
                        "B = 2; current counts particles): c = " +
                        fmt("%.6g", c) + ", E = " + fmt("%.6g", rep.f) +
                        ", E' = " + fmt("%.6g", rep.fp) + " (eq 2.93)");
    check("stationarity condition (eq 2.94)", h6 - h2 + h1 - h3 + h4 - h5 + (1 + c) * (r1 - r3) +
                                                  (1 - c) * (r4 - r2) + c * (r8 - r9) + r6 - r5);
  }

  for (std::size_t i = 0; i < m.fugacity.size(); ++i) {
    Branch b;
    b.z = m.fugacity[i];
    b.p = preset_marginal(m.preset, rep.ratio, b.z);
    const double z = b.z;
    if (f1) {
      const double r = rep.ratio;
      b.nu = 1.0 + z + r * z * z;
      b.rho_a = b.p[0];
      b.rho_b = b.p[2];
      b.sigma = b.rho_a - b.rho_b; // eq 2.27
      b.rho = b.rho_a + b.rho_b;   // eq 2.28
      const double nu2 = b.nu * b.nu;
      b.current_247 = (w(4, 2) - w(2, 4)) * z / nu2 +
                      (2.0 * (w(7, 3) - w(3, 7)) + w(5, 3) - w(5, 7)) * r * z * z / nu2 +
                      (w(8, 6) - w(6, 8)) * r * z * z * z / nu2 + (w(7, 5) - w(3, 5)) * z * z / nu2;
      b.current = 0.5 * (w(4, 2) - w(2, 4)) * (b.rho + b.sigma) * (1.0 - b.sigma) +
                  0.5 * (w(8, 6) - w(6, 8)) * (b.rho - b.sigma) * (1.0 + b.sigma); // eq 2.48
    } else {
      const double c = rep.ratio;
      b.nu = 1.0 + z + c * z;
      b.rho_a = b.p[1];
      b.rho_b = b.p[2];
      b.rho = b.rho_a + b.rho_b; // eq 2.84
      const double pre =
          (w(2, 4) - w(4, 2) + c * (w(3, 7) - w(7, 3)) + 2.0 * c * (w(2, 7) - w(4, 3))) / (1.0 + c);
      b.current = pre * b.rho * (1.0 - b.rho); // eq 2.126
    }
    const std::string side = m.fugacity.size() == 1 ? "" : (i == 0 ? " (left)" : " (right)");
    std::string line = "fugacity z" + side + " = " + fmt("%.6g", z) +
                       ": nu = " + fmt("%.6g", b.nu) + ", rho_A = " + fmt("%.6g", b.rho_a) +
                       ", rho_B = " + fmt("%.6g", b.rho_b);
    if (f1)
      line += ", sigma = " + fmt("%.6g", b.sigma) + ", rho = " + fmt("%.6g", b.rho) +
              "; current j* = " + fmt("%.6g", b.current) + " (eq 2.48; eq 2.47 gives " +
              fmt("%.6g", b.current_247) + ")";
    else
      line += ", rho = " + fmt("%.6g", b.rho) + "; current j* = " + fmt("%.6g", b.current) +
              " (eq 2.126)";
    rep.lines.push_back(line);

    const BulkFit fit = bulk_fit(m.rates, b.p, vac);
    check("product measure of z" + side + " = " + fmt("%g", z) +
              " stationary in the bulk (eq 2.30/2.92, max remainder)",
          fit.residual);
    if (m.boundary == Boundary::open) {
      if (i == 0)
        check("left boundary rates fit z" + side + " (eq " + (f1 ? "2.38-2.39" : "2.95") + ")",
              boundary_residual(m.left, b.p, fit.d, true));
      if (i + 1 == m.fugacity.size())
        check("right boundary rates fit z" + side + " (eq " + (f1 ? "2.40-2.41" : "2.96") + ")",
              boundary_residual(m.right, b.p, fit.d, false));
    }
    rep.branches.push_back(b);
  }

  if (m.fugacity.size() == 2) {
    rep.shock = true;
    const Branch &b1 = rep.branches[0], &b2 = rep.branches[1];
    if (f1) {
      // The special case of eq 2.72-2.76: w24 = 0, w57 = w37 = 0, w86 = w68, z2 = 0.
      check("shock condition w24 = 0 (eq 2.72 case)", w(2, 4));
      check("shock condition w57 = 0 (eq 2.74)", w(5, 7));
      check("shock condition w37 = 0 (eq 2.74)", w(3, 7));
      check("shock condition w86 = w68 (eq 2.75)", w(8, 6) - w(6, 8));
      check("shock condition z_right = 0 (eq 2.72)", b2.z);
      rep.d1 = w(4, 2) / b1.nu; // eq 2.73
      rep.d2 = 0.0;
      rep.v_s = w(4, 2) * b1.rho_a; // eq 2.76
      rep.d_s = 0.5 * rep.v_s;
    } else {
      const double c = rep.ratio;
      const double p1 = w(2, 4) + c * w(2, 7), p2 = w(3, 7) + w(2, 7);
      const double q1 = w(4, 2) + c * w(4, 3), q2 = w(7, 3) + w(4, 3);
      check("shock manifold h3 + c r4 = h6 + r4 (eq 2.109)", p1 - p2);
      check("shock manifold h1 + c r2 = h2 + r2 (eq 2.110)", q1 - q2);
      check("shock manifold p/q = z2/z1 (eq 2.111, times q z1)", p1 * b1.z - q1 * b2.z);
      const double h4 = w(8, 6), h5 = w(6, 8), r1 = w(4, 7), r3 = w(2, 3), r5 = w(5, 8),
                   r6 = w(5, 6), r8 = w(8, 9), r9 = w(6, 9);
      check("stationarity on the shock manifold (eq 2.114)",
            h4 - h5 + (1 + c) * (r1 - r3) + c * (r8 - r9) + r6 - r5);
      rep.d1 = q1 * b2.nu / b1.nu;                                                 // eq 2.112
      rep.d2 = p1 * b1.nu / b2.nu;                                                 // eq 2.113
      rep.v_s = (q1 * b2.nu * b2.nu - p1 * b1.nu * b1.nu) / (b1.nu * b2.nu);       // eq 2.115
      rep.d_s = (p1 * b1.nu * b1.nu + q1 * b2.nu * b2.nu) / (2.0 * b1.nu * b2.nu); // eq 2.116
    }
    rep.lines.push_back("shock: hopping rates d1 = " + fmt("%.6g", rep.d1) +
                        " (left), d2 = " + fmt("%.6g", rep.d2) + " (right); v_s = " +
                        fmt2("%.6g (positive = to the left), D_s = %.6g", rep.v_s, rep.d_s) +
                        (f1 ? " (eq 2.73, 2.76)" : " (eq 2.112-2.116)"));
  }
  if (!rep.warnings.empty())
    rep.lines.push_back("the derived values above assume these conditions; " +
                        std::to_string(rep.warnings.size()) + " of them do not hold (warnings)");
  return rep;
}

} // namespace narrows::three_state
