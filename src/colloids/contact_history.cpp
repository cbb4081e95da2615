// Contact history: lookup, order, migration with the owner colloid, gathering.
#include "narrows/colloids/contact_history.hpp"

#include "narrows/colloids/ownership.hpp"

#include <algorithm>
#include <cstring>
#include <numeric>

namespace narrows::colloids {

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
  const ContactHistory copy = *this;
  for (std::size_t j = 0; j < n; ++j) {
    owner[j] = copy.owner[order[j]];
    partner[j] = copy.partner[order[j]];
    for (int k = 0; k < dim; ++k)
      xi[k][j] = copy.xi[k][order[j]];
  }
}

parallel::SoaView contact_view(ContactHistory &h) {
  parallel::SoaView v;
  for (int k = 0; k < h.dim; ++k)
    v.reals.push_back(&h.xi[k]);
  v.words.push_back(&h.owner);
  v.words.push_back(&h.partner);
  return v;
}

namespace {

// Row of the colloid with this id among c's rows (in id order), or -1.
long row_of(const Colloids &c, std::uint64_t id) {
  const auto it = std::lower_bound(c.id.begin(), c.id.end(), id);
  return it != c.id.end() && *it == id ? static_cast<long>(it - c.id.begin()) : -1;
}

} // namespace

void migrate_contacts(ContactHistory &h, const Colloids &c, const parallel::Slabs &slabs,
                      parallel::Exchange &exchange) {
  std::vector<int> dest(h.size());
  for (std::size_t j = 0; j < h.size(); ++j) {
    const long a = row_of(c, h.owner[j]);
    dest[j] = a < 0 ? slabs.rank() : owner_of(c, static_cast<std::size_t>(a), slabs);
  }
  exchange.migrate(contact_view(h), dest);
  h.sort();
}

void keep_contacts_of(ContactHistory &h, const Colloids &c) {
  std::size_t n = 0;
  for (std::size_t j = 0; j < h.size(); ++j) {
    if (row_of(c, h.owner[j]) < 0)
      continue;
    h.owner[n] = h.owner[j];
    h.partner[n] = h.partner[j];
    for (int k = 0; k < h.dim; ++k)
      h.xi[k][n] = h.xi[k][j];
    ++n;
  }
  h.resize(n);
  h.sort();
}

ContactHistory gather_contacts(const ContactHistory &mine, MPI_Comm comm) {
  // Rows of 2 + dim words: owner, partner, the bits of xi.
  const int W = 2 + mine.dim;
  const int n = static_cast<int>(mine.size());
  std::vector<std::uint64_t> rows(static_cast<std::size_t>(n) * W);
  for (int j = 0; j < n; ++j) {
    std::uint64_t *r = &rows[static_cast<std::size_t>(j) * W];
    r[0] = mine.owner[j];
    r[1] = mine.partner[j];
    for (int k = 0; k < mine.dim; ++k)
      std::memcpy(&r[2 + k], &mine.xi[k][j], sizeof(double));
  }
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const int count = n * W;
  std::vector<int> counts(ranks), displs(ranks, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int r = 1; r < ranks; ++r)
    displs[r] = displs[r - 1] + counts[r - 1];
  std::vector<std::uint64_t> all(static_cast<std::size_t>(displs[ranks - 1] + counts[ranks - 1]));
  MPI_Allgatherv(rows.data(), count, MPI_UINT64_T, all.data(), counts.data(), displs.data(),
                 MPI_UINT64_T, comm);
  ContactHistory out;
  out.dim = mine.dim;
  out.resize(all.size() / static_cast<std::size_t>(W));
  for (std::size_t j = 0; j < out.size(); ++j) {
    const std::uint64_t *r = &all[j * W];
    out.owner[j] = r[0];
    out.partner[j] = r[1];
    for (int k = 0; k < out.dim; ++k)
      std::memcpy(&out.xi[k][j], &r[2 + k], sizeof(double));
  }
  out.sort();
  return out;
}

} // namespace narrows::colloids
