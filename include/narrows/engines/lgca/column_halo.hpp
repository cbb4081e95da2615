// Halo exchange of one column on each side of an x-slab, for any per-site array laid out as
// rows y of `stride` elements with the local columns at [1, nx] and the halos at 0 and nx + 1:
// the lattice bytes, the tagged-particle weights of moment propagation.
#pragma once

#include "narrows/parallel/slabs.hpp"

#include <cstddef>

namespace narrows::lgca {

// Fills column 0 of every row with the left neighbour's last column and column nx + 1 with the
// right neighbour's first (periodic in x; on one rank from the own slab). `base` points at
// element 0 of row 0; elements are `elem_bytes` bytes (copied as bytes).
void exchange_column_halos(const parallel::Slabs &slabs, void *base, std::size_t stride, int rows,
                           int nx, std::size_t elem_bytes, int tag);

// Typed form: T is copied bytewise.
template <class T>
void exchange_column_halos(const parallel::Slabs &slabs, T *base, std::size_t stride, int rows,
                           int nx, int tag) {
  exchange_column_halos(slabs, static_cast<void *>(base), stride, rows, nx, sizeof(T), tag);
}

} // namespace narrows::lgca
