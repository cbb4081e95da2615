// Contact history of the spring contacts (Kanehl (thesis) §4.2.3): the tangential spring of each
// contact that lasts, as data of its own. A contact is keyed by the ids of its two colloids,
// (owner, partner) with owner < partner, or (owner, wall) for a colloid touching a wall; it is
// owned by the colloid `owner` and lives on the rank that owns that colloid. It migrates with
// its owner colloid, is gathered in key order for checkpoints and is dropped as soon as the two
// bodies separate. Rows are kept sorted by key. Within a step the ranks that hold the owner as a
// ghost get a copy (ColloidGhosts::copy_contacts), compute the pair with it exactly as the owner
// does (springs.hpp) and drop it at the step's end: only the owner's rank keeps it.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/parallel/exchange.hpp"
#include "narrows/parallel/slabs.hpp"

#include <mpi.h>

#include <array>
#include <cstdint>
#include <vector>

namespace narrows::colloids {

// Partner ids of the walls at y = 0 and y = L_y (no colloid has them: ids are < 2^53).
inline constexpr std::uint64_t wall_low_id = ~std::uint64_t{0};
inline constexpr std::uint64_t wall_high_id = ~std::uint64_t{0} - 1;
inline bool is_wall_id(std::uint64_t id) { return id >= wall_high_id; }

struct ContactHistory {
  int dim = 2;
  std::vector<std::uint64_t> owner, partner;
  std::array<std::vector<double>, 3> xi; // tangential displacement, components k < dim

  std::size_t size() const { return owner.size(); }
  void resize(std::size_t n); // every field of table()
  // Sorts the rows by (owner, partner).
  void sort();
};

// The contact species' fields, one line each (the checkpoint's /particles/contacts/...).
species::Table table(ContactHistory &h);
// The same for reading only.
species::Table table(const ContactHistory &h);

// Sends each contact to the rank that will own its owner colloid (call before the colloids of
// c, which this rank owns, in id order, migrate); collective.
void migrate_contacts(ContactHistory &h, const Colloids &c, const parallel::Slabs &slabs,
                      parallel::Exchange &exchange);

// Keeps the contacts whose owner colloid is one of c's (owned rows in id order).
void keep_contacts_of(ContactHistory &h, const Colloids &c);
// The same for the first `rows` rows of c (in id order; the rest, ghosts, not looked at).
void keep_contacts_of(ContactHistory &h, const Colloids &c, std::size_t rows);
// Row of the colloid with this id among the first `rows` rows of c (in id order), or -1.
long row_of(const Colloids &c, std::size_t rows, std::uint64_t id);

// All contacts of every rank, in key order, on every rank (collective).
ContactHistory gather_contacts(const ContactHistory &mine, MPI_Comm comm);

} // namespace narrows::colloids
