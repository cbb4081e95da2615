// Counting sort of the fluid arrays by cell.
#include "narrows/engines/mpcd/kernels/cell_sort.hpp"

#include <type_traits>
#include <utility>

namespace narrows::mpcd {

namespace {

// a[i] moves to dest[i]; the old array ends up in tmp for reuse.
template <class T>
void scatter(std::vector<T> &a, const std::vector<std::uint32_t> &dest, std::vector<T> &tmp) {
  const std::size_t n = a.size();
  tmp.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    tmp[dest[i]] = a[i];
  std::swap(a, tmp);
}

} // namespace

void sort_by_cell(Fluid &fluid, const CellGrid &grid, SortScratch &s) {
  const std::size_t nc = grid.size(), n = fluid.size();
  // Destination of each particle: start of its cell plus its rank among earlier particles of
  // the same cell (stable).
  s.start.resize(nc);
  std::uint32_t offset = 0;
  for (std::size_t c = 0; c < nc; ++c) {
    s.start[c] = offset;
    offset += grid.sums[c].n;
  }
  s.dest.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    s.dest[i] = s.start[fluid.cell[i]]++;
  // Every field of the fluid (its table), each array through the spare array of its type.
  const species::Table fields = table(fluid);
  for (const species::Field &f : fields.fields())
    for (const species::Column &c : f.columns())
      std::visit(
          [&](auto *a) {
            using T = typename std::remove_pointer_t<decltype(a)>::value_type;
            if constexpr (std::is_same_v<T, double>)
              scatter(*a, s.dest, s.real);
            else if constexpr (std::is_same_v<T, std::uint64_t>)
              scatter(*a, s.dest, s.ids);
            else
              scatter(*a, s.dest, s.cells);
          },
          c.array);
}

} // namespace narrows::mpcd
