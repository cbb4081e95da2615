// The interaction potentials of Tabatabaei (2008) §3.3-3.4, as inline kernels for the force loops.
//
// Pair potentials phi(r) = 4 eps [(sigma/r)^(2n) - (sigma/r)^n + 1/4] for r < r_cut = 2^(1/n)
// sigma (the repulsive, shifted Lennard-Jones form): n = 6 colloid-fluid (eq 3.42, sigma_cf =
// r_a, the colloid's radius), n = 24 colloid-colloid (eq 3.43, sigma_cc = r_a + r_b; Tabatabaei's
// 2 r_c for equal radii).
//
// Wall (eq 3.35-3.37): a Lennard-Jones 12-6 line density q/sigma integrated along the wall,
//   U(h) = (3 pi eps q / 2) [ (21/32)(sigma/h)^11 - (sigma/h)^5 ] ,  h = distance to the wall,
// using int dx/(x^2+b^2)^3 = 3 pi/(8 b^5) and int dx/(x^2+b^2)^6 = 63 pi/(256 b^11). Its
// minimum solves (21/32) 11 (sigma/h)^11 = 5 (sigma/h)^5, i.e. (h/sigma)^6 = 231/160 = 1.44375:
//   h_cut = 1.44375^(1/6) sigma = 1.063119 sigma  (Tabatabaei's "(1.444375 sigma)^(1/6)" is
//   garbled: the constant is 231/160 and sigma stands outside the root),
// where U(h_cut) = -(3 pi eps q / 2)(6/11)(160/231)^(5/6). Truncated at h_cut and shifted by
// that value, U and the force F = -dU/dh = (15 pi eps q / 2)[(231/160)(sigma/h)^11 -
// (sigma/h)^5]/h (eq 3.37) both vanish at the cut-off, so the potential is continuous with a
// continuous force. The dissertation is 2D (a wall is a line of LJ centres); in a 3D slit the same
// profile is used as a smooth repulsive wall (the plane-integrated 9-3 form is not implemented).
#pragma once

#include <cmath>

namespace narrows::colloids {

struct PairTerm {
  double energy;   // phi(r)
  double f_over_r; // -phi'(r) / r: the force on the first particle is f_over_r * (x1 - x2)
};

// Cut-off of the (2n, n) repulsive potential: 2^(1/n) sigma.
inline double repulsive_cutoff(int n, double sigma) { return std::pow(2.0, 1.0 / n) * sigma; }

// The (2n, n) repulsive potential at squared distance r2 < cutoff^2 (the caller checks).
template <int N> inline PairTerm repulsive_pair(double r2, double sigma2, double eps) {
  static_assert(N == 6 || N == 24, "the potentials of Tabatabaei (2008) use n = 6 and n = 24");
  const double s2 = sigma2 / r2;
  double sn = s2 * s2 * s2; // (sigma/r)^6
  if constexpr (N == 24) {
    sn *= sn;
    sn *= sn;
  }
  const double s2n = sn * sn;
  return {4.0 * eps * (s2n - sn + 0.25), 4.0 * eps * N * (2.0 * s2n - sn) / r2};
}

inline constexpr double wall_min_ratio6 = 231.0 / 160.0; // (h_cut/sigma)^6

// Distance from the wall at which the integrated wall potential is cut (its minimum).
inline double wall_cutoff(double sigma) { return std::pow(wall_min_ratio6, 1.0 / 6.0) * sigma; }

struct WallTerm {
  double energy; // U(h), shifted to zero at the cut-off
  double force;  // -dU/dh: along the wall normal, into the channel
};

// The truncated wall potential at distance 0 < h < wall_cutoff(sigma) (the caller checks).
inline WallTerm wall_term(double h, double sigma, double eps, double q) {
  const double pi = 3.14159265358979323846;
  const double s = sigma / h;
  const double s5 = s * s * s * s * s, s11 = s5 * s5 * s;
  const double shift = (6.0 / 11.0) * std::pow(1.0 / wall_min_ratio6, 5.0 / 6.0);
  return {1.5 * pi * eps * q * ((21.0 / 32.0) * s11 - s5 + shift),
          7.5 * pi * eps * q * (wall_min_ratio6 * s11 - s5) / h};
}

} // namespace narrows::colloids
