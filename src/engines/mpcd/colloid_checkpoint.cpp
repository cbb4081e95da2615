// Writing and reading the colloid species of a checkpoint (all colloids, in id order).
#include "narrows/engines/mpcd/colloid_checkpoint.hpp"

#include "narrows/core/error.hpp"
#include "narrows/engines/mpcd/colloid_placement.hpp"
#include "narrows/io/species_fields.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <tuple>
#include <vector>

namespace narrows::mpcd {

namespace {

// The components of the angular velocity a colloid has: z in 2D, all three in 3D.
const char *const spin_names[3] = {"angular_velocity_x", "angular_velocity_y",
                                   "angular_velocity_z"};
int first_spin(int dim) { return dim == 2 ? 2 : 0; }

std::string number_text(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

} // namespace

io::SpeciesFields colloid_fields(colloids::Colloids &c, colloids::Colloids &empty, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0)
    return io::checkpoint_fields(table(c));
  empty.dim = c.dim;
  empty.extra = c.extra.same_fields();
  empty.resize(0);
  return io::checkpoint_fields(table(empty));
}

colloids::Colloids read_colloids(const std::string &path, const scene::Colloids &spec, int dim,
                                 double density, std::uint64_t seed, MPI_Comm comm,
                                 const colloids::Colloids *like) {
  colloids::Colloids block;
  block.dim = dim;
  if (like != nullptr)
    block.extra = like->extra.same_fields();
  block.resize(0);
  const species::Table fields = table(block);
  // Fields older checkpoints lack keep their fill: at rest, the identity orientation. Radius and
  // mass (both, or neither is used) then follow from the scene.
  std::vector<const species::Field *> absent;
  for (const species::Field &f : fields.fields())
    if (f.has(species::checkpoint | species::added_later) &&
        !io::has_checkpoint_field(path, fields, f, comm))
      absent.push_back(&f);
  const auto lacks = [&](std::string_view name) {
    return std::any_of(absent.begin(), absent.end(),
                       [&](const species::Field *f) { return f->name == name; });
  };
  // Checkpoints gained these fields in this order (radius and mass, then the angular velocity
  // with the no-slip colloids, then the orientation; the contacts came after all of them): an
  // older checkpoint lacks the newest ones only, and a checkpoint of no-slip colloids or of
  // contacts lacks none of those its scene needs. Anything else lost a field (issue 35: a deleted
  // orientation_w, radius or angular_velocity_z was silently reset).
  {
    const char *const order[4] = {"radius", "mass", "angular_velocity", "orientation"};
    int needed = 0; // fields of `order` this scene's checkpoints always hold
    if (spec.coupling == scene::ColloidCoupling::no_slip)
      needed = 3;
    if (spec.contacts != scene::ColloidContacts::none)
      needed = 4;
    const auto stored_name = [&](std::string_view name) {
      const species::Field *f = fields.find(name);
      return "/particles/colloids/" +
             f->stored_name(f->shape == species::Shape::split ? f->first_stored : 0) + "/value";
    };
    for (int k = 0; k < 4; ++k) {
      if (!lacks(order[k]))
        continue;
      for (int later = k + 1; later < 4; ++later)
        if (!lacks(order[later]))
          throw input_error(path + ": missing dataset " + stored_name(order[k]) + " but " +
                            stored_name(order[later]) +
                            " is there; allowed: every colloid field (only a checkpoint older "
                            "than a field lacks it, and then all that came later too)");
      if (k < needed)
        throw input_error(path + ": missing dataset " + stored_name(order[k]) +
                          "; allowed: a checkpoint of " +
                          (needed == 4 ? "colloid contacts" : "no-slip colloids") +
                          " holds radius, mass, angular_velocity_*" +
                          (needed == 4 ? ", orientation_*" : "") + " (it is not reset)");
    }
  }
  const bool sizes = !lacks("radius") && !lacks("mass");
  io::SpeciesFields s = io::checkpoint_fields(fields, [&](const species::Field &f) {
    return lacks(f.name) || (!sizes && (f.name == "radius" || f.name == "mass"));
  });
  io::read_species(path, s, comm);
  block.resize(block.id.size()); // (the fields left out: their fill)

  // Every rank's block everywhere, in file order.
  colloids::Colloids all;
  all.dim = dim;
  all.extra = block.extra.same_fields();
  species::Table gathered = table(all);
  species::gather(fields, gathered, comm);
  const int total = static_cast<int>(all.size());
  if (total != spec.count)
    throw input_error(path + ": holds " + std::to_string(total) + " colloids, the scene has " +
                      std::to_string(spec.count) + "; allowed: a checkpoint of this scene");
  colloids::Colloids c;
  c.dim = dim;
  c.extra = block.extra.same_fields();
  c.resize(static_cast<std::size_t>(total));
  set_radii_and_masses(c, spec, density, seed);
  const std::vector<double> scene_radius = c.radius, scene_mass = c.mass;
  const species::Table by_id = table(c);
  // Every rank holds all rows: the same refusal everywhere, naming the first bad row.
  const auto edges = io::read_box_edges(path, "colloids", dim, comm);
  std::vector<bool> seen(static_cast<std::size_t>(total), false);
  for (int i = 0; i < total; ++i) {
    const std::string at = " row " + std::to_string(i);
    for (int k = 0; k < dim; ++k) {
      const double x = all.x[k][i], v = all.v[k][i];
      if (!(x >= 0.0 && x <= edges[k]))
        throw input_error(path + ": /particles/colloids/position/value" + at + " component " +
                          std::to_string(k) + " = " + number_text(x) +
                          "; allowed: inside the box, 0 to " + number_text(edges[k]));
      if (!std::isfinite(v))
        throw input_error(path + ": /particles/colloids/velocity/value" + at + " component " +
                          std::to_string(k) + " = " + number_text(v) +
                          "; allowed: a finite number");
    }
    const std::uint64_t id = all.id[i];
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
    by_id.copy_row(id, gathered, static_cast<std::size_t>(i)); // every field, the row of its id
    for (int k = first_spin(dim); k < 3; ++k) {
      const double w = c.omega[k][id];
      if (!std::isfinite(w))
        throw input_error(path + ": /particles/colloids/" + spin_names[k] + "/value" + at + " = " +
                          number_text(w) + "; allowed: a finite number");
    }
    double norm2 = 0.0;
    for (int k = 0; k < 4; ++k)
      norm2 += c.q[k][id] * c.q[k][id];
    if (!(std::abs(norm2 - 1.0) < 1e-6))
      throw input_error(path + ": /particles/colloids/orientation_*" + at +
                        " is not a unit "
                        "quaternion (|q|^2 = " +
                        number_text(norm2) + "); allowed: w^2 + x^2 + y^2 + z^2 = 1");
    if (sizes) { // restored exactly as they were written: the scene's (issue 35)
      for (const auto &[name, stored, given] :
           {std::tuple{"radius", c.radius[id], scene_radius[id]},
            std::tuple{"mass", c.mass[id], scene_mass[id]}})
        if (!(std::abs(stored - given) <= 1e-12 * given))
          throw input_error(path + ": /particles/colloids/" + name + "/value" + at +
                            " (colloid id " + std::to_string(id) + ") = " + number_text(stored) +
                            "; allowed: " + number_text(given) + ", the " + name +
                            " the scene gives this colloid");
    } else { // an older checkpoint: from the scene
      c.radius[id] = scene_radius[id];
      c.mass[id] = scene_mass[id];
    }
  }
  return c;
}

io::SpeciesFields contact_fields(colloids::ContactHistory &all, colloids::ContactHistory &empty,
                                 MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0)
    return io::checkpoint_fields(table(all));
  empty.dim = all.dim;
  empty.resize(0);
  return io::checkpoint_fields(table(empty));
}

colloids::ContactHistory read_contacts(const std::string &path, std::int64_t colloids, int dim,
                                       bool walls, MPI_Comm comm) {
  colloids::ContactHistory block;
  block.dim = dim;
  if (!io::has_species_field(path, "contacts", "owner_id", comm))
    return block;
  io::SpeciesFields s = io::checkpoint_fields(table(block));
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
                          " = " + number_text(all.xi[k][j]) + at + "; allowed: a finite number");
  }
  return all;
}

} // namespace narrows::mpcd
