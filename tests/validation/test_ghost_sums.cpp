// The no-slip colloids' ghost particles enter the collision as sums per (colloid, cut cell)
// pair (colloids/ghost_particles.cpp): given the ghosts' positions r (N of them, moment matrix
// M = sum (1, r)(1, r)^T), each velocity component b of (sum v, sum r v^T) must be Gaussian with
// mean that of the rigid-body motion, sum (U + Omega x r'), and covariance kT M, and so must the
// MPC-AT draws (sum xi, sum r xi^T), with mean zero; the components, and eta and xi, independent.
// That is what drawing one Gaussian per ghost would give. Measured over the groups of a moving,
// spinning colloid in many steps (new positions each step), 2D and 3D, at kT = 1.3:
//   - the quadratic form y^T M^+ y / kT of each component (M^+ the pseudo-inverse: M is
//     singular for one ghost, or ghosts on a line) sums to chi^2 with sum rank(M) degrees of
//     freedom: within 5 standard deviations (sqrt(2 dof));
//   - every entry of sum y y^T against kT sum M, and the cross terms (x with y, eta with xi)
//     against 0, within 5 standard errors (the variance of a product of two of the Gaussians:
//     M_ii M_jj + M_ij^2, in units of kT^2).
// A mean off by the rigid-body part, a factor missing in the Cholesky factor, or shared normals
// between eta and xi fail these. ~0.5 s.
#include "narrows/engines/mpcd/coupling/no_slip.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"
#include "narrows/parallel/slabs.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace narrows;

namespace {

void check_ghost_sums(int dim) {
  const int L = dim == 2 ? 16 : 10;
  const mpcd::Box box = mpcd::make_periodic_box(dim, {L, L, dim == 3 ? L : 1});
  const double kT = 1.3;
  coupling::NoSlipParams params;
  params.kT = kT;
  params.density = dim == 2 ? 10.5 : 6.0; // a fractional density: the extra try too
  params.seed = 77;
  const parallel::Slabs slabs(MPI_COMM_SELF, L);
  coupling::NoSlipCoupling coupling(params, box, slabs);
  colloids::Colloids c;
  c.dim = dim;
  c.resize(1);
  c.radius[0] = dim == 2 ? 3.3 : 2.6;
  c.id[0] = 5;
  const double U[3] = {0.3, -0.2, dim == 3 ? 0.1 : 0.0};
  const double W[3] = {dim == 3 ? 0.15 : 0.0, dim == 3 ? -0.1 : 0.0, 0.25};
  for (int k = 0; k < dim; ++k) {
    c.x[k][0] = 0.5 * L + 0.37 * (k + 1);
    c.v[k][0] = U[k];
  }
  for (int k = 0; k < 3; ++k)
    c.omega[k][0] = W[k];
  Eigen::Matrix3d K; // Omega x y = K y
  K << 0, -W[2], W[1], W[2], 0, -W[0], -W[1], W[0], 0;

  const int m = dim + 1;
  double chi2 = 0.0, dof = 0.0;
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(m, m), E = S, V = S; // sum y y^T, kT sum M, var
  double cross_b = 0.0, cross_b_var = 0.0, cross_eta_xi = 0.0, cross_eta_xi_var = 0.0;
  std::size_t groups = 0;
  mpcd::CellGrid grid(box);
  for (std::uint64_t step = 0; step < (dim == 2 ? 2000u : 600u); ++step) {
    grid.set_shift(mpcd::grid_shift(params.seed, step, dim));
    for (auto &s : grid.sums)
      s = mpcd::CellSums{};
    coupling.add_ghost_particles(grid, c, step);
    for (const mpcd::ParticleGroup &g : grid.groups) {
      ++groups;
      // The cell's corner from the centre (the colloid lies far from the periodic edges).
      const std::size_t cell = g.cell;
      const int ix = static_cast<int>(cell % L), iy = static_cast<int>((cell / L) % L),
                iz = static_cast<int>(cell / (static_cast<std::size_t>(L) * L));
      const int idx[3] = {ix, iy, iz};
      Eigen::Vector3d corner = Eigen::Vector3d::Zero(), r = corner;
      Eigen::Matrix3d rr = Eigen::Matrix3d::Zero();
      for (int k = 0; k < dim; ++k) {
        corner[k] = idx[k] + grid.shift[k] - c.x[k][0];
        r[k] = g.r[k];
        for (int j = 0; j < dim; ++j)
          rr(k, j) = g.rr[3 * k + j];
      }
      Eigen::MatrixXd M(m, m);
      M(0, 0) = g.n;
      for (int k = 0; k < dim; ++k) {
        M(0, 1 + k) = M(1 + k, 0) = r[k];
        for (int j = 0; j < dim; ++j)
          M(1 + k, 1 + j) = rr(k, j);
      }
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(M);
      const Eigen::VectorXd lam = eig.eigenvalues();
      Eigen::VectorXd inv(m);
      int rank = 0;
      for (int k = 0; k < m; ++k) {
        const bool kept = lam[k] > 1e-9 * lam.maxCoeff();
        inv[k] = kept ? 1.0 / lam[k] : 0.0;
        rank += kept;
      }
      const Eigen::MatrixXd Mplus =
          eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
      // Means: sum v = N U + Omega x (N c + sum r); sum r_a v_b = r_a (U + Omega x c)_b +
      // (K rr^T)_ba.
      const Eigen::Vector3d Uv(U[0], U[1], U[2]);
      const Eigen::Vector3d mean_v = g.n * Uv + K * (g.n * corner + r);
      const Eigen::Vector3d at_corner = Uv + K * corner;
      const Eigen::Matrix3d mean_rv = r * at_corner.transpose() + rr * K.transpose();
      std::vector<Eigen::VectorXd> eta(dim, Eigen::VectorXd(m)), xi(dim, Eigen::VectorXd(m));
      for (int b = 0; b < dim; ++b) {
        eta[b][0] = g.v[b] - mean_v[b];
        xi[b][0] = g.xi[b];
        for (int a = 0; a < dim; ++a) {
          eta[b][1 + a] = g.rv[3 * a + b] - mean_rv(a, b);
          xi[b][1 + a] = g.rxi[3 * a + b];
        }
        for (const auto *y : {&eta[b], &xi[b]}) {
          chi2 += y->dot(Mplus * *y) / kT;
          dof += rank;
          S += *y * y->transpose();
          E += kT * M;
          for (int i = 0; i < m; ++i)
            for (int j = 0; j < m; ++j)
              V(i, j) += kT * kT * (M(i, i) * M(j, j) + M(i, j) * M(i, j));
        }
        cross_eta_xi += eta[b][0] * xi[b][0];
        cross_eta_xi_var += kT * kT * g.n * g.n;
      }
      cross_b += eta[0][0] * eta[1][0];
      cross_b_var += kT * kT * g.n * g.n;
    }
  }
  std::printf("%dD: %zu groups; chi^2 %.0f on %.0f degrees of freedom (%.2f sd)\n", dim, groups,
              chi2, dof, (chi2 - dof) / std::sqrt(2.0 * dof));
  EXPECT_GT(groups, 5000u);
  EXPECT_LT(std::abs(chi2 - dof), 5.0 * std::sqrt(2.0 * dof));
  for (int i = 0; i < m; ++i)
    for (int j = i; j < m; ++j) {
      const double z = (S(i, j) - E(i, j)) / std::sqrt(V(i, j));
      std::printf("  sum y_%d y_%d / (kT sum M_%d%d) = %.4f (%.2f se)\n", i, j, i, j,
                  S(i, j) / E(i, j), z);
      EXPECT_LT(std::abs(z), 5.0);
    }
  const double zb = cross_b / std::sqrt(cross_b_var),
               zx = cross_eta_xi / std::sqrt(cross_eta_xi_var);
  std::printf("  cross terms: x with y %.2f se, eta with xi %.2f se\n", zb, zx);
  EXPECT_LT(std::abs(zb), 5.0);
  EXPECT_LT(std::abs(zx), 5.0);
}

} // namespace

TEST(GhostSums, AreGaussianWithTheMomentsOfTheirPositions2D) { check_ghost_sums(2); }
TEST(GhostSums, AreGaussianWithTheMomentsOfTheirPositions3D) { check_ghost_sums(3); }
