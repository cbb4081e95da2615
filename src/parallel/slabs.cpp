// Column split of the slab decomposition.
#include "narrows/parallel/slabs.hpp"

#include "narrows/core/error.hpp"

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
  owner_.resize(columns);
  for (int r = 0; r < ranks_; ++r)
    for (int c = first_[r]; c < first_[r + 1]; ++c)
      owner_[c] = r;
}

} // namespace narrows::parallel
