// Exchange on any number of ranks with a toy species (large particles with a radius), so
// migrate, halo and reverse are exercised before colloids exist. On 3 or more ranks the left
// and right neighbours differ, which is what catches a left/right mix-up.
#include "narrows/core/error.hpp"
#include "narrows/parallel/exchange.hpp"

#include "../common/world.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <map>

using namespace narrows;

namespace {

struct Toy {
  std::vector<double> x, y, radius;
  std::vector<std::uint64_t> id;
  parallel::SoaView view() { return {{&x, &y, &radius}, {&id}}; }
  void add(double px, double py, double r, std::uint64_t i) {
    x.push_back(px);
    y.push_back(py);
    radius.push_back(r);
    id.push_back(i);
  }
};

int rank() { return narrows::testing::world_rank(); }
int ranks() { return narrows::testing::world_size(); }
// Periodic neighbours: on 2 ranks both are the other rank; on 3 or more they are distinct
// (left, self and right), so a left/right mix-up shows.
int left_of(int r) { return (r + ranks() - 1) % ranks(); }
int right_of(int r) { return (r + 1) % ranks(); }
constexpr double slab = 5.0; // rank r holds [5 r, 5 r + 5) of a periodic box of length 5 ranks

} // namespace

TEST(Exchange, MigrateToLeftAndRightNeighbours) {
  // Particle j goes to the left neighbour (j % 3 == 0), the right one (j % 3 == 1) or stays.
  Toy t;
  const int me = rank(), left = left_of(me), right = right_of(me);
  const auto x_of = [](int owner, int j) { return slab * owner + 0.1 * j; };
  for (int j = 0; j < 10; ++j)
    t.add(x_of(me, j), j, 0.5 + j, 100 * me + j);
  std::vector<int> dest(10);
  for (int j = 0; j < 10; ++j)
    dest[j] = j % 3 == 0 ? left : j % 3 == 1 ? right : me;
  parallel::Exchange ex(MPI_COMM_WORLD);
  ex.migrate(t.view(), dest);
  // Here now: my j % 3 == 2, the right neighbour's j % 3 == 0 (sent left), the left
  // neighbour's j % 3 == 1 (sent right).
  std::map<std::uint64_t, int> expected; // id -> its first owner
  for (int j = 0; j < 10; ++j) {
    if (j % 3 == 2)
      expected[100 * me + j] = me;
    if (j % 3 == 0)
      expected[100 * right + j] = right;
    if (j % 3 == 1)
      expected[100 * left + j] = left;
  }
  ASSERT_EQ(t.id.size(), expected.size()) << "rank " << me;
  std::map<std::uint64_t, std::size_t> at;
  for (std::size_t i = 0; i < t.id.size(); ++i)
    at[t.id[i]] = i;
  for (const auto &[id, owner] : expected) {
    ASSERT_TRUE(at.count(id)) << "id " << id << " missing on rank " << me;
    const std::size_t i = at[id];
    const int j = static_cast<int>(id % 100);
    EXPECT_EQ(t.x[i], x_of(owner, j)); // the row travelled whole
    EXPECT_EQ(t.y[i], j);
    EXPECT_EQ(t.radius[i], 0.5 + j);
  }
}

TEST(Exchange, HaloWidthEdgeCasesAndPeriodicShift) {
  const int me = rank(), left = left_of(me), right = right_of(me);
  const double lo = slab * me, hi = lo + slab, L = slab * ranks(), w = 1.0;
  Toy t;
  // Offsets from lo: at the left edge, exactly at the width (inclusive), just beyond it, in
  // the middle, exactly at the width from the right edge, just farther from it.
  const double offsets[] = {0.0, 1.0, 1.0 + 1e-9, 2.5, 4.0, 4.0 - 1e-9};
  for (int j = 0; j < 6; ++j)
    t.add(lo + offsets[j], 0.0, 1.0, 10 * me + j);
  parallel::Exchange ex(MPI_COMM_WORLD);
  const parallel::Halo h = ex.halo(t.view(), 0, lo, hi, L, w, left, right, slab);
  // The right neighbour's left-edge particles (offsets 0 and 1) and the left neighbour's
  // right-edge particle (offset 4): three ghosts, each placed next to my slab (x shifted by
  // +-L across the periodic end).
  ASSERT_EQ(h.size(), 3u) << "rank " << me;
  std::map<std::uint64_t, std::size_t> got;
  for (std::size_t g = 0; g < h.size(); ++g) {
    got[h.words[0][g]] = g;
    EXPECT_EQ(h.words[0][g] % 10, h.source_index[g]); // rows stayed together
  }
  const std::uint64_t from_right[] = {10u * right + 0, 10u * right + 1}, from_left = 10u * left + 4;
  for (int j = 0; j < 2; ++j) {
    ASSERT_TRUE(got.count(from_right[j])) << "rank " << me << ": id " << from_right[j];
    const std::size_t g = got[from_right[j]];
    EXPECT_EQ(h.source_rank[g], right);
    EXPECT_EQ(h.reals[0][g], hi + offsets[j]) << "rank " << me;
  }
  ASSERT_TRUE(got.count(from_left)) << "rank " << me << ": id " << from_left;
  EXPECT_EQ(h.source_rank[got[from_left]], left);
  EXPECT_EQ(h.reals[0][got[from_left]], lo - 1.0) << "rank " << me;
}

TEST(Exchange, HaloWiderThanASlabIsRefused) {
  Toy t;
  const int me = rank();
  t.add(slab * me + 0.5, 0, 1, 0);
  parallel::Exchange ex(MPI_COMM_WORLD);
  try {
    ex.halo(t.view(), 0, slab * me, slab * (me + 1), slab * ranks(), 5.5, left_of(me), right_of(me),
            slab);
    ADD_FAILURE() << "no error";
  } catch (const Error &e) {
    EXPECT_EQ(e.code(), ExitCode::bad_input);
    EXPECT_NE(std::string(e.what()).find("exceeds the narrowest slab"), std::string::npos);
  }
}

TEST(Exchange, ReverseSumsExactlyToOwners) {
  const int me = rank(), left = left_of(me), right = right_of(me);
  const double lo = slab * me;
  Toy t;
  for (int j = 0; j < 8; ++j) // every particle within 2.5 of some edge: one or two copies
    t.add(lo + 0.7 * j, 0.0, 1.0, 100 * me + j);
  parallel::Exchange ex(MPI_COMM_WORLD);
  const parallel::Halo h =
      ex.halo(t.view(), 0, lo, lo + slab, slab * ranks(), 2.5, left, right, slab);
  // Each ghost contributes a value of its id and of the rank holding it, so the sums show
  // that a left-edge copy went to the left neighbour and a right-edge copy to the right one.
  const int k = 2;
  const std::int64_t holder = std::int64_t{1} << 40;
  std::vector<std::int64_t> per_ghost(h.size() * k), per_owner(t.id.size() * k, 0);
  for (std::size_t g = 0; g < h.size(); ++g) {
    per_ghost[g * k] =
        (std::int64_t{1} << 50) + static_cast<std::int64_t>(h.words[0][g]) + holder * me;
    per_ghost[g * k + 1] = -3 * static_cast<std::int64_t>(h.words[0][g]) - 1;
  }
  ex.reverse(h, per_ghost, k, per_owner);
  for (std::size_t i = 0; i < t.id.size(); ++i) {
    const double u = 0.7 * static_cast<double>(i);
    const int at_left = u <= 2.5, at_right = slab - u <= 2.5;
    const auto id = static_cast<std::int64_t>(t.id[i]);
    const std::int64_t base = (std::int64_t{1} << 50) + id;
    EXPECT_EQ(per_owner[i * k],
              at_left * (base + holder * left) + at_right * (base + holder * right))
        << "rank " << me << " particle " << i;
    EXPECT_EQ(per_owner[i * k + 1], (at_left + at_right) * (-3 * id - 1));
  }
}

// Ghost rows for an arbitrary list of (row, rank) pairs, as colloids use them (ghosts.hpp): a
// row may go to several ranks, also beyond the neighbours; refresh() updates the same ghost
// rows from their owners; reverse() sums per-ghost values back.
TEST(Exchange, CopyRefreshAndReverseOfGhostRows) {
  const int me = rank(), P = ranks();
  Toy t;
  for (int j = 0; j < 4; ++j)
    t.add(slab * me + j, -j, 1.0 + j, 10 * me + j);
  // Row j goes to every other rank r with (r + j) % 2 == 0 (none, some or all of them).
  parallel::CopyList list;
  for (int j = 0; j < 4; ++j)
    for (int r = 0; r < P; ++r)
      if (r != me && (r + j) % 2 == 0) {
        list.index.push_back(j);
        list.dest.push_back(r);
      }
  parallel::Exchange ex(MPI_COMM_WORLD);
  const parallel::Halo h = ex.copy(t.view(), list);
  // Expected ghosts here: row j of every other rank s with (me + j) % 2 == 0.
  std::size_t expected = 0;
  for (int s = 0; s < P; ++s)
    for (int j = 0; j < 4; ++j)
      expected += s != me && (me + j) % 2 == 0;
  ASSERT_EQ(h.size(), expected) << "rank " << me;
  ASSERT_EQ(t.id.size(), 4 + expected);
  for (std::size_t g = 0; g < h.size(); ++g) {
    const std::size_t i = 4 + g;
    const int s = static_cast<int>(t.id[i] / 10), j = static_cast<int>(t.id[i] % 10);
    EXPECT_EQ(h.source_rank[g], s);
    EXPECT_EQ(h.source_index[g], static_cast<std::uint64_t>(j));
    EXPECT_EQ(t.x[i], slab * s + j); // the row unchanged, no periodic shift
    EXPECT_EQ(t.radius[i], 1.0 + j);
  }
  // Owners move their rows; refresh brings the ghosts along, in the same order.
  for (int j = 0; j < 4; ++j)
    t.x[j] += 1000.0;
  ex.refresh({&t.x}, list, 4);
  for (std::size_t g = 0; g < h.size(); ++g) {
    const std::size_t i = 4 + g;
    EXPECT_EQ(t.x[i], slab * static_cast<double>(t.id[i] / 10) + static_cast<double>(t.id[i] % 10) +
                          1000.0);
  }
  // Each ghost sends 1 + (its holder's rank) back: row j's sum is sum over its ghost holders.
  std::vector<std::int64_t> per_ghost(h.size(), 0), per_owner(4, 0);
  for (std::size_t g = 0; g < h.size(); ++g)
    per_ghost[g] = 1 + me;
  ex.reverse(h, per_ghost, 1, per_owner);
  for (int j = 0; j < 4; ++j) {
    std::int64_t want = 0;
    for (int r = 0; r < P; ++r)
      if (r != me && (r + j) % 2 == 0)
        want += 1 + r;
    EXPECT_EQ(per_owner[j], want) << "rank " << me << " row " << j;
  }
}
