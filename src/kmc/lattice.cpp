// One replica of the three-state lattice gas: rejection-chosen events, exact Exp(R) waiting
// times, conserved-charge currents and snapshot densities (see kmc/lattice.hpp).
#include "narrows/kmc/lattice.hpp"

#include "narrows/core/rng.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::kmc {

namespace {

// The incrementally kept total rate is recomputed from the bond counts this often, so rounding
// never accumulates over more than this many events.
constexpr std::uint64_t resync_every = 1u << 16;

} // namespace

Xoshiro256::Xoshiro256(std::uint64_t seed, std::uint64_t stream, std::uint32_t substream) {
  const auto a = rng::draw(seed, rng::Purpose::kmc_replica, 2 * substream, stream);
  const auto b = rng::draw(seed, rng::Purpose::kmc_replica, 2 * substream + 1, stream);
  s_ = {(std::uint64_t{a[0]} << 32) | a[1], (std::uint64_t{a[2]} << 32) | a[3],
        (std::uint64_t{b[0]} << 32) | b[1], (std::uint64_t{b[2]} << 32) | b[3]};
  if ((s_[0] | s_[1] | s_[2] | s_[3]) == 0)
    s_[0] = 0x9E3779B97F4A7C15ull; // the one forbidden state
}

Lattice::Lattice(const scene::Kmc &model, std::uint64_t seed, std::uint64_t replica,
                 LatticeOptions options)
    : model_(model), periodic_(model.boundary == scene::KmcBoundary::periodic),
      every_bond_(options.count_every_bond),
      bonds_(static_cast<std::size_t>(periodic_ ? model.length : model.length - 1)),
      n_(static_cast<std::size_t>(model.length)), rng_(seed, replica, 0),
      rng_time_(seed, replica, 1) {
  pairs_ = options.pair_histogram;
  const auto &C = model.charge;
  for (int from = 0; from < 9; ++from) {
    Class &c = classes_[from];
    int m = 0;
    double sum = 0.0;
    for (int to = 0; to < 9; ++to) {
      const double r = model.rates[from * 9 + to];
      if (to == from || r <= 0.0)
        continue;
      sum += r;
      c.t[m++] = {sum, static_cast<std::uint8_t>(to),
                  static_cast<std::int8_t>(C[from / 3] - C[to / 3])};
      if (C[from / 3] + C[from % 3] != C[to / 3] + C[to % 3])
        conserving_ = false;
    }
    c.rate = sum;
  }
  if (!conserving_)
    every_bond_ = true;
  for (int side = 0; side < 2; ++side)
    for (int from = 0; from < 3; ++from) {
      Class &c = classes_[9 + 3 * side + from];
      if (periodic_)
        continue;
      const auto &table = side == 0 ? model.left : model.right;
      int m = 0;
      double sum = 0.0;
      for (int to = 0; to < 3; ++to) {
        const double r = table[from * 3 + to];
        if (to == from || r <= 0.0)
          continue;
        sum += r;
        // left: charge entering site 1; right: charge leaving site L
        const int dq = side == 0 ? C[to] - C[from] : C[from] - C[to];
        c.t[m++] = {sum, static_cast<std::uint8_t>(to), static_cast<std::int8_t>(dq)};
      }
      c.rate = sum;
    }
  for (const auto &c : classes_)
    r_max_ = std::max(r_max_, c.rate);

  // Product measure, or a shock measure (eq 2.23): sites 1..shock_site from `initial`, the
  // rest from `initial_right`.
  const bool shock = model.initial_kind == scene::KmcInitial::shock;
  for (std::size_t k = 0; k < n_.size(); ++k) {
    const auto &p = shock && static_cast<std::int64_t>(k) >= model.shock_site ? model.initial_right
                                                                              : model.initial;
    const double u = rng_.open01();
    std::uint8_t s = u <= p[0] ? 0 : (u <= p[0] + p[1] ? 1 : 2);
    if (p[s] == 0.0) // rounding at the edge of an empty state: never pick it
      s = static_cast<std::uint8_t>(p[1] > 0.0 ? 1 : (p[0] > 0 ? 0 : 2));
    n_[k] = s;
  }
  for (std::size_t b = 0; b < bonds_; ++b)
    ++count_[code(b)];
  rate_ = total_rate();
  ahead_ = rng_.next();
}

double Lattice::total_rate() const {
  double r = 0.0;
  for (int j = 0; j < 9; ++j)
    r += static_cast<double>(count_[j]) * classes_[j].rate;
  if (!periodic_)
    r += classes_[9 + n_.front()].rate + classes_[12 + n_.back()].rate;
  return r;
}

std::int64_t Lattice::total_charge() const {
  std::int64_t q = 0;
  for (const auto s : n_)
    q += model_.charge[s];
  return q;
}

void Lattice::start_observing(double window) {
  const std::size_t L = n_.size();
  hist1_.assign(L, 0);
  hist2_.assign(L, 0);
  flushed1_.clear();
  flushed2_.clear();
  hist_pair_.assign(pairs_ ? 9 * bonds_ : 0, 0);
  flushed_pair_.clear();
  samples_ = 0;
  pending_ = 0;
  n_start_ = n_;
  q_bond_.assign(every_bond_ ? bonds_ : 0, 0);
  q_left_ = q_right_ = q_wrap_ = 0;
  t_obs_ = t_;
  const double r = total_rate();
  sample_dt_ = r > 0.0 ? static_cast<double>(L) / r : window;
  if (window > 0.0)
    sample_dt_ = std::min(sample_dt_, window / 1000.0);
  next_sample_ = t_ + 0.5 * sample_dt_;
  observing_ = true;
}

void Lattice::snapshot() {
  const std::size_t L = n_.size();
  const std::uint8_t *n = n_.data();
  std::uint32_t *h1 = hist1_.data(), *h2 = hist2_.data();
  for (std::size_t k = 0; k < L; ++k) {
    h1[k] += n[k] == 1;
    h2[k] += n[k] == 2;
  }
  if (pairs_) {
    std::uint32_t *hp = hist_pair_.data();
    for (std::size_t k = 0; k < bonds_; ++k)
      ++hp[9 * k + code(k)];
  }
  ++samples_;
  if (++pending_ == (1u << 31))
    flush_histogram();
}

void Lattice::flush_histogram() {
  flushed1_.resize(hist1_.size(), 0.0);
  flushed2_.resize(hist2_.size(), 0.0);
  for (std::size_t k = 0; k < hist1_.size(); ++k) {
    flushed1_[k] += hist1_[k];
    flushed2_[k] += hist2_[k];
    hist1_[k] = hist2_[k] = 0;
  }
  flushed_pair_.resize(hist_pair_.size(), 0.0);
  for (std::size_t i = 0; i < hist_pair_.size(); ++i) {
    flushed_pair_[i] += hist_pair_[i];
    hist_pair_[i] = 0;
  }
  pending_ = 0;
}

bool Lattice::run_until(double t_end, const std::function<bool()> &interrupted) {
  if (!observing_)
    return run<false, false>(t_end, interrupted);
  if (every_bond_)
    return run<true, true>(t_end, interrupted);
  return run<true, false>(t_end, interrupted);
}

template <bool Observe, bool EveryBond>
bool Lattice::run(double t_end, const std::function<bool()> &interrupted) {
  const std::size_t L = n_.size();
  const std::uint64_t slots = bonds_ + (periodic_ ? 0 : 2);
  const double r_max = r_max_;
  const bool periodic = periodic_;
  const Class *cls = classes_.data();
  std::uint8_t *n = n_.data();
  std::int64_t *cnt = count_.data();
  double t = t_;
  double rate = rate_;
  std::uint64_t events = 0, tries = 0;
  std::uint64_t until_resync = resync_every;
  std::uint64_t x_next = ahead_;

  bool finished = true;
  while (true) {
    if ((events & ((std::uint64_t{1} << 20) - 1)) == 0 && events > 0 && interrupted &&
        interrupted()) {
      finished = false;
      break;
    }
    if (--until_resync == 0) {
      rate_ = rate;
      rate = total_rate();
      until_resync = resync_every;
    }
    if (!(rate > 0.0)) { // absorbing state: nothing happens any more
      rate = total_rate();
      if (!(rate > 0.0)) {
        t = t_end;
        break;
      }
    }
    const double dt = -std::log(rng_time_.open01()) / rate;
    const double t_next = t + dt;
    if constexpr (Observe) {
      // the configuration is constant on [t, t_next): it is what the snapshots in there see
      while (next_sample_ < t_next && next_sample_ < t_end) {
        snapshot();
        next_sample_ += sample_dt_;
      }
    }
    if (t_next >= t_end) {
      t = t_end;
      break;
    }
    t = t_next;
    ++events;
    for (;;) {
      ++tries;
      // One 64-bit draw gives both the slot (high word of x * slots) and a uniform fraction
      // (low word) that decides acceptance and the transition.
      const unsigned __int128 p = static_cast<unsigned __int128>(x_next) * slots;
      x_next = rng_.next();
      const std::uint64_t slot_next =
          static_cast<std::uint64_t>((static_cast<unsigned __int128>(x_next) * slots) >> 64);
      __builtin_prefetch(n + std::min<std::uint64_t>(slot_next, L - 1));
      const std::uint64_t slot = static_cast<std::uint64_t>(p >> 64);
      const double v = static_cast<double>(static_cast<std::uint64_t>(p)) * 0x1p-64 * r_max;
      if (slot < bonds_) {
        const std::size_t k = slot;
        const std::size_t k2 = k + 1 == L ? 0 : k + 1;
        const int a = n[k], b = n[k2];
        const Class &c = cls[3 * a + b];
        if (!(v < c.rate))
          continue;
        int m = 0;
        while (!(v < c.t[m].threshold))
          ++m;
        const int to = c.t[m].to;
        const int a2 = to / 3, b2 = to % 3;
        --cnt[3 * a + b];
        ++cnt[to];
        rate += cls[to].rate - c.rate;
        if (a2 != a) {
          if (k > 0 || periodic) {
            const std::size_t kl = k == 0 ? L - 1 : k - 1;
            const int before = 3 * n[kl] + a, after = 3 * n[kl] + a2;
            --cnt[before];
            ++cnt[after];
            rate += cls[after].rate - cls[before].rate;
          } else { // site 1 of an open chain: its boundary rates change
            rate += cls[9 + a2].rate - cls[9 + a].rate;
          }
          n[k] = static_cast<std::uint8_t>(a2);
        }
        if (b2 != b) {
          if (k2 + 1 < L || periodic) {
            const std::size_t kr = k2 + 1 == L ? 0 : k2 + 1;
            const int before = 3 * b + n[kr], after = 3 * b2 + n[kr];
            --cnt[before];
            ++cnt[after];
            rate += cls[after].rate - cls[before].rate;
          } else { // site L of an open chain
            rate += cls[12 + b2].rate - cls[12 + b].rate;
          }
          n[k2] = static_cast<std::uint8_t>(b2);
        }
        if constexpr (Observe) {
          if constexpr (EveryBond)
            q_bond_[k] += c.t[m].dq;
          else if (k2 == 0) // the bond L -> 1 of a periodic chain
            q_wrap_ += c.t[m].dq;
        }
        break;
      }
      const bool left = slot == bonds_;
      const std::size_t site = left ? 0 : L - 1;
      const int s = n[site];
      const Class &c = cls[(left ? 9 : 12) + s];
      if (!(v < c.rate))
        continue;
      int m = 0;
      while (!(v < c.t[m].threshold))
        ++m;
      const int s2 = c.t[m].to;
      rate += cls[(left ? 9 : 12) + s2].rate - c.rate;
      const int before = left ? 3 * s + n[1] : 3 * n[L - 2] + s;
      const int after = left ? 3 * s2 + n[1] : 3 * n[L - 2] + s2;
      --cnt[before];
      ++cnt[after];
      rate += cls[after].rate - cls[before].rate;
      if constexpr (Observe)
        (left ? q_left_ : q_right_) += c.t[m].dq;
      n[site] = static_cast<std::uint8_t>(s2);
      break;
    }
  }
  t_ = t;
  ahead_ = x_next;
  rate_ = total_rate();
  events_ += events;
  tries_ += tries;
  return finished;
}

ReplicaResult Lattice::result() const {
  ReplicaResult r;
  const std::size_t L = n_.size();
  const double T = t_ - t_obs_;
  const double inv = T > 0.0 ? 1.0 / T : 0.0;
  const double inv_samples = samples_ > 0 ? 1.0 / static_cast<double>(samples_) : 0.0;
  r.density.resize(3 * L);
  for (std::size_t k = 0; k < L; ++k) {
    const double c1 = hist1_[k] + (flushed1_.empty() ? 0.0 : flushed1_[k]);
    const double c2 = hist2_[k] + (flushed2_.empty() ? 0.0 : flushed2_[k]);
    r.density[3 * k + 0] = (static_cast<double>(samples_) - c1 - c2) * inv_samples;
    r.density[3 * k + 1] = c1 * inv_samples;
    r.density[3 * k + 2] = c2 * inv_samples;
  }
  r.pair.resize(hist_pair_.size());
  for (std::size_t i = 0; i < hist_pair_.size(); ++i)
    r.pair[i] = (hist_pair_[i] + (flushed_pair_.empty() ? 0.0 : flushed_pair_[i])) * inv_samples;
  // Integrated charge across each bond.
  std::vector<std::int64_t> q(bonds_);
  if (every_bond_) {
    q = q_bond_;
  } else {
    // Continuity: the charge across bond k (sites k, k+1) is the charge across bond k-1 minus
    // what site k gained. Open chains start from the left reservoir, periodic ones from the
    // bond L -> 1 (index L - 1).
    const auto &C = model_.charge;
    std::int64_t prev = periodic_ ? q_wrap_ : q_left_;
    for (std::size_t k = 0; k < bonds_; ++k) {
      prev += C[n_start_[k]] - C[n_[k]];
      q[k] = prev;
    }
  }
  r.current.resize(bonds_);
  std::int64_t total = 0;
  for (std::size_t b = 0; b < bonds_; ++b) {
    r.current[b] = static_cast<double>(q[b]) * inv;
    total += q[b];
  }
  r.mean_current = static_cast<double>(total) * inv / static_cast<double>(bonds_);
  r.current_left = static_cast<double>(q_left_) * inv;
  r.current_right = static_cast<double>(q_right_) * inv;
  r.events = events_;
  r.tries = tries_;
  return r;
}

} // namespace narrows::kmc
