// The implicit exchange's response of a colloid to its ghosts in a cut cell (ghost_response.hpp).
#include "narrows/engines/mpcd/coupling/ghost_response.hpp"

namespace narrows::coupling {

namespace {

// sum_j r_j x (M r_j) from the second moment m2 = sum_j r_j r_j^T.
void cross_moment(const double (&M)[3][3], const double (&m2)[3][3], double *out) {
  double T[3][3] = {}; // T[c][b] = sum_j (M r_j)_c r_jb = (M m2)_cb
  for (int c = 0; c < 3; ++c)
    for (int b = 0; b < 3; ++b)
      for (int d = 0; d < 3; ++d)
        T[c][b] += M[c][d] * m2[d][b];
  out[0] = T[2][1] - T[1][2];
  out[1] = T[0][2] - T[2][0];
  out[2] = T[1][0] - T[0][1];
}

// [w]x: the matrix of w x r.
void cross_matrix(const double *w, double (&M)[3][3]) {
  M[0][0] = M[1][1] = M[2][2] = 0.0;
  M[0][1] = -w[2];
  M[0][2] = w[1];
  M[1][0] = w[2];
  M[1][2] = -w[0];
  M[2][0] = -w[1];
  M[2][1] = w[0];
}

} // namespace

// Ghost j at r_j from the centre moves with dU + dW x r_j more when the colloid changes by
// dX = (dU, dW): the cell's mean velocity by du = (n dU + dW x m1) / N, its angular momentum
// about rc (AT+a) by dL = sum_j (r_j - rc) x (dU + dW x r_j), so its rigid rotation by
// dw = spin dL; each ghost's new velocity by Q (du - dU - dW x r_j) + dw x (r_j - rc). Summed over
// the ghosts, the colloid's impulse and angular impulse change by -G dX; the fluid of the cell
// gets Q du + dw x (r - rc) each. Computed for each unit dX.
void ghost_response_general(const GhostMoments &g, int dim, GhostResponse &out) {
  const int dof = dim == 2 ? 3 : 6;
  const double m0 = g.m0, N = g.N;
  const double *m1 = g.m1, *rc = g.rc;
  const auto &m2 = g.m2;
  const auto &Q = g.Q;
  for (int i = 0; i < dof; ++i) {
    double dU[3] = {0.0, 0.0, 0.0}, dW[3] = {0.0, 0.0, 0.0};
    if (i < dim)
      dU[i] = 1.0;
    else
      dW[dim == 2 ? 2 : i - 3] = 1.0;
    double S[3], du[3], Qdu[3], QdU[3], t[3];
    cross(dW, m1, t);
    for (int a = 0; a < 3; ++a) {
      S[a] = m0 * dU[a] + t[a];
      du[a] = N > 0.0 ? S[a] / N : 0.0;
    }
    for (int a = 0; a < 3; ++a) {
      Qdu[a] = Q[a][0] * du[0] + Q[a][1] * du[1] + Q[a][2] * du[2];
      QdU[a] = Q[a][0] * dU[0] + Q[a][1] * dU[1] + Q[a][2] * dU[2];
    }
    // dL = (m1 - n rc) x dU + sum r x (dW x r) - rc x (dW x m1).
    double W[3][3], dL[3], u1[3], u2[3], u3[3], off[3];
    cross_matrix(dW, W);
    for (int a = 0; a < 3; ++a)
      off[a] = m1[a] - m0 * rc[a];
    cross(off, dU, u1);
    cross_moment(W, m2, u2);
    cross(rc, t, u3);
    double dw[3];
    for (int a = 0; a < 3; ++a)
      dL[a] = u1[a] + u2[a] - u3[a];
    for (int a = 0; a < 3; ++a)
      dw[a] = g.spin[a][0] * dL[0] + g.spin[a][1] * dL[1] + g.spin[a][2] * dL[2];
    // The colloid's change: P = Q (n du - S) + dw x (m1 - n rc);
    // L = m1 x Q du - m1 x Q dU - sum r x Q (dW x r) + sum r x (dw x r) - m1 x (dw x rc).
    double P[3], L[3], a1[3], a2[3], a3[3], a4[3], a5[3], QW[3][3], Dw[3][3], wr[3];
    cross(dw, off, a1);
    for (int a = 0; a < 3; ++a)
      P[a] = Qdu[a] * m0 - (Q[a][0] * S[0] + Q[a][1] * S[1] + Q[a][2] * S[2]) + a1[a];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        QW[a][b] = Q[a][0] * W[0][b] + Q[a][1] * W[1][b] + Q[a][2] * W[2][b];
    cross_matrix(dw, Dw);
    cross(m1, Qdu, a2);
    cross(m1, QdU, a3);
    cross_moment(QW, m2, a4);
    cross_moment(Dw, m2, a5);
    cross(dw, rc, wr);
    double a6[3];
    cross(m1, wr, a6);
    for (int a = 0; a < 3; ++a)
      L[a] = a2[a] - a3[a] - a4[a] + a5[a] - a6[a];
    for (int k = 0; k < dim; ++k)
      out.G[k][i] = -P[k];
    if (dim == 2)
      out.G[2][i] = -L[2];
    else
      for (int k = 0; k < 3; ++k)
        out.G[3 + k][i] = -L[k];
    for (int a = 0; a < 3; ++a) {
      out.du[i][a] = Qdu[a];
      out.dw[i][a] = dw[a];
    }
  }
}

// The same in space with the unit dX's zeros left out (the general algebra multiplies them
// through: ~300 operations a dof). With off = m1 - n rc and tr = tr m2, and
// sum r x (w x r) = tr w - m2 w for any w:
//   translation e_i: S = n e_i, QdU = Q e_i, dL = off x e_i;
//     P = Q du n - n Q e_i + dw x off; L = m1 x Q du - m1 x Q e_i + (tr dw - m2 dw) - m1 x (dw x
//     rc);
//   rotation e_j: S = e_j x m1, dL = tr e_j - m2 e_j - rc x S;
//     P = Q du n - Q S + dw x off; L = m1 x Q du - sum r x Q (e_j x r) + (tr dw - m2 dw)
//     - m1 x (dw x rc), where sum r x Q (e_j x r) is the cross moment of Q [e_j]x.
void ghost_response_3d(const GhostMoments &g, GhostResponse &out) {
  const double m0 = g.m0, N = g.N;
  const double *m1 = g.m1, *rc = g.rc;
  const auto &m2 = g.m2;
  const auto &Q = g.Q;
  const double tr = m2[0][0] + m2[1][1] + m2[2][2];
  double off[3];
  for (int a = 0; a < 3; ++a)
    off[a] = m1[a] - m0 * rc[a];
  for (int i = 0; i < 6; ++i) {
    const int e = i % 3;
    double S[3] = {0.0, 0.0, 0.0}, dL[3], QS[3];
    if (i < 3) {
      S[e] = m0;
      double unit[3] = {0.0, 0.0, 0.0};
      unit[e] = 1.0;
      cross(off, unit, dL);
      for (int a = 0; a < 3; ++a)
        QS[a] = Q[a][e] * m0;
    } else {
      double unit[3] = {0.0, 0.0, 0.0}, t[3];
      unit[e] = 1.0;
      cross(unit, m1, S);
      cross(rc, S, t);
      for (int a = 0; a < 3; ++a) {
        dL[a] = (a == e ? tr : 0.0) - m2[a][e] - t[a];
        QS[a] = Q[a][0] * S[0] + Q[a][1] * S[1] + Q[a][2] * S[2];
      }
    }
    double du[3], Qdu[3], dw[3];
    for (int a = 0; a < 3; ++a)
      du[a] = N > 0.0 ? S[a] / N : 0.0;
    for (int a = 0; a < 3; ++a) {
      Qdu[a] = Q[a][0] * du[0] + Q[a][1] * du[1] + Q[a][2] * du[2];
      dw[a] = g.spin[a][0] * dL[0] + g.spin[a][1] * dL[1] + g.spin[a][2] * dL[2];
    }
    double a1[3], a2[3], wr[3], a6[3];
    cross(dw, off, a1);
    cross(m1, Qdu, a2);
    cross(dw, rc, wr);
    cross(m1, wr, a6);
    double L[3];
    for (int a = 0; a < 3; ++a) {
      const double m2dw = m2[a][0] * dw[0] + m2[a][1] * dw[1] + m2[a][2] * dw[2];
      L[a] = a2[a] + (tr * dw[a] - m2dw) - a6[a];
      out.G[a][i] = -(Qdu[a] * m0 - QS[a] + a1[a]);
    }
    if (i < 3) { // - m1 x Q e_i
      const double Qe[3] = {Q[0][e], Q[1][e], Q[2][e]};
      double a3[3];
      cross(m1, Qe, a3);
      for (int a = 0; a < 3; ++a)
        L[a] -= a3[a];
    } else { // - sum r x Q (e_j x r): T = Q [e_j]x m2, ([e_j]x m2) row c = (e_j x column of m2)
      double X[3][3];
      for (int b = 0; b < 3; ++b) {
        const double col[3] = {m2[0][b], m2[1][b], m2[2][b]};
        double unit[3] = {0.0, 0.0, 0.0}, ex[3];
        unit[e] = 1.0;
        cross(unit, col, ex);
        for (int c = 0; c < 3; ++c)
          X[c][b] = ex[c];
      }
      double T[3][3];
      for (int c = 0; c < 3; ++c)
        for (int b = 0; b < 3; ++b)
          T[c][b] = Q[c][0] * X[0][b] + Q[c][1] * X[1][b] + Q[c][2] * X[2][b];
      L[0] -= T[2][1] - T[1][2];
      L[1] -= T[0][2] - T[2][0];
      L[2] -= T[1][0] - T[0][1];
    }
    for (int k = 0; k < 3; ++k) {
      out.G[3 + k][i] = -L[k];
      out.du[i][k] = Qdu[k];
      out.dw[i][k] = dw[k];
    }
  }
}

// The same in the plane. With e the unit dX: S = n e (translation) or z x m1 (rotation);
// du = S / N; dL_z = (m1 - n rc) x e or tr m2 - rc . m1; dw = spin_zz dL_z;
// P = (n / N - 1) Q S + dw z x (m1 - n rc);
// L_z = m1 x Q du - m1 x Q e (translation) - [z . sum r x Q (z x r)] (rotation)
//       + dw (tr m2 - m1 . rc),
// where z . sum r x Q (z x r) = Q_yy m2_xx - (Q_xy + Q_yx) m2_xy + Q_xx m2_yy.
void ghost_response_2d(const GhostMoments &g, GhostResponse &out) {
  const PlanarMoments m{g.m0,       g.N,        g.spin[2][2], g.m1[0],  g.m1[1],
                        g.m2[0][0], g.m2[0][1], g.m2[1][1],   g.rc[0],  g.rc[1],
                        g.Q[0][0],  g.Q[0][1],  g.Q[1][0],    g.Q[1][1]};
  PlanarResponse r;
  planar_response(m, r);
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k)
      out.G[k][i] = r.G[k][i];
    out.du[i][0] = r.du[i][0];
    out.du[i][1] = r.du[i][1];
    out.du[i][2] = 0.0;
    out.dw[i][0] = out.dw[i][1] = 0.0;
    out.dw[i][2] = r.dw[i];
  }
}

} // namespace narrows::coupling
