// Slab decomposition along x (the flow axis) by columns of the shifted collision grid: rank r
// owns global cell columns [first[r], first[r+1]), i.e. x in [first[r] + s_x, first[r+1] + s_x)
// for the grid shift s_x of the step. Collisions are therefore entirely rank-local.
#pragma once

#include <mpi.h>

#include <vector>

namespace narrows::parallel {

class Slabs {
public:
  // Balanced split of `columns` over the ranks of `comm`; every slab at least `min_columns`
  // wide, else narrows::Error(bad_input) saying how many ranks the box allows.
  Slabs(MPI_Comm comm, int columns, int min_columns = 1);
  // Given boundaries: rank r owns [first[r], first[r + 1]) (first[ranks] = columns); `first`
  // holds one entry per rank, starting at 0, each slab at least `min_columns` wide, else
  // std::invalid_argument (a caller's error, not the scene's).
  Slabs(MPI_Comm comm, int columns, const std::vector<int> &first, int min_columns = 1);

  MPI_Comm comm() const { return comm_; }
  int rank() const { return rank_; }
  int ranks() const { return ranks_; }
  int columns() const { return columns_; }
  int first_column() const { return first_[rank_]; }
  int local_columns() const { return first_[rank_ + 1] - first_[rank_]; }
  int first_column_of(int r) const { return first_[r]; }
  // The first column of every rank (ranks entries), as the constructor from boundaries takes.
  std::vector<int> first_columns() const { return {first_.begin(), first_.end() - 1}; }
  // Owner of a global column in [0, columns).
  int owner(int column) const { return owner_[column]; }

private:
  void fill_owners();

  MPI_Comm comm_;
  int rank_ = 0, ranks_ = 1, columns_ = 1;
  std::vector<int> first_; // ranks + 1 entries
  std::vector<int> owner_; // per column
};

} // namespace narrows::parallel
