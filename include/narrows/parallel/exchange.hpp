// Moving particles of any structure-of-arrays species between ranks: migrate (ownership
// changed), copy (ghost copies of listed rows for other ranks) and refresh (their values
// again), reverse (sum per-copy quantities back to the owners, in fixed point so the sum is
// exact).
#pragma once

#include "narrows/parallel/slabs.hpp"
#include "narrows/species/table.hpp"

#include <string>

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

// Which ranks an exchange may send rows to: the neighbours set by set_neighbours(), or (a
// checkpoint's rows, which may belong anywhere) any rank.
enum class Reach { neighbours, anywhere };

// Each exchange is one round of point-to-point messages ending in one MPI_Waitall.
// - copy() and migrate() to the neighbours: one message to each neighbour (empty if no rows go
//   there); the receiver learns the row count from the message itself (MPI_Mprobe).
// - refresh() and reverse(): the counts are those of the last copy(), known on both sides;
//   messages only between ranks that have rows for each other.
// - without neighbours, or with Reach::anywhere: the row counts by MPI_Alltoall first.
// No collective over the communicator is needed in a step when the neighbours are set.
class Exchange {
public:
  explicit Exchange(MPI_Comm comm);

  // The ranks this rank exchanges rows with from now on: those whose slabs come within
  // `columns` (on the ring of cell columns) of this rank's slab, found from `slabs` the same
  // way on every rank (the relation is symmetric). A row for a rank beyond stops the run
  // (invariant error) naming `what` (e.g. "fluid particle", "colloid ghost"). The same
  // `columns` on every rank.
  void set_neighbours(const Slabs &slabs, double columns, std::string what);
  // Back to any rank (counts by MPI_Alltoall): for rows that may go anywhere (slabs moved).
  void clear_neighbours() {
    neighbours_.clear();
    neighbours_set_ = false;
  }
  const std::vector<int> &neighbours() const { return neighbours_; }
  bool has_neighbours() const { return neighbours_set_; }

  // Sends every particle i with dest[i] != this rank to dest[i] and appends what arrives.
  void migrate(const SoaView &species, const std::vector<int> &dest,
               Reach reach = Reach::neighbours);

  // The same for a list of leavers (ascending indices) and their destinations: O(leavers),
  // the holes are filled from the end of the arrays, so the order of particles changes
  // (nothing in narrows depends on it: cell sums are fixed point).
  void migrate(const SoaView &species, const std::vector<std::size_t> &leavers,
               const std::vector<int> &leaver_dest, Reach reach = Reach::neighbours);

  // Ghost copies of the rows `list` names, appended to the arrays of `species` themselves
  // (rows size() .. size() + ghosts - 1, ordered by source rank, then by the sender's order).
  // Returns where each came from, for refresh() and reverse().
  Halo copy(const SoaView &species, const CopyList &list);

  // Sends the current values of `fields` of the rows of `list` again, to the same ghost rows
  // (from `first_ghost` on, in the order copy() made): the same list and fields on every rank,
  // the list of this Exchange's last copy().
  void refresh(const std::vector<std::vector<double> *> &fields, const CopyList &list,
               std::size_t first_ghost);

  // Bytes of rows this rank has sent to other ranks since construction (a figure for benchmarks).
  std::uint64_t bytes_sent() const { return bytes_sent_; }

  // For each ghost of `halo` (this Exchange's last copy()), `per_ghost[g * k + j]` (k values
  // per ghost) is added to `per_owner[i * k + j]` of its owner particle i. Exact and
  // order-independent.
  void reverse(const Halo &halo, const std::vector<std::int64_t> &per_ghost, int k,
               std::vector<std::int64_t> &per_owner);

  MPI_Comm comm() const { return comm_; }

  // After the caller dropped copies of the last copy() on both sides (the same ones, decided
  // alike): rows per rank still copied to (`to`) and from (`from`) each rank, for refresh()
  // and reverse().
  void keep_copies(const std::vector<int> &to, const std::vector<int> &from) {
    copied_to_ = to;
    copied_from_ = from;
  }

private:
  // Sends send_ (rows of `row` words, send_counts_ rows per rank, in rank order) and receives
  // into recv_ (in the order of the source ranks; recv_counts_ rows per rank). With
  // counts_known, recv_counts_ is already right; else it comes from the messages (neighbours)
  // or by MPI_Alltoall (anywhere).
  void exchange_rows(std::size_t row, bool counts_known, Reach reach);
  // Throws if a row goes to a rank that is not a neighbour.
  void check_destinations() const;

  MPI_Comm comm_;
  int rank_ = 0, ranks_ = 1;
  std::vector<int> neighbours_; // ascending, without this rank
  std::vector<std::uint8_t> is_neighbour_;
  bool neighbours_set_ = false;
  double reach_columns_ = 0.0;
  std::string what_;
  std::vector<int> copied_to_, copied_from_; // rows per rank of the last copy()
  std::vector<MPI_Message> messages_;
  // Buffers reused between calls (no allocation in the step loop once warm).
  std::vector<int> send_counts_, recv_counts_, send_words_, recv_words_, send_displs_, recv_displs_;
  std::vector<std::uint64_t> send_, recv_;
  std::vector<MPI_Request> requests_;
  std::vector<std::size_t> leavers_;
  std::vector<int> leaver_dest_;
  std::uint64_t bytes_sent_ = 0;
};

} // namespace narrows::parallel
