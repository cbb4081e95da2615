// The FHP lattice on 2, 3 or 4 ranks is bitwise the lattice on 1 rank (walls, obstacle, body
// force, every model), a checkpoint written on them continues bitwise on 1 rank, and the
// moment-propagation VACF is bitwise the one on 1 rank, and so are the lattice and the
// Ladd-Frenkel colloid (held across the slab edge, moving across it). 203 columns: uneven slabs
// on 2, 3 and 4 ranks.
#include "narrows/engines/lgca/fhp_checkpoint.hpp"
#include "narrows/engines/lgca/fhp_colloid.hpp"
#include "narrows/engines/lgca/fhp_lattice.hpp"
#include "narrows/engines/lgca/fhp_tagged.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

using namespace narrows::lgca;

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

TEST(LgcaBitwise, RanksEqualOneRank) {
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

TEST(LgcaBitwise, CheckpointOnRanksContinuesOnOne) {
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
TEST(LgcaBitwise, TaggedVacfRanksEqualOneRank) {
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

namespace {

// Everything a colloid run produces, in one vector of doubles: per step the composite
// velocity, composite mass and centre-of-mass velocity (collective), then the final momentum,
// omega, position and angle. Followed by the lattice (gather on rank 0).
struct ColloidRun {
  std::vector<double> trace;
  std::vector<std::uint8_t> lattice;
};

ColloidRun run_colloid(const FhpParams &p, const ColloidParams &cp, int steps, MPI_Comm comm) {
  FhpLattice l(p, comm);
  l.initialise(0.5, 0.0);
  FhpColloid c(cp, l);
  ColloidRun out;
  for (int i = 0; i < steps; ++i) {
    c.apply(l);
    l.step();
    const auto u = c.composite_velocity(l);
    const auto v = c.centre_of_mass_velocity(l);
    const auto x = c.position();
    out.trace.insert(out.trace.end(), {u[0], u[1], c.composite_mass(l), v[0], v[1], x[0], x[1]});
  }
  const auto m = c.momentum();
  const auto x = c.position();
  out.trace.insert(out.trace.end(), {static_cast<double>(m[0]), static_cast<double>(m[1]),
                                     c.omega(), x[0], x[1], c.angle()});
  // the replicated colloid is the same on every rank
  std::vector<double> lo(out.trace.size()), hi(out.trace.size());
  MPI_Allreduce(out.trace.data(), lo.data(), static_cast<int>(lo.size()), MPI_DOUBLE, MPI_MIN,
                comm);
  MPI_Allreduce(out.trace.data(), hi.data(), static_cast<int>(hi.size()), MPI_DOUBLE, MPI_MAX,
                comm);
  EXPECT_EQ(lo, hi) << "the colloid differs between the ranks";
  out.lattice = gather(l);
  return out;
}

} // namespace

// The colloid on slabs: replicated on every rank, the end sites of its boundary links gathered
// by one reduction. A held disc centred on the slab edge and a moving disc that crosses it
// (and one that crosses the periodic edge x = 0, the other slab edge) give the 1-rank lattice
// and colloid bit for bit, with the collective composite velocity, composite mass and
// centre-of-mass velocity equal at every step.
TEST(LgcaBitwise, ColloidRanksEqualOneRank) {
  FhpParams p;
  p.model = FhpModel::fhp_saturated;
  p.size_x = 203;
  p.size_y = 30;
  p.seed = 5;
  FhpLattice probe(p, MPI_COMM_WORLD);
  const double edge = probe.slabs().ranks() > 1 ? probe.slabs().first_column_of(1) : 101.0;
  struct Case {
    const char *name;
    double x, vx;
    bool held;
  };
  for (const Case &k : {Case{"held across the slab edge", edge + 0.2, 0.1, true},
                        Case{"moving across the slab edge", edge - 4.0, 0.3, false},
                        Case{"moving across x = 0", 3.0, -0.3, false}}) {
    ColloidParams cp;
    cp.x = k.x;
    cp.y = 13.0;
    cp.radius = 3.5;
    cp.mass = 680.0;
    cp.vx = k.vx;
    cp.vy = 0.05;
    cp.held = k.held;
    cp.seed_for_rules = p.seed;
    const int steps = 400;
    const ColloidRun two = run_colloid(p, cp, steps, MPI_COMM_WORLD);
    if (world_rank() != 0)
      continue;
    const ColloidRun one = run_colloid(p, cp, steps, MPI_COMM_SELF);
    ASSERT_EQ(one.trace.size(), two.trace.size());
    std::size_t trace_differ = 0;
    for (std::size_t i = 0; i < one.trace.size(); ++i)
      trace_differ += one.trace[i] != two.trace[i];
    EXPECT_EQ(trace_differ, 0u) << k.name;
    EXPECT_EQ(differ(one.lattice, two.lattice), 0u) << k.name << ": sites differ";
    const std::size_t end = one.trace.size() - 6;
    const double x_end = one.trace[end + 3];
    std::printf("colloid %s: start x = %.2f, end x = %.2f, momentum (%.0f, %.0f) units\n", k.name,
                k.x, x_end, one.trace[end], one.trace[end + 1]);
    if (!k.held) {
      // it really crossed the edge it was meant to cross
      const double travelled = std::remainder(x_end - k.x, 203.0);
      EXPECT_GT(std::abs(travelled), 8.0) << k.name;
      EXPECT_GT(travelled * k.vx, 0.0) << k.name;
    }
  }
}
