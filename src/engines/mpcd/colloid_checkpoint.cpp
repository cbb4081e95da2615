// Writing and reading the colloid species of a checkpoint (all colloids, in id order).
#include "narrows/engines/mpcd/colloid_checkpoint.hpp"

#include "narrows/core/error.hpp"
#include "narrows/engines/mpcd/colloid_placement.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace narrows::mpcd {

namespace {

// The components of the angular velocity a colloid has: z in 2D, all three in 3D.
const char *const spin_names[3] = {"angular_velocity_x", "angular_velocity_y",
                                   "angular_velocity_z"};
int first_spin(int dim) { return dim == 2 ? 2 : 0; }
// The orientation quaternion (w, x, y, z).
const char *const orientation_names[4] = {"orientation_w", "orientation_x", "orientation_y",
                                          "orientation_z"};

// The stored fields of c: position, velocity, id, and (sizes) radius and mass, (spins) the
// angular velocity.
io::SpeciesFields fields_of(colloids::Colloids &c, bool sizes = true, bool spins = true,
                            bool orientations = true) {
  io::SpeciesFields s;
  s.name = "colloids";
  s.dim = c.dim;
  s.vectors.push_back({"position", {&c.x[0], &c.x[1], &c.x[2]}});
  s.vectors.push_back({"velocity", {&c.v[0], &c.v[1], &c.v[2]}});
  s.words.push_back({"id", &c.id});
  if (sizes) {
    s.scalars.push_back({"radius", &c.radius});
    s.scalars.push_back({"mass", &c.mass});
  }
  if (spins)
    for (int k = first_spin(c.dim); k < 3; ++k)
      s.scalars.push_back({spin_names[k], &c.omega[k]});
  if (orientations)
    for (int k = 0; k < 4; ++k)
      s.scalars.push_back({orientation_names[k], &c.q[k]});
  return s;
}

} // namespace

io::SpeciesFields colloid_fields(colloids::Colloids &c, colloids::Colloids &empty, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0)
    return fields_of(c);
  empty.dim = c.dim;
  empty.resize(0);
  return fields_of(empty);
}

colloids::Colloids read_colloids(const std::string &path, const scene::Colloids &spec, int dim,
                                 double density, std::uint64_t seed, MPI_Comm comm) {
  colloids::Colloids block;
  block.dim = dim;
  block.resize(0);
  // Checkpoints written before radius and mass were stored: both follow from the scene.
  const bool sizes = io::has_species_field(path, "colloids", "radius", comm) &&
                     io::has_species_field(path, "colloids", "mass", comm);
  // Checkpoints written before colloids could spin: they did not.
  const bool spins = io::has_species_field(path, "colloids", "angular_velocity_z", comm);
  // ... nor orientations: the identity.
  const bool orientations = io::has_species_field(path, "colloids", "orientation_w", comm);
  io::SpeciesFields s = fields_of(block, sizes, spins, orientations);
  io::read_species(path, s, comm);

  // Gather every rank's block everywhere: rows of 2 dim + 3 words (id, radius, mass), 3 spins
  // and 4 orientation components.
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const int row = 2 * dim + 10;
  const int mine = static_cast<int>(block.id.size());
  std::vector<int> counts(ranks), displs(ranks, 0);
  MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  std::vector<double> send(static_cast<std::size_t>(mine) * row);
  for (int i = 0; i < mine; ++i) {
    double *r = &send[static_cast<std::size_t>(i) * row];
    for (int k = 0; k < dim; ++k) {
      r[k] = block.x[k][i];
      r[dim + k] = block.v[k][i];
    }
    r[2 * dim] = static_cast<double>(block.id[i]); // ids < 2^53
    r[2 * dim + 1] = sizes ? block.radius[i] : 0.0;
    r[2 * dim + 2] = sizes ? block.mass[i] : 0.0;
    for (int k = 0; k < 3; ++k)
      r[2 * dim + 3 + k] = spins && k >= first_spin(dim) ? block.omega[k][i] : 0.0;
    for (int k = 0; k < 4; ++k)
      r[2 * dim + 6 + k] = orientations ? block.q[k][i] : (k == 0 ? 1.0 : 0.0);
  }
  int total = 0;
  for (int r = 0; r < ranks; ++r) {
    displs[r] = total * row;
    total += counts[r];
    counts[r] *= row;
  }
  if (total != spec.count)
    throw input_error(path + ": holds " + std::to_string(total) + " colloids, the scene has " +
                      std::to_string(spec.count) + "; allowed: a checkpoint of this scene");
  std::vector<double> all(static_cast<std::size_t>(total) * row);
  MPI_Allgatherv(send.data(), mine * row, MPI_DOUBLE, all.data(), counts.data(), displs.data(),
                 MPI_DOUBLE, comm);
  colloids::Colloids c;
  c.dim = dim;
  c.resize(static_cast<std::size_t>(total));
  set_radii_and_masses(c, spec, density, seed);
  // Every rank holds all rows: the same refusal everywhere, naming the first bad row.
  const auto edges = io::read_box_edges(path, "colloids", dim, comm);
  std::vector<bool> seen(static_cast<std::size_t>(total), false);
  for (int i = 0; i < total; ++i) {
    const double *r = &all[static_cast<std::size_t>(i) * row];
    const std::string at = " row " + std::to_string(i);
    for (int k = 0; k < dim; ++k) {
      if (!(r[k] >= 0.0 && r[k] <= edges[k]))
        throw input_error(path + ": /particles/colloids/position/value" + at + " component " +
                          std::to_string(k) + " = " + std::to_string(r[k]) +
                          "; allowed: inside the box, 0 to " + std::to_string(edges[k]));
      if (!std::isfinite(r[dim + k]))
        throw input_error(path + ": /particles/colloids/velocity/value" + at + " component " +
                          std::to_string(k) + " = " + std::to_string(r[dim + k]) +
                          "; allowed: a finite number");
    }
    const auto id = static_cast<std::uint64_t>(r[2 * dim]);
    if (id >= static_cast<std::uint64_t>(total))
      throw input_error(path + ": /particles/colloids/id/value" + at + " holds id " +
                        std::to_string(id) + "; allowed: 0 to " + std::to_string(total - 1));
    if (seen[id])
      throw input_error(path + ": /particles/colloids/id/value" + at + " holds id " +
                        std::to_string(id) +
                        ", as does an earlier row; allowed: every id from 0 "
                        "to " +
                        std::to_string(total - 1) + " once");
    seen[id] = true;
    for (int k = 0; k < dim; ++k) {
      c.x[k][id] = r[k];
      c.v[k][id] = r[dim + k];
    }
    c.id[id] = id;
    for (int k = first_spin(dim); k < 3; ++k) {
      const double w = r[2 * dim + 3 + k];
      if (!std::isfinite(w))
        throw input_error(path + ": /particles/colloids/" + spin_names[k] + "/value" + at + " = " +
                          std::to_string(w) + "; allowed: a finite number");
      c.omega[k][id] = w;
    }
    double norm2 = 0.0;
    for (int k = 0; k < 4; ++k) {
      c.q[k][id] = r[2 * dim + 6 + k];
      norm2 += c.q[k][id] * c.q[k][id];
    }
    if (!(std::abs(norm2 - 1.0) < 1e-6))
      throw input_error(path + ": /particles/colloids/orientation_*" + at +
                        " is not a unit "
                        "quaternion (|q|^2 = " +
                        std::to_string(norm2) + "); allowed: w^2 + x^2 + y^2 + z^2 = 1");
    if (sizes) { // restored exactly as they were written
      const double radius = r[2 * dim + 1], mass = r[2 * dim + 2];
      if (!(radius > 0.0 && std::isfinite(radius) && mass > 0.0 && std::isfinite(mass)))
        throw input_error(path + ": colloid id " + std::to_string(id) + " has radius " +
                          std::to_string(radius) + " and mass " + std::to_string(mass) +
                          "; allowed: finite numbers > 0");
      c.radius[id] = radius;
      c.mass[id] = mass;
    }
  }
  return c;
}

namespace {

io::SpeciesFields fields_of(colloids::ContactHistory &h) {
  io::SpeciesFields s;
  s.name = "contacts";
  s.dim = h.dim;
  s.words.push_back({"owner_id", &h.owner});
  s.words.push_back({"partner_id", &h.partner});
  s.vectors.push_back({"tangential_displacement", {&h.xi[0], &h.xi[1], &h.xi[2]}});
  return s;
}

} // namespace

io::SpeciesFields contact_fields(colloids::ContactHistory &all, colloids::ContactHistory &empty,
                                 MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0)
    return fields_of(all);
  empty.dim = all.dim;
  empty.resize(0);
  return fields_of(empty);
}

colloids::ContactHistory read_contacts(const std::string &path, std::int64_t colloids, int dim,
                                       bool walls, MPI_Comm comm) {
  colloids::ContactHistory block;
  block.dim = dim;
  if (!io::has_species_field(path, "contacts", "owner_id", comm))
    return block;
  io::SpeciesFields s = fields_of(block);
  io::read_species(path, s, comm);
  block.resize(block.owner.size());
  colloids::ContactHistory all = colloids::gather_contacts(block, comm);
  // Every rank holds all rows (in key order): the same refusal everywhere.
  const auto n = static_cast<std::uint64_t>(colloids);
  const std::string set = path + ": /particles/contacts/";
  for (std::size_t j = 0; j < all.size(); ++j) {
    const std::string at =
        " (contact " + std::to_string(all.owner[j]) + "-" +
        (colloids::is_wall_id(all.partner[j])
             ? std::string(all.partner[j] == colloids::wall_low_id ? "wall y = 0" : "wall y = L_y")
             : std::to_string(all.partner[j])) +
        ")";
    if (all.owner[j] >= n)
      throw input_error(set + "owner_id/value holds " + std::to_string(all.owner[j]) + at +
                        "; allowed: a colloid id, 0 to " + std::to_string(n - 1));
    const std::uint64_t p = all.partner[j];
    if (colloids::is_wall_id(p) ? !walls : (p >= n || p <= all.owner[j]))
      throw input_error(set + "partner_id/value holds " + std::to_string(p) + at +
                        "; allowed: a colloid id above the owner's, up to " +
                        std::to_string(n - 1) +
                        (walls ? ", or a wall (2^64 - 1: y = 0, 2^64 - 2: y = L_y)" : ""));
    if (j > 0 && all.owner[j] == all.owner[j - 1] && p == all.partner[j - 1])
      throw input_error(set + "owner_id/value and partner_id/value hold the same contact twice" +
                        at + "; allowed: each pair once");
    for (int k = 0; k < dim; ++k)
      if (!std::isfinite(all.xi[k][j]))
        throw input_error(set + "tangential_displacement/value component " + std::to_string(k) +
                          " = " + std::to_string(all.xi[k][j]) + at + "; allowed: a finite number");
  }
  return all;
}

} // namespace narrows::mpcd
