// Column split of the slab decomposition.
#include "narrows/parallel/slabs.hpp"

#include "narrows/core/error.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace narrows::parallel {

Slabs::Slabs(MPI_Comm comm, int columns, int min_columns) : comm_(comm), columns_(columns) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &ranks_);
  const int allowed = columns / std::max(min_columns, 1);
  if (ranks_ > allowed)
    throw input_error("domain.size[0] = " + std::to_string(columns) + " cells gives at most " +
                      std::to_string(allowed) + " slabs of at least " +
                      std::to_string(min_columns) + " cell column(s); found " +
                      std::to_string(ranks_) + " ranks; allowed: 1 to " + std::to_string(allowed));
  first_.resize(ranks_ + 1);
  for (int r = 0; r <= ranks_; ++r)
    first_[r] = static_cast<int>(static_cast<long long>(r) * columns / ranks_);
  fill_owners();
}

Slabs::Slabs(MPI_Comm comm, int columns, const std::vector<int> &first, int min_columns)
    : comm_(comm), columns_(columns) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &ranks_);
  if (static_cast<int>(first.size()) != ranks_ || first.empty() || first[0] != 0)
    throw std::invalid_argument("Slabs: " + std::to_string(first.size()) + " first columns for " +
                                std::to_string(ranks_) + " ranks (one per rank, the first 0)");
  first_ = first;
  first_.push_back(columns);
  for (int r = 0; r < ranks_; ++r)
    if (first_[r + 1] - first_[r] < std::max(min_columns, 1))
      throw std::invalid_argument("Slabs: the slab of rank " + std::to_string(r) + ", columns " +
                                  std::to_string(first_[r]) + " to " +
                                  std::to_string(first_[r + 1]) + ", is narrower than " +
                                  std::to_string(std::max(min_columns, 1)) + " column(s)");
  fill_owners();
}

void Slabs::fill_owners() {
  owner_.resize(columns_);
  for (int r = 0; r < ranks_; ++r)
    for (int c = first_[r]; c < first_[r + 1]; ++c)
      owner_[c] = r;
}

} // namespace narrows::parallel
