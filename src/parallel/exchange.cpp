// Migrate, copy, refresh and reverse for any structure-of-arrays species: the row counts by
// MPI_Alltoall, the rows by point-to-point messages to and from the ranks that have any.
#include "narrows/parallel/exchange.hpp"

#include "narrows/core/error.hpp"

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

// Rows of `row` words to every rank (counts in rows, send in rank order); the received rows in
// recv, in the order of their source ranks. The counts go by MPI_Alltoall; the rows only between
// ranks that have any for each other, as point-to-point messages (an MPI_Alltoallv may pay a
// latency for each of the P - 1 ranks even when the message is empty: the cost of a halo
// exchange would grow with the number of ranks).
// Words (not rows) per rank and their offsets go to scount, rcount, sdispl, rdispl (kept by the
// caller: no allocation per exchange).
void exchange_rows(MPI_Comm comm, int ranks, std::size_t row, const std::vector<int> &send_rows,
                   std::vector<int> &recv_rows, std::vector<int> &scount, std::vector<int> &rcount,
                   std::vector<int> &sdispl, std::vector<int> &rdispl,
                   const std::vector<std::uint64_t> &send, std::vector<std::uint64_t> &recv,
                   std::vector<MPI_Request> &requests, std::uint64_t &bytes_sent) {
  recv_rows.assign(ranks, 0);
  MPI_Alltoall(send_rows.data(), 1, MPI_INT, recv_rows.data(), 1, MPI_INT, comm);
  scount.resize(ranks);
  rcount.resize(ranks);
  sdispl.assign(ranks, 0);
  rdispl.assign(ranks, 0);
  long long stotal = 0, rtotal = 0;
  for (int r = 0; r < ranks; ++r) {
    scount[r] = static_cast<int>(send_rows[r] * row);
    rcount[r] = static_cast<int>(recv_rows[r] * row);
    sdispl[r] = static_cast<int>(stotal);
    rdispl[r] = static_cast<int>(rtotal);
    stotal += scount[r];
    rtotal += rcount[r];
  }
  if (stotal > std::numeric_limits<int>::max() || rtotal > std::numeric_limits<int>::max())
    throw Error(ExitCode::other, "exchange of more than 2^31 words in one step");
  recv.resize(static_cast<std::size_t>(rtotal));
  int me = 0;
  MPI_Comm_rank(comm, &me);
  bytes_sent += 8 * static_cast<std::uint64_t>(stotal - scount[me]);
  requests.clear();
  for (int r = 0; r < ranks; ++r)
    if (r != me && rcount[r] > 0) {
      requests.emplace_back();
      MPI_Irecv(recv.data() + rdispl[r], rcount[r], MPI_UINT64_T, r, rows_tag, comm,
                &requests.back());
    }
  for (int r = 0; r < ranks; ++r)
    if (r != me && scount[r] > 0) {
      requests.emplace_back();
      MPI_Isend(send.data() + sdispl[r], scount[r], MPI_UINT64_T, r, rows_tag, comm,
                &requests.back());
    }
  std::copy(send.begin() + sdispl[me], send.begin() + sdispl[me] + scount[me],
            recv.begin() + rdispl[me]); // (the rows a rank keeps)
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
}

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

void Exchange::migrate(const SoaView &s, const std::vector<int> &dest) {
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
  migrate(s, leavers, to);
}

void Exchange::migrate(const SoaView &s, const std::vector<std::size_t> &leavers,
                       const std::vector<int> &to) {
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
  exchange_rows(comm_, ranks_, F, send_counts_, recv_counts_, send_words_, recv_words_,
                send_displs_, recv_displs_, send_, recv_, requests_, bytes_sent_);
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
  exchange_rows(comm_, ranks_, row_len, send_counts_, recv_counts_, send_words_, recv_words_,
                send_displs_, recv_displs_, send_, recv_, requests_, bytes_sent_);
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
  exchange_rows(comm_, ranks_, F, send_counts_, recv_counts_, send_words_, recv_words_,
                send_displs_, recv_displs_, send_, recv_, requests_, bytes_sent_);
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
  exchange_rows(comm_, ranks_, row_len, send_counts_, recv_counts_, send_words_, recv_words_,
                send_displs_, recv_displs_, send_, recv_, requests_, bytes_sent_);
  for (std::size_t j = 0; j < recv_.size() / row_len; ++j) {
    const std::uint64_t *row = &recv_[j * row_len];
    for (int q = 0; q < k; ++q)
      per_owner[row[0] * k + q] += static_cast<std::int64_t>(row[1 + q]);
  }
}

} // namespace narrows::parallel
