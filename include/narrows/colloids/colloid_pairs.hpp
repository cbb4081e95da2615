// Candidate pairs of colloids from a linked cell list over the whole box (cells at least the
// largest interaction range wide): the 48-24 force term and the spring contacts both ask it.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/colloids/forces.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"

#include <cstdint>
#include <vector>

namespace narrows::colloids {

// Fills `cl` (sized) with every row of c and calls visit(a, partners) for each row a, with the
// rows b > a in the cells within one of a's own: along an axis of fewer than three cells all of
// its cells, so no cell is visited twice and no pair listed twice; along a wall axis the range
// stops at the walls. `cell_of` and `partners` are scratch.
template <int D, bool WallsY, class Visit>
void for_each_colloid_pair(CellList &cl, std::vector<int> &cell_of,
                           std::vector<std::uint32_t> &partners, const Colloids &c, Visit &&visit) {
  const std::size_t nc = c.size();
  const auto &cells = cl.cells;
  cl.clear();
  cl.next.resize(nc);
  cell_of.resize(nc * D);
  for (std::size_t a = 0; a < nc; ++a) {
    std::size_t cell = 0;
    for (int k = D - 1; k >= 0; --k) {
      const int n = cells[k];
      const int ck = mpcd::clamped_cell(c.x[k][a], cl.inv_cell[k], n, "colloid", c.id[a], k);
      cell_of[a * D + k] = ck;
      cell = cell * static_cast<std::size_t>(n) + static_cast<std::size_t>(ck);
    }
    cl.push(cell, static_cast<std::int32_t>(a));
  }
  for (std::size_t a = 0; a < nc; ++a) {
    int lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, home[3] = {0, 0, 0};
    for (int k = 0; k < D; ++k) {
      const int n = cells[k];
      home[k] = cell_of[a * D + k];
      if (n < 3) {
        lo[k] = -home[k], hi[k] = n - 1 - home[k];
      } else if (WallsY && k == 1) {
        lo[k] = home[k] > 0 ? -1 : 0, hi[k] = home[k] < n - 1 ? 1 : 0;
      } else {
        lo[k] = -1, hi[k] = 1;
      }
    }
    partners.clear();
    int off[3] = {0, 0, 0};
    for (off[2] = lo[2]; off[2] <= hi[2]; ++off[2])
      for (off[1] = lo[1]; off[1] <= hi[1]; ++off[1])
        for (off[0] = lo[0]; off[0] <= hi[0]; ++off[0]) {
          std::size_t cell = 0;
          for (int k = D - 1; k >= 0; --k) {
            const int n = cells[k];
            int ck = home[k] + off[k];
            ck = ck < 0 ? ck + n : (ck >= n ? ck - n : ck);
            cell = cell * static_cast<std::size_t>(n) + static_cast<std::size_t>(ck);
          }
          for (std::int32_t b = cl.head[cell]; b >= 0; b = cl.next[b])
            if (static_cast<std::size_t>(b) > a)
              partners.push_back(static_cast<std::uint32_t>(b));
        }
    visit(a, partners);
  }
}

} // namespace narrows::colloids
