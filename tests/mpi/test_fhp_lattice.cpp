// The FHP lattice on one rank (each rank of the MPI test runs it on MPI_COMM_SELF): the two
// kernels agree bit for bit, propagation follows the neighbour table, mass and momentum are
// conserved, walls bounce back, the force pushes.
#include "narrows/engines/lgca/fhp_lattice.hpp"
#include "narrows/engines/lgca/fhp_observables.hpp"
#include "narrows/engines/lgca/fhp_update.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <random>
#include <vector>

using namespace narrows::lgca;

namespace {

// One rank owns the whole lattice (MPI_COMM_SELF): local column = global column.
FhpLattice make(FhpModel m, int X, int Y, bool walls = false, double force = 0.0) {
  FhpParams p;
  p.model = m;
  p.size_x = X;
  p.size_y = Y;
  p.seed = 5;
  p.walls = walls;
  p.force = force;
  return FhpLattice(p, MPI_COMM_SELF);
}

void clear(FhpLattice &l) {
  for (int y = 0; y < l.size_y(); ++y)
    for (int x = 0; x < l.local_columns(); ++x)
      l.row(y)[x] = 0;
}

} // namespace

TEST(FhpKernel, PortableAndVbmiAgree) {
  if (!vbmi_kernel())
    GTEST_SKIP() << "this build has no AVX-512 VBMI kernel";
#ifdef __AVX512VBMI__
  std::mt19937_64 gen(3);
  const auto t = make_collision_table(FhpModel::fhp_iii);
  std::array<std::uint8_t, 128> bounce{};
  for (int s = 0; s < 128; ++s)
    bounce[s] = bounce_back(static_cast<std::uint8_t>(s));
  for (const int n : {1, 63, 64, 65, 200, 517}) {
    std::vector<std::uint8_t> rows(3 * (n + 2) + 64), solid(n + 64), a(n + 64), b(n + 64);
    for (auto &v : rows)
      v = static_cast<std::uint8_t>(gen() & 0x7F);
    for (auto &v : solid)
      v = (gen() % 5 == 0) ? 0xFF : 0;
    std::vector<std::uint64_t> chir((n + 63) / 64 + 1);
    for (auto &w : chir)
      w = gen();
    for (int odd = 0; odd < 2; ++odd)
      for (const bool with_solid : {false, true}) {
        RowUpdate r;
        r.below = rows.data() + 1;
        r.here = rows.data() + (n + 2) + 1;
        r.above = rows.data() + 2 * (n + 2) + 1;
        r.solid = with_solid ? solid.data() : nullptr;
        r.chirality = chir.data();
        r.table = t.out[0].data();
        r.bounce = bounce.data();
        r.n = n;
        r.odd = odd;
        r.out = a.data();
        update_row_portable(r);
        r.out = b.data();
        update_row_vbmi(r);
        for (int x = 0; x < n; ++x)
          ASSERT_EQ(a[x], b[x]) << "n " << n << " odd " << odd << " solid " << with_solid << " x "
                                << x;
      }
  }
#endif
}

// A lone particle (it never collides) moves to the neighbour of the header's table.
TEST(FhpLattice, PropagationFollowsTheNeighbourTable) {
  const int X = 8, Y = 6;
  for (int y = 0; y < 2; ++y)
    for (int i = 0; i < 7; ++i) {
      auto l = make(FhpModel::fhp_ii, X, Y);
      clear(l);
      const int x = 3;
      l.row(y + 2)[x] = static_cast<std::uint8_t>(1u << i);
      l.step();
      const int o = y % 2; // row y + 2 has the parity of y
      const int dx[7] = {1, o, -1 + o, -1, -1 + o, o, 0};
      const int dy[7] = {0, 1, 1, 0, -1, -1, 0};
      for (int yy = 0; yy < Y; ++yy)
        for (int xx = 0; xx < X; ++xx) {
          const bool here = xx == x + dx[i] && yy == y + 2 + dy[i];
          EXPECT_EQ(l.site(xx, yy), here ? (1u << i) : 0u) << "link " << i << " row " << y + 2;
        }
    }
}

TEST(FhpLattice, ConservesMassAndMomentum) {
  for (const auto m :
       {FhpModel::fhp_i, FhpModel::fhp_ii, FhpModel::fhp_iii, FhpModel::fhp_saturated}) {
    auto l = make(m, 130, 24);
    l.initialise(0.35, 0.1);
    const auto mass0 = total_mass(l);
    const auto p0 = total_momentum_x2(l);
    EXPECT_GT(shear_wave_amplitude(l), 0.05);
    for (int i = 0; i < 50; ++i)
      l.step();
    EXPECT_EQ(total_mass(l), mass0) << to_string(m);
    EXPECT_EQ(total_momentum_x2(l), p0) << to_string(m);
  }
}

TEST(FhpLattice, WallsBounceBack) {
  auto l = make(FhpModel::fhp_i, 8, 6, true);
  clear(l);
  // Row 1 is next to the solid row 0; a particle on link 4 (down-left) hits it and comes back
  // on link 1 to the site it left.
  l.row(1)[4] = 0x10;
  l.step();
  EXPECT_EQ(l.site(4, 0), 0x02); // reversed at the wall (odd row 1: down-left is x)
  l.step();
  EXPECT_EQ(l.site(4, 1), 0x02);
  EXPECT_EQ(total_mass(l), 1);
}

// The force moves a particle from link 3 to link 0 with probability p at every site where link 3
// is occupied and link 0 empty: +4 in units of momentum/2 per flip. initialise(d, 0) draws
// every link independently with probability d; propagation permutes links and the collision is
// a mass-conserving bijection of site states, so both keep that product measure exactly. At the
// first step's force the sites therefore qualify independently with probability d (1 - d), and
// the number of flips is Binomial(N, p d (1 - d)) (p the 16-bit threshold / 2^16): mean and
// standard deviation known exactly. Periodic box, so the momentum gained is 4 x the flips.
// Tolerance 4 sigma (0.5 % of the gain here).
TEST(FhpLattice, BodyForceInjectsTheExpectedMomentum) {
  const double p = 0.5, d = 0.3;
  const int X = 1024, Y = 256, seeds = 4;
  const double n_sites = double(X) * Y;
  const double p_eff = std::lround(p * 65536.0) / 65536.0;
  for (const auto m : {FhpModel::fhp_i, FhpModel::fhp_iii}) {
    double gained = 0.0;
    for (int seed = 0; seed < seeds; ++seed) {
      FhpParams prm;
      prm.model = m;
      prm.size_x = X;
      prm.size_y = Y;
      prm.seed = 100 + static_cast<std::uint64_t>(seed);
      prm.force = p;
      FhpLattice l(prm, MPI_COMM_SELF);
      l.initialise(d, 0.0);
      const auto mass0 = total_mass(l);
      const auto p0 = total_momentum_x2(l);
      l.step();
      EXPECT_EQ(total_mass(l), mass0);
      gained += static_cast<double>(total_momentum_x2(l) - p0);
    }
    const double q = p_eff * d * (1.0 - d), trials = seeds * n_sites;
    const double mean = trials * q, sigma = std::sqrt(trials * q * (1.0 - q));
    EXPECT_NEAR(gained / 4.0, mean, 4.0 * sigma) << to_string(m) << ": flips";
  }
}
