// Contact history: lookup, order, migration with the owner colloid, gathering.
#include "narrows/colloids/contact_history.hpp"

#include "narrows/colloids/ownership.hpp"

#include <algorithm>
#include <numeric>

namespace narrows::colloids {

species::Table table(ContactHistory &h) {
  using namespace species;
  // Only the rank of the owner colloid keeps a contact (ghost copies live for one step). Walls
  // are partners wall_low_id and wall_high_id.
  constexpr unsigned held = migrates | checkpoint;
  Table t("contacts", h.dim);
  t.scalar("owner_id", h.owner, held)
      .scalar("partner_id", h.partner, held)
      .vector("tangential_displacement", h.xi, held);
  return t;
}

species::Table table(const ContactHistory &h) {
  species::Table t = table(const_cast<ContactHistory &>(h));
  t.read_only();
  return t;
}

void ContactHistory::resize(std::size_t n) { table(*this).resize(n); }

void ContactHistory::sort() {
  const std::size_t n = size();
  const auto less = [&](std::size_t a, std::size_t b) {
    return owner[a] < owner[b] || (owner[a] == owner[b] && partner[a] < partner[b]);
  };
  bool sorted = true; // (the usual case, every step: checked without allocating)
  for (std::size_t j = 1; j < n && sorted; ++j)
    sorted = !less(j, j - 1);
  if (sorted)
    return;
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), less);
  table(*this).permute(order);
}

long row_of(const Colloids &c, std::size_t rows, std::uint64_t id) {
  const auto end = c.id.begin() + static_cast<std::ptrdiff_t>(rows);
  const auto it = std::lower_bound(c.id.begin(), end, id);
  return it != end && *it == id ? static_cast<long>(it - c.id.begin()) : -1;
}

namespace {

// Row of the colloid with this id among c's rows (in id order), or -1.
long row_of(const Colloids &c, std::uint64_t id) { return row_of(c, c.size(), id); }

} // namespace

void migrate_contacts(ContactHistory &h, const Colloids &c, const parallel::Slabs &slabs,
                      parallel::Exchange &exchange) {
  std::vector<int> dest(h.size());
  for (std::size_t j = 0; j < h.size(); ++j) {
    const long a = row_of(c, h.owner[j]);
    dest[j] = a < 0 ? slabs.rank() : owner_of(c, static_cast<std::size_t>(a), slabs);
  }
  exchange.migrate(parallel::view(table(h), species::migrates), dest);
  h.sort();
}

void keep_contacts_of(ContactHistory &h, const Colloids &c) { keep_contacts_of(h, c, c.size()); }

void keep_contacts_of(ContactHistory &h, const Colloids &c, std::size_t rows) {
  std::vector<bool> keep(h.size());
  for (std::size_t j = 0; j < h.size(); ++j)
    keep[j] = row_of(c, rows, h.owner[j]) >= 0;
  table(h).keep_rows(keep);
  h.sort();
}

ContactHistory gather_contacts(const ContactHistory &mine, MPI_Comm comm) {
  ContactHistory out;
  out.dim = mine.dim;
  species::Table all = table(out);
  species::gather(table(mine), all, comm);
  out.sort();
  return out;
}

} // namespace narrows::colloids
