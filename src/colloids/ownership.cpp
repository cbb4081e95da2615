// Colloids owned by slabs: keeping, migrating and gathering them.
#include "narrows/colloids/ownership.hpp"

#include <algorithm>
#include <numeric>

namespace narrows::colloids {

parallel::SoaView colloid_view(Colloids &c) {
  parallel::SoaView v;
  for (int k = 0; k < c.dim; ++k)
    v.reals.push_back(&c.x[k]);
  for (int k = 0; k < c.dim; ++k)
    v.reals.push_back(&c.v[k]);
  for (int k = 0; k < 3; ++k)
    v.reals.push_back(&c.omega[k]);
  for (int k = 0; k < 4; ++k)
    v.reals.push_back(&c.q[k]);
  v.reals.push_back(&c.radius);
  v.reals.push_back(&c.mass);
  v.words.push_back(&c.id);
  return v;
}

namespace {

// Reorders the rows of c by id (a handful per rank: a permutation through a copy).
void sort_by_id(Colloids &c) {
  const std::size_t n = c.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return c.id[a] < c.id[b]; });
  if (std::is_sorted(order.begin(), order.end()))
    return;
  Colloids copy = c;
  const parallel::SoaView from = colloid_view(copy), to = colloid_view(c);
  for (std::size_t f = 0; f < from.reals.size(); ++f)
    for (std::size_t j = 0; j < n; ++j)
      (*to.reals[f])[j] = (*from.reals[f])[order[j]];
  for (std::size_t j = 0; j < n; ++j)
    c.id[j] = copy.id[order[j]];
}

// Keeps the rows with keep[a] (in order).
void keep_rows(Colloids &c, const std::vector<bool> &keep) {
  const parallel::SoaView view = colloid_view(c);
  std::size_t n = 0;
  for (std::size_t a = 0; a < c.size(); ++a) {
    if (!keep[a])
      continue;
    for (auto *r : view.reals)
      (*r)[n] = (*r)[a];
    c.id[n] = c.id[a];
    ++n;
  }
  view.resize(n);
}

} // namespace

void keep_owned(Colloids &c, const parallel::Slabs &slabs) {
  std::vector<bool> keep(c.size());
  for (std::size_t a = 0; a < c.size(); ++a)
    keep[a] = owner_of(c, a, slabs) == slabs.rank();
  keep_rows(c, keep);
  sort_by_id(c);
}

void migrate_colloids(Colloids &c, const parallel::Slabs &slabs, parallel::Exchange &exchange) {
  std::vector<int> dest(c.size());
  for (std::size_t a = 0; a < c.size(); ++a)
    dest[a] = owner_of(c, a, slabs);
  exchange.migrate(colloid_view(c), dest);
  sort_by_id(c);
}

Colloids gather_colloids(const Colloids &owned, MPI_Comm comm) {
  Colloids mine = owned; // colloid_view needs mutable arrays
  const parallel::SoaView view = colloid_view(mine);
  const std::size_t F = view.fields(), n = mine.size();
  std::vector<double> rows(n * F);
  for (std::size_t a = 0; a < n; ++a) {
    std::size_t f = 0;
    for (auto *r : view.reals)
      rows[a * F + f++] = (*r)[a];
    rows[a * F + f] = static_cast<double>(mine.id[a]); // ids < 2^53
  }
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const int count = static_cast<int>(n * F);
  std::vector<int> counts(ranks), displs(ranks, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int r = 1; r < ranks; ++r)
    displs[r] = displs[r - 1] + counts[r - 1];
  std::vector<double> all(static_cast<std::size_t>(displs[ranks - 1] + counts[ranks - 1]));
  MPI_Allgatherv(rows.data(), count, MPI_DOUBLE, all.data(), counts.data(), displs.data(),
                 MPI_DOUBLE, comm);
  Colloids out;
  out.dim = owned.dim;
  out.resize(all.size() / F);
  const parallel::SoaView to = colloid_view(out);
  for (std::size_t a = 0; a < out.size(); ++a) {
    std::size_t f = 0;
    for (auto *r : to.reals)
      (*r)[a] = all[a * F + f++];
    out.id[a] = static_cast<std::uint64_t>(all[a * F + f]);
  }
  sort_by_id(out);
  return out;
}

} // namespace narrows::colloids
