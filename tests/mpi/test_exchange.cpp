// Exchange on any number of ranks with a toy species (large particles with a radius): migrate,
// and the copy, refresh and reverse of ghost rows that colloids use. On 3 or more ranks the left
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
  parallel::SoaView view() { return {{&x, &y, &radius}, {&id}, {}, {}}; }
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
