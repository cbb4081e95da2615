// Moving particles of any structure-of-arrays species between ranks: migrate (ownership
// changed), copy (ghost copies of listed rows for other ranks) and refresh (their values
// again), reverse (sum per-copy quantities back to the owners, in fixed point so the sum is
// exact).
#pragma once

#include "narrows/species/table.hpp"

#include <mpi.h>

#include <cstdint>
#include <vector>

namespace narrows::parallel {

// The arrays of one species, all of the same length. A particle travels as one row of 8-byte
// words (a 4-byte field takes a whole word). Made from the species' table by view().
struct SoaView {
  std::vector<std::vector<double> *> reals;
  std::vector<std::vector<std::uint64_t> *> words;
  std::vector<std::vector<std::uint32_t> *> halfwords;
  // Arrays of the species that are not sent: they stay row-aligned with the others (a row that
  // leaves leaves them too; a row that arrives, or a ghost row, gets their fill).
  std::vector<species::Column> kept;
  std::size_t size() const;
  std::size_t fields() const { return reals.size() + words.size() + halfwords.size(); }
  void resize(std::size_t n) const;
};

// The arrays of a species' table for an exchange: those of the fields with `flag`
// (species::migrates for migrate(), species::ghost for copy()) are sent, the others kept.
SoaView view(const species::Table &table, species::Flag flag);

// Where each ghost copy made by copy() came from, so reverse() can send per-copy sums back.
struct Halo {
  std::vector<int> source_rank;            // per ghost
  std::vector<std::uint64_t> source_index; // per ghost: index in the owner's arrays
  std::size_t size() const { return source_rank.size(); }
};

// Rows to copy to other ranks: row index[j] goes to rank dest[j] (a row may be listed for
// several ranks, never twice for the same one).
struct CopyList {
  std::vector<std::size_t> index;
  std::vector<int> dest;
  void clear() {
    index.clear();
    dest.clear();
  }
};

class Exchange {
public:
  explicit Exchange(MPI_Comm comm);

  // Sends every particle i with dest[i] != this rank to dest[i] and appends what arrives.
  void migrate(const SoaView &species, const std::vector<int> &dest);

  // The same for a list of leavers (ascending indices) and their destinations: O(leavers),
  // the holes are filled from the end of the arrays, so the order of particles changes
  // (nothing in narrows depends on it: cell sums are fixed point).
  void migrate(const SoaView &species, const std::vector<std::size_t> &leavers,
               const std::vector<int> &leaver_dest);

  // Ghost copies of the rows `list` names, appended to the arrays of `species` themselves
  // (rows size() .. size() + ghosts - 1, ordered by source rank, then by the sender's order).
  // Returns where each came from, for refresh() and reverse().
  Halo copy(const SoaView &species, const CopyList &list);

  // Sends the current values of `fields` of the rows of `list` again, to the same ghost rows
  // (from `first_ghost` on, in the order copy() made): the same list and fields on every rank.
  void refresh(const std::vector<std::vector<double> *> &fields, const CopyList &list,
               std::size_t first_ghost);

  // Bytes of rows this rank has sent to other ranks since construction (a figure for benchmarks).
  std::uint64_t bytes_sent() const { return bytes_sent_; }

  // For each ghost of `halo`, `per_ghost[g * k + j]` (k values per ghost) is added to
  // `per_owner[i * k + j]` of its owner particle i. Exact and order-independent.
  void reverse(const Halo &halo, const std::vector<std::int64_t> &per_ghost, int k,
               std::vector<std::int64_t> &per_owner);

  MPI_Comm comm() const { return comm_; }

private:
  MPI_Comm comm_;
  int rank_ = 0, ranks_ = 1;
  // Buffers reused between calls (no allocation in the step loop once warm).
  std::vector<int> send_counts_, recv_counts_, send_words_, recv_words_, send_displs_, recv_displs_;
  std::vector<std::uint64_t> send_, recv_;
  std::vector<MPI_Request> requests_;
  std::vector<std::size_t> leavers_;
  std::vector<int> leaver_dest_;
  std::uint64_t bytes_sent_ = 0;
};

} // namespace narrows::parallel
