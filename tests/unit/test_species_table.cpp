// The species tables (species/table.hpp): the checkpoint datasets each species derives from its
// table are exactly those checkpoints have always held (names, shapes, kinds: older checkpoints
// must still restart, and new ones must read in older tools), and the row operations move every
// field, added ones too.
#include "narrows/colloids/colloids.hpp"
#include "narrows/colloids/contact_history.hpp"
#include "narrows/core/error.hpp"
#include "narrows/engines/mpcd/kernels/fluid.hpp"
#include "narrows/io/species_fields.hpp"
#include "narrows/parallel/exchange.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace narrows;

namespace {

// "name[d]" for vector fields, "name:u64" for word fields, "name" for the others, in the
// order the checkpoint writer creates them (vectors, words, scalars).
std::vector<std::string> datasets(const io::SpeciesFields &s) {
  std::vector<std::string> out;
  for (const auto &[name, comp] : s.vectors)
    out.push_back(name + "[" + std::to_string(s.dim) + "]");
  for (const auto &[name, words] : s.words)
    out.push_back(name + ":u64");
  for (const auto &[name, values] : s.scalars)
    out.push_back(name);
  return out;
}

} // namespace

TEST(SpeciesTable, CheckpointDatasetsAsEver) {
  for (int dim : {2, 3}) {
    colloids::Colloids c;
    c.dim = dim;
    const io::SpeciesFields s = io::checkpoint_fields(table(c));
    EXPECT_EQ(s.name, "colloids");
    std::vector<std::string> want{"position[" + std::to_string(dim) + "]",
                                  "velocity[" + std::to_string(dim) + "]", "id:u64", "radius",
                                  "mass"};
    if (dim == 3) // a disk spins about z only
      want.insert(want.end(), {"angular_velocity_x", "angular_velocity_y"});
    want.insert(want.end(), {"angular_velocity_z", "orientation_w", "orientation_x",
                             "orientation_y", "orientation_z"});
    EXPECT_EQ(datasets(s), want) << dim << "D colloids";

    mpcd::Fluid f;
    f.dim = dim;
    const io::SpeciesFields fs = io::checkpoint_fields(table(f));
    EXPECT_EQ(fs.name, "fluid");
    EXPECT_EQ(datasets(fs),
              (std::vector<std::string>{"position[" + std::to_string(dim) + "]",
                                        "velocity[" + std::to_string(dim) + "]", "id:u64"}));

    colloids::ContactHistory h;
    h.dim = dim;
    const io::SpeciesFields hs = io::checkpoint_fields(table(h));
    EXPECT_EQ(hs.name, "contacts");
    EXPECT_EQ(datasets(hs),
              (std::vector<std::string>{"tangential_displacement[" + std::to_string(dim) + "]",
                                        "owner_id:u64", "partner_id:u64"}));
  }
}

TEST(SpeciesTable, ExchangeSendsEveryFieldOfTheFlag) {
  // What migrates with a fluid particle: positions, velocities, id and cell (so a row moved within
  // a rank keeps its binning); a colloid also sends its spin and orientation in 2D.
  mpcd::Fluid f;
  const parallel::SoaView fv = parallel::view(table(f), species::migrates);
  EXPECT_EQ(fv.reals.size(), 4u);
  EXPECT_EQ(fv.words.size(), 1u);
  EXPECT_EQ(fv.halfwords.size(), 1u);
  EXPECT_TRUE(fv.kept.empty());
  colloids::Colloids c;
  c.extra.add<double>("kept_here", species::checkpoint, 0);
  const parallel::SoaView cv = parallel::view(table(c), species::ghost);
  EXPECT_EQ(cv.reals.size(), 2u + 2u + 1u + 1u + 3u + 4u);
  EXPECT_EQ(cv.words.size(), 1u);
  EXPECT_EQ(cv.kept.size(), 1u); // the added field without the ghost flag
}

TEST(SpeciesTable, RowOperationsMoveEveryField) {
  colloids::Colloids c;
  c.resize(3);
  auto &tag = c.extra.add<std::uint64_t>("tag", species::everywhere, c.size(), 7.0);
  EXPECT_EQ(tag, (std::vector<std::uint64_t>{7, 7, 7}));
  for (std::size_t a = 0; a < 3; ++a) {
    c.id[a] = a;
    c.x[0][a] = 10.0 + a;
    c.q[2][a] = 0.5 * a;
    tag[a] = 100 + a;
  }
  c.resize(4); // a new row: at rest, the identity orientation, the added field's fill
  EXPECT_EQ(c.q[0][3], 1.0);
  EXPECT_EQ(c.q[2][3], 0.0);
  EXPECT_EQ(c.extra.get<std::uint64_t>("tag")[3], 7u);
  EXPECT_EQ(c.omega[2].size(), 4u);
  EXPECT_TRUE(c.x[2].empty()); // no z in 2D

  table(c).permute({2, 0, 3, 1});
  EXPECT_EQ(c.id, (std::vector<std::uint64_t>{2, 0, 0, 1}));
  EXPECT_EQ(c.extra.get<std::uint64_t>("tag"), (std::vector<std::uint64_t>{102, 100, 7, 101}));
  EXPECT_EQ(c.x[0][0], 12.0);
  EXPECT_EQ(c.q[2][0], 1.0);

  table(c).keep_rows({true, false, true, true});
  EXPECT_EQ(c.size(), 3u);
  EXPECT_EQ(c.extra.get<std::uint64_t>("tag"), (std::vector<std::uint64_t>{102, 7, 101}));
  EXPECT_EQ(c.q[0].size(), 3u);

  colloids::Colloids d;
  d.extra = c.extra.same_fields();
  d.resize(1);
  table(d).copy_row(0, table(c), 2);
  EXPECT_EQ(d.id[0], 1u);
  EXPECT_EQ(d.x[0][0], 11.0);
  EXPECT_EQ(d.extra.get<std::uint64_t>("tag")[0], 101u);

  // A field twice, or rows changed through a table of a const species: refused.
  c.extra.add<double>("radius", species::everywhere, c.size());
  EXPECT_THROW(table(c), Error);
  const colloids::Colloids &read = d;
  EXPECT_THROW(table(read).resize(0), Error);
}
