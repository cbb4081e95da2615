// Counted work and balanced slab boundaries (see work_balance.hpp).
#include "narrows/engines/mpcd/work_balance.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace narrows::mpcd {

WorkCounts &WorkCounts::operator+=(const WorkCounts &o) {
  fluid += o.fluid;
  colloids += o.colloids;
  contacts += o.contacts;
  bounces += o.bounces;
  ghosts += o.ghosts;
  return *this;
}

double WorkCounts::work() const {
  using W = WorkWeights;
  return W::fluid * fluid + W::colloid * colloids + W::contact * contacts + W::bounce * bounces +
         W::ghost * ghosts;
}

double imbalance(const std::vector<double> &per_rank) {
  if (per_rank.empty())
    return 1.0;
  double sum = 0.0, most = 0.0;
  for (double w : per_rank) {
    sum += w;
    most = std::max(most, w);
  }
  return sum > 0.0 ? most * static_cast<double>(per_rank.size()) / sum : 1.0;
}

std::vector<double> speed_shares(const std::vector<double> &work, const std::vector<double> &busy) {
  if (work.size() != busy.size())
    throw std::invalid_argument("speed_shares: " + std::to_string(work.size()) + " works and " +
                                std::to_string(busy.size()) + " times");
  std::vector<double> shares(work.size());
  for (std::size_t r = 0; r < work.size(); ++r) {
    if (!(work[r] > 0.0 && busy[r] > 0.0 && std::isfinite(work[r] / busy[r])))
      return {};
    shares[r] = work[r] / busy[r];
  }
  return shares;
}

std::vector<int> balanced_first_columns(const std::vector<double> &work, int ranks, int min_columns,
                                        const std::vector<double> &shares) {
  const int columns = static_cast<int>(work.size());
  const int m = std::max(min_columns, 1);
  if (ranks < 1 || static_cast<long long>(ranks) * m > columns)
    throw std::invalid_argument("balanced_first_columns: " + std::to_string(ranks) +
                                " slabs of at least " + std::to_string(m) + " of " +
                                std::to_string(columns) + " columns");
  std::vector<double> sum(static_cast<std::size_t>(columns) + 1, 0.0); // work of columns < c
  for (int c = 0; c < columns; ++c)
    sum[c + 1] = sum[c] + std::max(work[c], 0.0);
  const double total = sum[columns];
  // The running sum of the shares (ranks before r), and their total.
  std::vector<double> before;
  if (!shares.empty()) {
    if (shares.size() != static_cast<std::size_t>(ranks))
      throw std::invalid_argument("balanced_first_columns: " + std::to_string(shares.size()) +
                                  " shares for " + std::to_string(ranks) + " ranks");
    before.assign(shares.size() + 1, 0.0);
    for (std::size_t r = 0; r < shares.size(); ++r) {
      if (!(shares[r] >= 0.0 && std::isfinite(shares[r])))
        throw std::invalid_argument("balanced_first_columns: share " + std::to_string(shares[r]));
      before[r + 1] = before[r] + shares[r];
    }
    if (!(before.back() > 0.0))
      throw std::invalid_argument("balanced_first_columns: all shares zero");
  }
  std::vector<int> first(static_cast<std::size_t>(ranks), 0);
  for (int r = 1; r < ranks; ++r) {
    const int lo = first[r - 1] + m, hi = columns - (ranks - r) * m;
    int c = lo;
    if (total > 0.0) {
      const double target =
          before.empty() ? total * r / ranks : total * (before[r] / before.back());
      c = static_cast<int>(std::lower_bound(sum.begin() + lo, sum.begin() + hi + 1, target) -
                           sum.begin());
      c = std::min(c, hi);
      if (c > lo && target - sum[c - 1] < sum[c] - target)
        --c;
    } else { // nothing counted: equal slabs
      c = std::clamp(static_cast<int>(static_cast<long long>(r) * columns / ranks), lo, hi);
    }
    first[r] = c;
  }
  return first;
}

} // namespace narrows::mpcd
