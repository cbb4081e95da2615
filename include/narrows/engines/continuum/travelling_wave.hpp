// Travelling waves phi(z), v(z), z = x - c t, of the jamming model (Kanehl (thesis) §6.3.3-6.3.4):
// with the co-moving flux q = (v - c) phi - D phi' constant (eq 6.12), the PDE becomes the ODEs
//   D phi' = (v - c) phi - q,     v' = (sigma - xi(phi) v) / (v - c)        (eq 6.13-6.14)
// (sigma = D = 1 in the thesis). Fixed points lie where q = phi0 (v_ss(phi0) - c) (eq 6.18); their
// type comes from the eigenvalues of the Jacobian (eq 6.19-6.20, solved by Eigen). A limit cycle
// of the ODEs is a periodic pulse train of the PDE moving at c.
#pragma once

#include "narrows/engines/continuum/jamming_model.hpp"

#include <Eigen/Dense>

#include <array>
#include <complex>
#include <vector>

namespace narrows::continuum {

enum class FixedPointType { saddle, node_sink, node_source, focus_sink, focus_source, centre };
const char *to_string(FixedPointType t);

struct FixedPoint {
  double phi = 0.0, v = 0.0;                    // v = v_ss(phi)
  std::array<std::complex<double>, 2> lambda{}; // eigenvalues of the Jacobian (eq 6.20)
  FixedPointType type = FixedPointType::saddle;
};

// (phi', v') of eq 6.13-6.14.
std::array<double, 2> wave_rhs(const JammingModel &m, double c, double q, double phi, double v);
// The Jacobian at a fixed point (phi0, v_ss(phi0)) (eq 6.19 with sigma and D).
Eigen::Matrix2d wave_jacobian(const JammingModel &m, double c, double phi0);
// Eigenvalues and type of the fixed point at phi0 (on the nullcline v = v_ss).
FixedPoint classify(const JammingModel &m, double c, double phi0);
// Every fixed point with phi in (lo, hi): roots of phi (v_ss(phi) - c) = q, by a scan of
// `samples` intervals and bisection, in increasing phi.
std::vector<FixedPoint> fixed_points(const JammingModel &m, double c, double q, double lo = 1e-3,
                                     double hi = 0.999, int samples = 20000);
// The wave speed c at which the fixed point phi0 has a Hopf bifurcation (eq 6.21: the trace
// (v0 - c)/D - xi0/(v0 - c) vanishes, c = v0 - sqrt(D xi0)); `valid` tells whether the
// eigenvalues are then imaginary (determinant > 0).
double hopf_speed(const JammingModel &m, double phi0, bool *valid = nullptr);

struct LimitCycle {
  bool found = false;
  double period = 0.0;   // in z
  double phi_mean = 0.0; // mean of phi over one period in z
  double phi_min = 0.0, phi_max = 0.0;
  bool attracting_forward = false; // attracts trajectories for increasing z
  std::vector<double> z, phi, v;   // one period, from a crossing of the section
};

// The limit cycle around the fixed point `centre` (a focus or node): trajectories start next to
// it and are integrated (RK4, step dz) forward in z if it repels, backward if it attracts, until
// the returns to the section phi = centre.phi converge (|dv| < tol) or the trajectory leaves
// (0, 1) (no cycle).
LimitCycle limit_cycle(const JammingModel &m, double c, double q, const FixedPoint &centre,
                       double dz = 2e-3, double tol = 1e-9, int max_turns = 4000);
// The same from any start (phi, v), integrating forward or backward in z, with the section
// phi = section (e.g. a point of a pulse train measured in a PDE run: the cycle it lies on).
LimitCycle limit_cycle_from(const JammingModel &m, double c, double q, double phi_start,
                            double v_start, double section, bool forward, double dz = 2e-3,
                            double tol = 1e-9, int max_turns = 4000);

} // namespace narrows::continuum
