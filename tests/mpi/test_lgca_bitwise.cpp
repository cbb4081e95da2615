// The FHP lattice on 2 ranks is bitwise the lattice on 1 rank (walls, obstacle, body force,
// every model), a checkpoint written on 2 ranks continues bitwise on 1 rank, and the
// moment-propagation VACF on 2 ranks is bitwise the one on 1 rank.
#include "narrows/lattice/fhp_checkpoint.hpp"
#include "narrows/lattice/fhp_lattice.hpp"
#include "narrows/lattice/fhp_tagged.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <filesystem>
#include <vector>

using namespace narrows::lattice;

namespace {

int world_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

FhpParams params(FhpModel m) {
  FhpParams p;
  p.model = m;
  p.size_x = 203; // not a multiple of 64 or 128: slab edges inside words and Philox blocks
  p.size_y = 30;
  p.seed = 11;
  p.walls = true;
  p.force = 0.02;
  p.obstacles.push_back({100.3, 12.0, 4.5});
  return p;
}

// The whole lattice on rank 0 (row-major [y][x]); empty elsewhere.
std::vector<std::uint8_t> gather(const FhpLattice &l) {
  int ranks = 1;
  MPI_Comm_size(l.comm(), &ranks);
  const int X = l.size_x(), Y = l.size_y();
  std::vector<std::uint8_t> mine;
  for (int x = 0; x < l.local_columns(); ++x)
    for (int y = 0; y < Y; ++y)
      mine.push_back(l.site(x, y));
  std::vector<int> counts(ranks), displs(ranks);
  const int n = static_cast<int>(mine.size());
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, l.comm());
  for (int r = 1; r < ranks; ++r)
    displs[r] = displs[r - 1] + counts[r - 1];
  std::vector<std::uint8_t> cols(static_cast<std::size_t>(X) * Y);
  MPI_Gatherv(mine.data(), n, MPI_BYTE, cols.data(), counts.data(), displs.data(), MPI_BYTE, 0,
              l.comm());
  std::vector<std::uint8_t> out(cols.size());
  for (int x = 0; x < X; ++x)
    for (int y = 0; y < Y; ++y)
      out[static_cast<std::size_t>(y) * X + x] = cols[static_cast<std::size_t>(x) * Y + y];
  return out;
}

std::size_t differ(const std::vector<std::uint8_t> &a, const std::vector<std::uint8_t> &b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    n += a[i] != b[i];
  return n;
}

} // namespace

TEST(LgcaBitwise, TwoRanksEqualOneRank) {
  for (const auto m :
       {FhpModel::fhp_i, FhpModel::fhp_ii, FhpModel::fhp_iii, FhpModel::fhp_saturated}) {
    const int steps = 300;
    FhpLattice par(params(m), MPI_COMM_WORLD);
    par.initialise(0.3, 0.05);
    for (int i = 0; i < steps; ++i)
      par.step();
    const auto two = gather(par);
    if (world_rank() != 0)
      continue;
    FhpLattice ser(params(m), MPI_COMM_SELF);
    ser.initialise(0.3, 0.05);
    for (int i = 0; i < steps; ++i)
      ser.step();
    const auto one = gather(ser);
    ASSERT_EQ(one.size(), two.size());
    EXPECT_EQ(differ(one, two), 0u) << to_string(m) << ": sites differ after " << steps;
  }
}

TEST(LgcaBitwise, CheckpointOnTwoRanksContinuesOnOne) {
  const auto p = params(FhpModel::fhp_iii);
  const std::string dir = "lgca_bitwise_ckpt";
  if (world_rank() == 0)
    std::filesystem::create_directories(dir);
  MPI_Barrier(MPI_COMM_WORLD);
  const std::string path = dir + "/checkpoint-0000000100.h5";
  FhpLattice par(p, MPI_COMM_WORLD);
  par.initialise(0.4, 0.05);
  for (int i = 0; i < 100; ++i)
    par.step();
  write_lattice_checkpoint(path, par, "# test scene\n");
  for (int i = 0; i < 50; ++i)
    par.step();
  const auto straight = gather(par);
  if (world_rank() == 0) {
    FhpLattice ser(p, MPI_COMM_SELF);
    const auto info = narrows::io::read_checkpoint_header(path, MPI_COMM_SELF);
    read_lattice_checkpoint(path, info, ser);
    EXPECT_EQ(ser.time(), 100);
    for (int i = 0; i < 50; ++i)
      ser.step();
    EXPECT_EQ(differ(gather(ser), straight), 0u);
    std::filesystem::remove_all(dir);
  }
}

// The tagged weights cross the slab boundaries every step (one halo column of q = a / rho);
// column sums taken in global order make the VACF bitwise equal, error included.
TEST(LgcaBitwise, TaggedVacfTwoRanksEqualOneRank) {
  for (const auto m : {FhpModel::fhp_i, FhpModel::fhp_iii}) {
    auto p = params(m);
    p.force = 0.0;
    const auto run = [&](MPI_Comm comm) {
      FhpLattice l(p, comm);
      l.initialise(0.3, 0.0);
      FhpTagged tagged(l, 25);
      tagged.feed(l);
      for (int i = 0; i < 160; ++i) {
        l.step();
        tagged.feed(l);
      }
      auto z = tagged.mean();
      const auto e = tagged.error();
      z.insert(z.end(), e.begin(), e.end());
      return z;
    };
    const auto two = run(MPI_COMM_WORLD);
    if (world_rank() != 0)
      continue;
    const auto one = run(MPI_COMM_SELF);
    ASSERT_EQ(one.size(), 52u);
    ASSERT_EQ(two.size(), one.size());
    for (std::size_t k = 0; k < one.size(); ++k)
      EXPECT_EQ(one[k], two[k]) << to_string(m) << " entry " << k;
    EXPECT_GT(one[26 + 1], 0.0); // six curves: a real spread, not a vacuous comparison
  }
}
