// The implicit exchange's ghost response: the 2D and 3D closed forms against the general 3 x 3
// algebra.
#include "narrows/engines/mpcd/coupling/ghost_response.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace narrows::coupling;

namespace {

// A random group in the plane (dim 2) or in space: n ghosts at offsets r from the centre (their
// moments), the cell's rc and N; Q an SRD rotation's 1 - R by +-alpha (about z in the plane,
// about a random axis in space) or MPC-AT's identity; spin 1/I about z in the plane, the inverse
// of a random symmetric positive matrix in space, or 0.
GhostMoments random_group(std::mt19937_64 &gen, int rule, int dim) {
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  GhostMoments m;
  const int n = 1 + static_cast<int>(gen() % 20);
  for (int j = 0; j < n; ++j) {
    double r[3] = {0.0, 0.0, 0.0};
    for (int a = 0; a < dim; ++a)
      r[a] = u(gen);
    m.m0 += 1.0;
    for (int a = 0; a < dim; ++a) {
      m.m1[a] += r[a];
      for (int b = 0; b < dim; ++b)
        m.m2[a][b] += r[a] * r[b];
    }
  }
  for (int a = 0; a < dim; ++a)
    m.rc[a] = u(gen);
  m.N = m.m0 + static_cast<double>(gen() % 30);
  if (rule == 0) { // 1 - R(alpha) about the unit axis k (Rodrigues)
    double k[3] = {0.0, 0.0, 1.0};
    if (dim == 3) {
      for (double &x : k)
        x = u(gen);
      const double len = std::sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]);
      for (double &x : k)
        x /= len;
    }
    const double alpha = (gen() % 2 ? 1.0 : -1.0) * 130.0 * M_PI / 180.0;
    const double c = std::cos(alpha), s = std::sin(alpha);
    const double K[3][3] = {{0, -k[2], k[1]}, {k[2], 0, -k[0]}, {-k[1], k[0], 0}};
    for (int a = 0; a < dim; ++a)
      for (int b = 0; b < dim; ++b) {
        double KK = 0.0;
        for (int d = 0; d < 3; ++d)
          KK += K[a][d] * K[d][b];
        const double R = (a == b ? 1.0 : 0.0) + s * K[a][b] + (1.0 - c) * KK;
        m.Q[a][b] = (a == b ? 1.0 : 0.0) - R;
      }
  } else {
    for (int a = 0; a < 3; ++a)
      m.Q[a][a] = 1.0;
  }
  if (rule == 2 && dim == 2)
    m.spin[2][2] = 1.0 / (1.0 + std::abs(u(gen)) * 10.0);
  if (rule == 2 && dim == 3) { // B B^T / 10 + 0.1
    double B[3][3];
    for (auto &row : B)
      for (double &x : row)
        x = u(gen);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        double t = a == b ? 0.1 : 0.0;
        for (int d = 0; d < 3; ++d)
          t += B[a][d] * B[b][d] / 10.0;
        m.spin[a][b] = t;
      }
  }
  return m;
}

} // namespace

TEST(GhostResponse, ClosedForm2dIsTheGeneralAlgebra) {
  std::mt19937_64 gen(7);
  for (int rule = 0; rule < 3; ++rule)
    for (int trial = 0; trial < 2000; ++trial) {
      const GhostMoments m = random_group(gen, rule, 2);
      GhostResponse a{}, b{};
      ghost_response_general(m, 2, a);
      ghost_response_2d(m, b);
      double scale = 1.0; // the size of the terms: n |r|^2 with |r| up to ~4
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k)
          scale = std::max(scale, std::abs(a.G[k][i]));
      for (int i = 0; i < 3; ++i) {
        for (int k = 0; k < 3; ++k)
          ASSERT_NEAR(b.G[k][i], a.G[k][i], 1e-12 * scale)
              << "rule " << rule << " trial " << trial << " G[" << k << "][" << i << "]";
        for (int k = 0; k < 3; ++k) {
          ASSERT_NEAR(b.du[i][k], a.du[i][k], 1e-13) << "rule " << rule << " du " << i << k;
          ASSERT_NEAR(b.dw[i][k], a.dw[i][k], 1e-13) << "rule " << rule << " dw " << i << k;
        }
      }
    }
}

TEST(GhostResponse, ClosedForm3dIsTheGeneralAlgebra) {
  std::mt19937_64 gen(11);
  for (int rule = 0; rule < 3; ++rule)
    for (int trial = 0; trial < 2000; ++trial) {
      const GhostMoments m = random_group(gen, rule, 3);
      GhostResponse a{}, b{};
      ghost_response_general(m, 3, a);
      ghost_response_3d(m, b);
      double scale = 1.0, motion = 1.0; // the sizes of G's terms and of du, dw
      for (int i = 0; i < 6; ++i)
        for (int k = 0; k < 6; ++k)
          scale = std::max(scale, std::abs(a.G[k][i]));
      for (int i = 0; i < 6; ++i)
        for (int k = 0; k < 3; ++k)
          motion = std::max({motion, std::abs(a.du[i][k]), std::abs(a.dw[i][k])});
      for (int i = 0; i < 6; ++i) {
        for (int k = 0; k < 6; ++k)
          ASSERT_NEAR(b.G[k][i], a.G[k][i], 1e-12 * scale)
              << "rule " << rule << " trial " << trial << " G[" << k << "][" << i << "]";
        for (int k = 0; k < 3; ++k) {
          ASSERT_NEAR(b.du[i][k], a.du[i][k], 1e-13 * motion)
              << "rule " << rule << " du " << i << k;
          ASSERT_NEAR(b.dw[i][k], a.dw[i][k], 1e-13 * motion)
              << "rule " << rule << " dw " << i << k;
        }
      }
    }
}
