// The implicit exchange's response of a no-slip colloid to its ghost particles in one cut cell
// (coupling/no_slip.hpp): how the ghosts' momentum and angular momentum change, and how the
// cell's fluid moves, per unit change dX = (dU, dOmega) of the colloid.
#pragma once

namespace narrows::coupling {

// One group of ghosts (one colloid in one cut cell), about the colloid's centre: count m0,
// first and second moments m1 = sum r, m2 = sum r r^T; the cell's centre rc and its particle
// count N (fluid, ghosts and virtual particles); the collision rule's response Q (SRD: 1 - R;
// MPC-AT: 1) and, for MPC-AT+a, the cell's inverse moment of inertia `spin` (2D: only [2][2]).
struct GhostMoments {
  double m0 = 0.0;
  double m1[3] = {0.0, 0.0, 0.0};
  double m2[3][3] = {};
  double rc[3] = {0.0, 0.0, 0.0};
  double N = 0.0;
  double Q[3][3] = {};
  double spin[3][3] = {};
};

// Per degree of freedom i of dX (2D: Ux, Uy, Omega_z; 3D: U, Omega): column i of G (the
// colloid's impulse and angular impulse change by -G dX), and the cell's mean velocity change
// times Q (du) and rigid rotation (dw) that the fluid of the cell gets.
struct GhostResponse {
  double G[6][6];
  double du[6][3], dw[6][3];
};

// out = a x b (3 components).
inline void cross(const double *a, const double *b, double *out) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

// Any dimension (dim 2 or 3): each unit dX through the whole of the rule (3 x 3 algebra).
void ghost_response_general(const GhostMoments &g, int dim, GhostResponse &out);
// 2D in closed form (every vector in the plane, every rotation about z): the same response,
// to round-off, at a tenth of the cost.
void ghost_response_2d(const GhostMoments &g, GhostResponse &out);

} // namespace narrows::coupling
