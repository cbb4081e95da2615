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
// 3D with the unit dX's zeros left out: the same response, to round-off, at a fraction of the
// cost.
void ghost_response_3d(const GhostMoments &g, GhostResponse &out);

// The planar case's inputs and outputs alone (what ghost_response_2d reads of GhostMoments and
// writes of GhostResponse; the rest is zero in the plane), for the per-group loop of 2D runs.
struct PlanarMoments {
  double m0, N, spin;      // count, the cell's count, spin[2][2]
  double m1x, m1y;         // first moment about the centre
  double m2xx, m2xy, m2yy; // second moment
  double rcx, rcy;         // the cell's centre
  double Qxx, Qxy, Qyx, Qyy;
};
struct PlanarResponse {
  double G[3][3];  // rows Px, Py, L_z; column i: dof Ux, Uy, Omega_z
  double du[3][2]; // per dof, Q du in the plane
  double dw[3];    // per dof, the rotation about z
};

// ghost_response_2d's closed form (its comment), inline: the same operations, the same bits.
inline void planar_response(const PlanarMoments &g, PlanarResponse &out) {
  const double m0 = g.m0, N = g.N, s = g.spin;
  const double m1x = g.m1x, m1y = g.m1y, rcx = g.rcx, rcy = g.rcy;
  const double Qxx = g.Qxx, Qxy = g.Qxy, Qyx = g.Qyx, Qyy = g.Qyy;
  const double offx = m1x - m0 * rcx, offy = m1y - m0 * rcy;
  const double trace = g.m2xx + g.m2yy, m1rc = m1x * rcx + m1y * rcy;
  const double spun = Qyy * g.m2xx - (Qxy + Qyx) * g.m2xy + Qxx * g.m2yy;
  for (int i = 0; i < 3; ++i) {
    double Sx, Sy, dL;
    if (i < 2) {
      Sx = i == 0 ? m0 : 0.0;
      Sy = i == 1 ? m0 : 0.0;
      dL = i == 0 ? -offy : offx;
    } else {
      Sx = -m1y;
      Sy = m1x;
      dL = trace - m1rc;
    }
    const double dux = N > 0.0 ? Sx / N : 0.0, duy = N > 0.0 ? Sy / N : 0.0;
    const double Qdux = Qxx * dux + Qxy * duy, Qduy = Qyx * dux + Qyy * duy;
    const double QSx = Qxx * Sx + Qxy * Sy, QSy = Qyx * Sx + Qyy * Sy;
    const double dw = s * dL;
    const double Px = m0 * Qdux - QSx - dw * offy, Py = m0 * Qduy - QSy + dw * offx;
    double L = m1x * Qduy - m1y * Qdux + dw * (trace - m1rc);
    if (i < 2) // - m1 x Q e
      L -= i == 0 ? m1x * Qyx - m1y * Qxx : m1x * Qyy - m1y * Qxy;
    else
      L -= spun;
    out.G[0][i] = -Px;
    out.G[1][i] = -Py;
    out.G[2][i] = -L;
    out.du[i][0] = Qdux;
    out.du[i][1] = Qduy;
    out.dw[i] = dw;
  }
}

} // namespace narrows::coupling
