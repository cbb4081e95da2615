// Colloids owned by slabs: keeping, migrating and gathering them.
#include "narrows/colloids/ownership.hpp"

#include <algorithm>
#include <numeric>

namespace narrows::colloids {

namespace {

// Reorders the rows of c by id (a handful per rank).
void sort_by_id(Colloids &c) {
  const std::size_t n = c.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return c.id[a] < c.id[b]; });
  if (!std::is_sorted(order.begin(), order.end()))
    table(c).permute(order);
}

} // namespace

void keep_owned(Colloids &c, const parallel::Slabs &slabs) {
  std::vector<bool> keep(c.size());
  for (std::size_t a = 0; a < c.size(); ++a)
    keep[a] = owner_of(c, a, slabs) == slabs.rank();
  table(c).keep_rows(keep);
  sort_by_id(c);
}

void migrate_colloids(Colloids &c, const parallel::Slabs &slabs, parallel::Exchange &exchange) {
  std::vector<int> dest(c.size());
  for (std::size_t a = 0; a < c.size(); ++a)
    dest[a] = owner_of(c, a, slabs);
  exchange.migrate(parallel::view(table(c), species::migrates), dest);
  sort_by_id(c);
}

Colloids gather_colloids(const Colloids &owned, MPI_Comm comm) {
  Colloids out;
  out.dim = owned.dim;
  out.extra = owned.extra.same_fields();
  species::Table all = table(out);
  species::gather(table(owned), all, comm);
  sort_by_id(out);
  return out;
}

} // namespace narrows::colloids
