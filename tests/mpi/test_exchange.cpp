// Exchange on 2 ranks with a toy species (large particles with a radius), so migrate, halo
// and reverse are exercised before colloids exist.
#include "narrows/core/error.hpp"
#include "narrows/parallel/exchange.hpp"

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

int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

} // namespace

TEST(Exchange, MigrateAcrossBothPeriodicEnds) {
  // Rank 0 holds slab [0, 5), rank 1 [5, 10) of a periodic box of length 10. Particles that
  // crossed x = 0 / x = 10 (the periodic end) and x = 5 change owner; the rest stay.
  Toy t;
  const int me = rank(), other = 1 - me;
  for (int j = 0; j < 10; ++j)
    t.add(me == 0 ? 0.1 * j : 9.9 - 0.1 * j, j, 0.5 + j, 100 * me + j);
  std::vector<int> dest(10);
  for (int j = 0; j < 10; ++j)
    dest[j] = j % 2 == 0 ? other : me;
  parallel::Exchange ex(MPI_COMM_WORLD);
  ex.migrate(t.view(), dest);
  ASSERT_EQ(t.id.size(), 10u);
  std::map<std::uint64_t, std::size_t> at;
  for (std::size_t i = 0; i < t.id.size(); ++i)
    at[t.id[i]] = i;
  for (int j = 0; j < 10; ++j) {
    const int owner_before = j % 2 == 0 ? other : me; // whose particle j is now here
    const std::uint64_t id = 100 * owner_before + j;
    ASSERT_TRUE(at.count(id)) << "id " << id << " missing on rank " << me;
    const std::size_t i = at[id];
    EXPECT_EQ(t.x[i], owner_before == 0 ? 0.1 * j : 9.9 - 0.1 * j);
    EXPECT_EQ(t.y[i], j);
    EXPECT_EQ(t.radius[i], 0.5 + j);
  }
}

TEST(Exchange, HaloWidthEdgeCasesAndPeriodicShift) {
  const int me = rank();
  const double lo = me == 0 ? 0.0 : 5.0, hi = lo + 5.0, L = 10.0, w = 1.0;
  Toy t;
  // Offsets from lo: at the left edge, exactly at the width (inclusive), just beyond it, in
  // the middle, exactly at the width from the right edge, just inside it.
  const double offsets[] = {0.0, 1.0, 1.0 + 1e-9, 2.5, 4.0, 4.0 - 1e-9};
  for (int j = 0; j < 6; ++j)
    t.add(lo + offsets[j], 0.0, 1.0, 10 * me + j);
  parallel::Exchange ex(MPI_COMM_WORLD);
  const int other = 1 - me;
  const parallel::Halo h = ex.halo(t.view(), 0, lo, hi, L, w, other, other, 5.0);
  // From the other rank: offsets 0 and 1 (left edge) and 4 (right edge) -> three ghosts.
  ASSERT_EQ(h.size(), 3u);
  std::map<std::uint64_t, double> got;
  for (std::size_t g = 0; g < h.size(); ++g) {
    EXPECT_EQ(h.source_rank[g], other);
    got[h.words[0][g]] = h.reals[0][g];
    EXPECT_EQ(h.words[0][g] % 10, h.source_index[g]); // rows stayed together
  }
  const double other_lo = other == 0 ? 0.0 : 5.0;
  // Rank 0's left-edge particles reach rank 1 across the periodic end: x + L.
  const double left_shift = other == 0 ? L : 0.0;
  const double right_shift = other == 1 ? -L : 0.0;
  EXPECT_EQ(got.at(10 * other + 0), other_lo + 0.0 + left_shift);
  EXPECT_EQ(got.at(10 * other + 1), other_lo + 1.0 + left_shift);
  EXPECT_EQ(got.at(10 * other + 4), other_lo + 4.0 + right_shift);
}

TEST(Exchange, HaloWiderThanASlabIsRefused) {
  Toy t;
  t.add(0.5, 0, 1, 0);
  parallel::Exchange ex(MPI_COMM_WORLD);
  try {
    ex.halo(t.view(), 0, 0.0, 5.0, 10.0, 5.5, 1 - rank(), 1 - rank(), 5.0);
    ADD_FAILURE() << "no error";
  } catch (const Error &e) {
    EXPECT_EQ(e.code(), ExitCode::bad_input);
    EXPECT_NE(std::string(e.what()).find("exceeds the narrowest slab"), std::string::npos);
  }
}

TEST(Exchange, ReverseSumsExactlyToOwners) {
  const int me = rank();
  const double lo = me == 0 ? 0.0 : 5.0;
  Toy t;
  for (int j = 0; j < 8; ++j) // every particle within 2.5 of some edge: one or two copies
    t.add(lo + 0.7 * j, 0.0, 1.0, 100 * me + j);
  parallel::Exchange ex(MPI_COMM_WORLD);
  const parallel::Halo h = ex.halo(t.view(), 0, lo, lo + 5.0, 10.0, 2.5, 1 - me, 1 - me, 5.0);
  const int k = 2;
  std::vector<std::int64_t> per_ghost(h.size() * k), per_owner(t.id.size() * k, 0);
  for (std::size_t g = 0; g < h.size(); ++g) {
    per_ghost[g * k] = (std::int64_t{1} << 50) + static_cast<std::int64_t>(h.words[0][g]);
    per_ghost[g * k + 1] = -3 * static_cast<std::int64_t>(h.words[0][g]) - 1;
  }
  ex.reverse(h, per_ghost, k, per_owner);
  for (std::size_t i = 0; i < t.id.size(); ++i) {
    const double u = 0.7 * static_cast<double>(i);
    const int copies = (u <= 2.5) + (5.0 - u <= 2.5);
    const auto id = static_cast<std::int64_t>(t.id[i]);
    EXPECT_EQ(per_owner[i * k], copies * ((std::int64_t{1} << 50) + id)) << "particle " << i;
    EXPECT_EQ(per_owner[i * k + 1], copies * (-3 * id - 1));
  }
}
