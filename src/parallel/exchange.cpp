// Migrate, copy, refresh and reverse for any structure-of-arrays species: the rows by
// point-to-point messages, their counts in the messages themselves (to the neighbours), known
// from the last copy (refresh, reverse) or by MPI_Alltoall (rows that may go anywhere).
#include "narrows/parallel/exchange.hpp"

#include "narrows/core/error.hpp"
#include "narrows/parallel/message_clock.hpp"

#include <algorithm>
#include <bit>
#include <limits>
#include <string>

namespace narrows::parallel {

std::size_t SoaView::size() const {
  if (!reals.empty())
    return reals[0]->size();
  if (!words.empty())
    return words[0]->size();
  if (!halfwords.empty())
    return halfwords[0]->size();
  return kept.empty() ? 0 : kept[0].size();
}

void SoaView::resize(std::size_t n) const {
  for (auto *a : reals)
    a->resize(n);
  for (auto *a : words)
    a->resize(n);
  for (auto *a : halfwords)
    a->resize(n);
  for (const auto &c : kept)
    c.resize(n);
}

SoaView view(const species::Table &table, species::Flag flag) {
  SoaView v;
  for (const species::Field &f : table.fields())
    for (const species::Column &c : f.columns()) {
      if (!f.has(flag)) {
        v.kept.push_back(c);
        continue;
      }
      std::visit(
          [&](auto *a) {
            using T = typename std::remove_pointer_t<decltype(a)>::value_type;
            if constexpr (std::is_same_v<T, double>)
              v.reals.push_back(a);
            else if constexpr (std::is_same_v<T, std::uint64_t>)
              v.words.push_back(a);
            else
              v.halfwords.push_back(a);
          },
          c.array);
    }
  return v;
}

Exchange::Exchange(MPI_Comm comm) : comm_(comm) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &ranks_);
}

namespace {

// The tag of the rows' messages (an exchange completes before the next starts, so messages of
// two exchanges between the same ranks are never matched with each other).
constexpr int rows_tag = 0x6e72;

} // namespace

void Exchange::set_neighbours(const Slabs &slabs, double columns, std::string what) {
  what_ = std::move(what);
  reach_columns_ = columns;
  neighbours_.clear();
  is_neighbour_.assign(ranks_, 0);
  const long long C = slabs.columns();
  const long long lo = slabs.first_column(), hi = lo + slabs.local_columns(); // [lo, hi)
  for (int r = 0; r < ranks_; ++r) {
    if (r == rank_)
      continue;
    const long long a = slabs.first_column_of(r);
    const long long b = r + 1 < ranks_ ? slabs.first_column_of(r + 1) : C;
    // Whole columns between the two slabs, going right from this one and going left (the
    // ring of columns: the box is periodic along x).
    const long long right = ((a - hi) % C + C) % C, left = ((lo - b) % C + C) % C;
    if (static_cast<double>(std::min(right, left)) <= columns) {
      neighbours_.push_back(r);
      is_neighbour_[r] = 1;
    }
  }
  neighbours_set_ = true;
}

void Exchange::check_destinations() const {
  for (int r = 0; r < ranks_; ++r)
    if (r != rank_ && send_counts_[r] > 0 && !is_neighbour_[r]) {
      std::string ranks;
      for (const int n : neighbours_)
        ranks += (ranks.empty() ? "" : ", ") + std::to_string(n);
      throw invariant_error(
          std::to_string(send_counts_[r]) + " " + what_ + " row(s) of rank " +
          std::to_string(rank_) + " belong to rank " + std::to_string(r) +
          ", beyond the ranks whose slabs come within " + std::to_string(reach_columns_) +
          " columns of this one (" + (ranks.empty() ? std::string("none") : ranks) +
          "): something moved further within one step than the exchange allows (allowed: "
          "fewer ranks, or a smaller fluid.dt)");
    }
}

// Rows of `row` words to other ranks, as point-to-point messages between the ranks that have
// rows for each other (an MPI_Alltoallv may pay a latency for each of the P - 1 ranks even when
// the message is empty: the cost of a halo exchange would grow with the number of ranks).
// Words (not rows) per rank and their offsets in send_words_, recv_words_, send_displs_,
// recv_displs_ (no allocation per exchange once warm).
void Exchange::exchange_rows(std::size_t row, bool counts_known, Reach reach) {
  const MessageTimer timed;
  const bool to_neighbours = neighbours_set_ && reach == Reach::neighbours;
  if (!counts_known) {
    recv_counts_.assign(ranks_, 0);
    if (to_neighbours)
      check_destinations();
    else
      MPI_Alltoall(send_counts_.data(), 1, MPI_INT, recv_counts_.data(), 1, MPI_INT, comm_);
  }
  send_words_.resize(ranks_);
  recv_words_.resize(ranks_);
  send_displs_.assign(ranks_, 0);
  recv_displs_.assign(ranks_, 0);
  requests_.clear();
  long long stotal = 0;
  for (int r = 0; r < ranks_; ++r) {
    send_words_[r] = static_cast<int>(send_counts_[r] * row);
    send_displs_[r] = static_cast<int>(stotal);
    stotal += send_words_[r];
  }
  if (stotal > std::numeric_limits<int>::max())
    throw Error(ExitCode::other, "exchange of more than 2^31 words in one step");
  bytes_sent_ += 8 * static_cast<std::uint64_t>(stotal - send_words_[rank_]);
  // Sends first (non-blocking): to each neighbour one message, empty or not, when the
  // receiver learns the count from it; else only where there are rows.
  const bool counts_in_messages = to_neighbours && !counts_known;
  for (int r = 0; r < ranks_; ++r)
    if (r != rank_ && (send_words_[r] > 0 || (counts_in_messages && is_neighbour_[r]))) {
      requests_.emplace_back();
      MPI_Isend(send_.data() + send_displs_[r], send_words_[r], MPI_UINT64_T, r, rows_tag, comm_,
                &requests_.back());
    }
  if (counts_in_messages) { // the counts: the sizes of the neighbours' messages
    messages_.resize(neighbours_.size());
    for (std::size_t j = 0; j < neighbours_.size(); ++j) {
      MPI_Status status;
      MPI_Mprobe(neighbours_[j], rows_tag, comm_, &messages_[j], &status);
      int words = 0;
      MPI_Get_count(&status, MPI_UINT64_T, &words);
      recv_counts_[neighbours_[j]] = static_cast<int>(words / static_cast<int>(row ? row : 1));
    }
  }
  recv_counts_[rank_] = send_counts_[rank_];
  long long rtotal = 0;
  for (int r = 0; r < ranks_; ++r) {
    recv_words_[r] = static_cast<int>(recv_counts_[r] * row);
    recv_displs_[r] = static_cast<int>(rtotal);
    rtotal += recv_words_[r];
  }
  if (rtotal > std::numeric_limits<int>::max())
    throw Error(ExitCode::other, "exchange of more than 2^31 words in one step");
  recv_.resize(static_cast<std::size_t>(rtotal));
  if (counts_in_messages) {
    for (std::size_t j = 0; j < neighbours_.size(); ++j) {
      const int r = neighbours_[j];
      requests_.emplace_back();
      MPI_Imrecv(recv_.data() + recv_displs_[r], recv_words_[r], MPI_UINT64_T, &messages_[j],
                 &requests_.back());
    }
  } else {
    for (int r = 0; r < ranks_; ++r)
      if (r != rank_ && recv_words_[r] > 0) {
        requests_.emplace_back();
        MPI_Irecv(recv_.data() + recv_displs_[r], recv_words_[r], MPI_UINT64_T, r, rows_tag, comm_,
                  &requests_.back());
      }
  }
  std::copy(send_.begin() + send_displs_[rank_],
            send_.begin() + send_displs_[rank_] + send_words_[rank_],
            recv_.begin() + recv_displs_[rank_]); // (the rows a rank keeps)
  MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
}

namespace {

// Rows per destination rank (into counts) and where each rank's rows start in the send
// buffer (returned); dest_of(j) is the destination of row j of `rows`.
template <class DestOf>
std::vector<std::size_t> plan_rows(int ranks, std::size_t rows, DestOf dest_of,
                                   std::vector<int> &counts, std::size_t &total) {
  counts.assign(ranks, 0);
  for (std::size_t j = 0; j < rows; ++j)
    ++counts[dest_of(j)];
  std::vector<std::size_t> next(ranks, 0);
  total = 0;
  for (int r = 0; r < ranks; ++r) {
    next[r] = total;
    total += counts[r];
  }
  return next;
}

} // namespace

void Exchange::migrate(const SoaView &s, const std::vector<int> &dest, Reach reach) {
  leavers_.clear();
  leaver_dest_.clear();
  for (std::size_t i = 0; i < s.size(); ++i)
    if (dest[i] != rank_) {
      leavers_.push_back(i);
      leaver_dest_.push_back(dest[i]);
    }
  // Copies: the overload below may be handed these very members by other callers.
  const std::vector<std::size_t> leavers = leavers_;
  const std::vector<int> to = leaver_dest_;
  migrate(s, leavers, to, reach);
}

void Exchange::migrate(const SoaView &s, const std::vector<std::size_t> &leavers,
                       const std::vector<int> &to, Reach reach) {
  const std::size_t F = s.fields();
  std::size_t total = 0;
  auto next = plan_rows(
      ranks_, to.size(), [&](std::size_t j) { return to[j]; }, send_counts_, total);
  send_.resize(total * F);
  for (std::size_t j = 0; j < leavers.size(); ++j) {
    const std::size_t i = leavers[j];
    std::uint64_t *row = &send_[next[to[j]]++ * F];
    std::size_t f = 0;
    for (auto *a : s.reals)
      row[f++] = std::bit_cast<std::uint64_t>((*a)[i]);
    for (auto *a : s.words)
      row[f++] = (*a)[i];
    for (auto *a : s.halfwords)
      row[f++] = (*a)[i];
  }
  // Remove the leavers from the largest index down, filling each hole with the current last
  // particle: every leaver above the hole is already gone, so that one stays.
  std::size_t n = s.size();
  for (auto it = leavers.rbegin(); it != leavers.rend(); ++it) {
    --n;
    if (*it != n) {
      for (auto *a : s.reals)
        (*a)[*it] = (*a)[n];
      for (auto *a : s.words)
        (*a)[*it] = (*a)[n];
      for (auto *a : s.halfwords)
        (*a)[*it] = (*a)[n];
      for (const auto &c : s.kept)
        c.move_row(*it, n);
    }
  }
  exchange_rows(F, false, reach);
  const std::size_t arrived = recv_.size() / (F ? F : 1);
  for (const auto &c : s.kept) // (arrivals get the fill, not what the last rows held)
    c.resize(n);
  s.resize(n + arrived);
  for (std::size_t j = 0; j < arrived; ++j) {
    const std::uint64_t *row = &recv_[j * F];
    std::size_t f = 0;
    for (auto *a : s.reals)
      (*a)[n + j] = std::bit_cast<double>(row[f++]);
    for (auto *a : s.words)
      (*a)[n + j] = row[f++];
    for (auto *a : s.halfwords)
      (*a)[n + j] = static_cast<std::uint32_t>(row[f++]);
  }
}

Halo Exchange::copy(const SoaView &s, const CopyList &list) {
  if (!s.halfwords.empty())
    throw Error(ExitCode::other, "copies of 4-byte fields are not supported");
  const std::size_t F = s.fields(), row_len = F + 1; // + source index
  std::size_t total = 0;
  auto next = plan_rows(
      ranks_, list.dest.size(), [&](std::size_t j) { return list.dest[j]; }, send_counts_, total);
  send_.resize(total * row_len);
  for (std::size_t j = 0; j < list.index.size(); ++j) {
    const std::size_t i = list.index[j];
    std::uint64_t *row = &send_[next[list.dest[j]]++ * row_len];
    std::size_t f = 0;
    for (auto *a : s.reals)
      row[f++] = std::bit_cast<std::uint64_t>((*a)[i]);
    for (auto *a : s.words)
      row[f++] = (*a)[i];
    row[f] = i;
  }
  exchange_rows(row_len, false, Reach::neighbours);
  copied_to_ = send_counts_;
  copied_from_ = recv_counts_;
  const std::size_t n = s.size(), g = recv_.size() / row_len;
  s.resize(n + g);
  Halo h;
  h.source_rank.resize(g);
  h.source_index.resize(g);
  std::size_t j = 0;
  for (int r = 0; r < ranks_; ++r)
    for (int q = 0; q < recv_counts_[r]; ++q, ++j) {
      const std::uint64_t *row = &recv_[j * row_len];
      std::size_t f = 0;
      for (auto *a : s.reals)
        (*a)[n + j] = std::bit_cast<double>(row[f++]);
      for (auto *a : s.words)
        (*a)[n + j] = row[f++];
      h.source_rank[j] = r;
      h.source_index[j] = row[f];
    }
  return h;
}

void Exchange::refresh(const std::vector<std::vector<double> *> &fields, const CopyList &list,
                       std::size_t first_ghost) {
  const std::size_t F = fields.size();
  std::size_t total = 0;
  auto next = plan_rows(
      ranks_, list.dest.size(), [&](std::size_t j) { return list.dest[j]; }, send_counts_, total);
  send_.resize(total * F);
  for (std::size_t j = 0; j < list.index.size(); ++j) {
    std::uint64_t *row = &send_[next[list.dest[j]]++ * F];
    for (std::size_t f = 0; f < F; ++f)
      row[f] = std::bit_cast<std::uint64_t>((*fields[f])[list.index[j]]);
  }
  recv_counts_ = copied_from_; // (the ghosts of the last copy)
  exchange_rows(F, true, Reach::neighbours);
  const std::size_t g = F ? recv_.size() / F : 0;
  for (std::size_t j = 0; j < g; ++j)
    for (std::size_t f = 0; f < F; ++f)
      (*fields[f])[first_ghost + j] = std::bit_cast<double>(recv_[j * F + f]);
}

void Exchange::reverse(const Halo &h, const std::vector<std::int64_t> &per_ghost, int k,
                       std::vector<std::int64_t> &per_owner) {
  const std::size_t row_len = static_cast<std::size_t>(k) + 1;
  std::size_t total = 0;
  auto next = plan_rows(
      ranks_, h.size(), [&](std::size_t g) { return h.source_rank[g]; }, send_counts_, total);
  send_.resize(total * row_len);
  for (std::size_t g = 0; g < h.size(); ++g) {
    std::uint64_t *row = &send_[next[h.source_rank[g]]++ * row_len];
    row[0] = h.source_index[g];
    for (int j = 0; j < k; ++j)
      row[1 + j] = static_cast<std::uint64_t>(per_ghost[g * k + j]);
  }
  recv_counts_ = copied_to_; // (one row back for each copy sent)
  exchange_rows(row_len, true, Reach::neighbours);
  for (std::size_t j = 0; j < recv_.size() / row_len; ++j) {
    const std::uint64_t *row = &recv_[j * row_len];
    for (int q = 0; q < k; ++q)
      per_owner[row[0] * k + q] += static_cast<std::int64_t>(row[1 + q]);
  }
}

} // namespace narrows::parallel
