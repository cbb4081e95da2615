// One replica of the three-state lattice gas: uniformised tries (Poisson numbers of tries
// between fixed times), conserved-charge currents and snapshot densities (see kmc/lattice.hpp).
#include "narrows/engines/kmc/lattice.hpp"

#include "narrows/core/error.hpp"
#include "narrows/core/rng.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>

namespace narrows::kmc {

namespace {

// Tries per Poisson draw at most (the span to the next fixed time is cut into pieces of this
// mean), which is also how often `interrupted` is asked.
constexpr double piece_tries = 1u << 20;

// The two state bytes of a pair code as they lie in memory (n_k first).
std::uint16_t pair_bytes(int code) {
  const std::uint8_t b[2] = {static_cast<std::uint8_t>(code / 3),
                             static_cast<std::uint8_t>(code % 3)};
  std::uint16_t w;
  std::memcpy(&w, b, 2);
  return w;
}

// f > up picks transitions with probability (cumulative rate) / r_max: up = that fraction of
// 2^64, minus one (the whole range when the fraction is 1).
std::uint64_t upper(double cumulative, double r_max) {
  const double x = cumulative / r_max;
  if (x >= 1.0)
    return std::numeric_limits<std::uint64_t>::max();
  const auto t = static_cast<std::uint64_t>(x * 0x1p64);
  return t == 0 ? 0 : t - 1;
}

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
    c.count = m;
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
      c.count = m;
    }
  for (const auto &c : classes_)
    r_max_ = std::max(r_max_, c.rate);
  int most = 0;
  for (int k = 0; k < 15; ++k) {
    Class &c = classes_[k];
    c.up.fill(std::numeric_limits<std::uint64_t>::max());
    for (int m = 0; m < c.count; ++m)
      c.up[m] = upper(c.t[m].threshold, r_max_);
    if (k < 9) {
      most = std::max(most, c.count);
      for (int m = 0; m < 9; ++m) {
        next_pair_[9 * k + m] = pair_bytes(m < c.count ? c.t[m].to : k);
        next_dq_[9 * k + m] = m < c.count ? c.t[m].dq : 0;
      }
    }
  }
  max_bulk_ = most <= 1 ? 1 : (most <= 2 ? 2 : (most <= 4 ? 4 : 8));

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
}

double Lattice::total_rate() const {
  std::array<std::int64_t, 9> count{};
  for (std::size_t b = 0; b < bonds_; ++b)
    ++count[code(b)];
  double r = 0.0;
  for (int j = 0; j < 9; ++j)
    r += static_cast<double>(count[j]) * classes_[j].rate;
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
  recent_.assign(L, 0);
  recent_count_ = 0;
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
  std::uint16_t *h = recent_.data();
  for (std::size_t k = 0; k < L; ++k) // states 0, 1, 2 add 0, 1, 256
    h[k] = static_cast<std::uint16_t>(h[k] + (n[k] & 1u) + ((n[k] & 2u) << 7));
  if (++recent_count_ == 255)
    add_recent();
  if (pairs_) {
    std::uint32_t *hp = hist_pair_.data();
    for (std::size_t k = 0; k < bonds_; ++k)
      ++hp[9 * k + code(k)];
  }
  ++samples_;
  if (++pending_ == (1u << 31))
    flush_histogram();
}

void Lattice::add_recent() {
  std::uint32_t *h1 = hist1_.data(), *h2 = hist2_.data();
  std::uint16_t *h = recent_.data();
  for (std::size_t k = 0; k < recent_.size(); ++k) {
    h1[k] += h[k] & 0xffu;
    h2[k] += h[k] >> 8;
    h[k] = 0;
  }
  recent_count_ = 0;
}

void Lattice::flush_histogram() {
  add_recent();
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

// Poisson(mean): multiplication of uniforms below 10, else Hoermann's transformed rejection
// with squeeze (PTRS, W. Hoermann, Insurance Math. Econom. 12, 39 (1993)), both exact.
std::uint64_t Lattice::poisson(double mean) {
  if (!(mean > 0.0))
    return 0;
  if (mean < 10.0) {
    const double limit = std::exp(-mean);
    std::uint64_t k = 0;
    double prod = rng_time_.open01();
    while (prod > limit) {
      ++k;
      prod *= rng_time_.open01();
    }
    return k;
  }
  const double slam = std::sqrt(mean), loglam = std::log(mean);
  const double b = 0.931 + 2.53 * slam;
  const double a = -0.059 + 0.02483 * b;
  const double inv_alpha = 1.1239 + 1.1328 / (b - 3.4);
  const double vr = 0.9277 - 3.6224 / (b - 2.0);
  for (;;) {
    const double u = rng_time_.open01() - 0.5; // (-1/2, 1/2]
    const double v = rng_time_.open01();       // (0, 1]
    const double us = 0.5 - std::abs(u);
    const double k = std::floor((2.0 * a / us + b) * u + mean + 0.43);
    if (us >= 0.07 && v <= vr)
      return static_cast<std::uint64_t>(k);
    if (k < 0.0 || (us < 0.013 && v > us))
      continue;
    if (std::log(v) + std::log(inv_alpha) - std::log(a / (us * us) + b) <=
        -mean + k * loglam - std::lgamma(k + 1.0))
      return static_cast<std::uint64_t>(k);
  }
}

// A try on a slot the bulk kernel leaves out: the bond L -> 1 (periodic) or a boundary site
// (open: slot L - 1 is site 1, slot L is site L).
std::uint64_t Lattice::edge_try(std::uint64_t slot, std::uint64_t f) {
  const std::size_t L = n_.size();
  if (periodic_) {
    const Class &c = classes_[3 * n_[L - 1] + n_[0]];
    int m = 0;
    while (m < c.count && f > c.up[m])
      ++m;
    if (m == c.count)
      return 0;
    n_[L - 1] = static_cast<std::uint8_t>(c.t[m].to / 3);
    n_[0] = static_cast<std::uint8_t>(c.t[m].to % 3);
    q_wrap_ += c.t[m].dq;
    if (!q_bond_.empty())
      q_bond_[L - 1] += c.t[m].dq;
    return 1;
  }
  const bool left = slot == bonds_;
  std::uint8_t &site = left ? n_[0] : n_[L - 1];
  const Class &c = classes_[(left ? 9 : 12) + site];
  int m = 0;
  while (m < c.count && f > c.up[m])
    ++m;
  if (m == c.count)
    return 0;
  (left ? q_left_ : q_right_) += c.t[m].dq;
  site = c.t[m].to;
  return 1;
}

template <int M, bool EveryBond> std::uint64_t Lattice::try_bulk(std::uint64_t count) {
  const std::uint64_t slots = bonds_ + (periodic_ ? 0 : 2);
  const std::uint64_t inner = n_.size() - 1; // slots below: bonds (k, k+1) with k + 1 < L
  std::uint8_t *n = n_.data();
  std::int64_t *q = EveryBond ? q_bond_.data() : nullptr;
  // The thresholds of the 9 bulk classes side by side: up[9 * code + j], j < M.
  std::array<std::uint64_t, 9 * M> up;
  for (int c = 0; c < 9; ++c)
    for (int j = 0; j < M; ++j)
      up[M * c + j] = classes_[c].up[j];
  const std::uint16_t *next = next_pair_.data();
  const std::int8_t *dq = next_dq_.data();
  Xoshiro256 rng = rng_;
  std::uint64_t done = 0;
  // Tries go in blocks: the draws of a block first (their sites prefetched), then the tries.
  constexpr std::uint64_t block = 64;
  std::array<std::uint64_t, block> slot_of, f_of;
  for (std::uint64_t first = 0; first < count; first += block) {
    const std::uint64_t nb = std::min(block, count - first);
    // the draws (a serial chain), then x * slots in 32-bit halves (slots < 2^32 as
    // kmc.length < 2^31) so that it vectorises: the high word of the product is the slot, the
    // low word the fraction, as with a 128-bit product
    alignas(64) std::array<std::uint64_t, block> x;
    for (std::uint64_t i = 0; i < nb; ++i)
      x[i] = rng.next();
    for (std::uint64_t i = 0; i < nb; ++i) {
      const std::uint64_t lo = (x[i] & 0xffffffffu) * slots, hi = (x[i] >> 32) * slots;
      const std::uint64_t mid = hi + (lo >> 32);
      slot_of[i] = mid >> 32;
      f_of[i] = (mid << 32) | (lo & 0xffffffffu);
    }
    for (std::uint64_t i = 0; i < nb; ++i)
      __builtin_prefetch(n + slot_of[i], 1); // slot L (a boundary site) is one past: harmless
    for (std::uint64_t i = 0; i < nb; ++i) {
      const std::uint64_t slot = slot_of[i], f = f_of[i];
      if (slot >= inner) [[unlikely]] {
        done += edge_try(slot, f);
        continue;
      }
      // Branch-free: the pair is always written back, unchanged when the try is rejected.
      std::uint16_t w;
      std::memcpy(&w, n + slot, 2);
      const int c = 3 * (w & 0xff) + (w >> 8);
      int m = 0;
      for (int j = 0; j < M; ++j)
        m += f > up[M * c + j];
      const std::uint16_t w2 = next[9 * c + m];
      std::memcpy(n + slot, &w2, 2);
      done += w2 != w;
      if constexpr (EveryBond)
        if (w2 != w)
          q[slot] += dq[9 * c + m];
    }
  }
  rng_ = rng;
  return done;
}

bool Lattice::asked_to_stop(const std::function<bool()> &interrupted) {
  if (since_asked_ < (1u << 20))
    return false;
  since_asked_ = 0;
  return interrupted && interrupted();
}

template <bool Observe, bool EveryBond>
bool Lattice::run(double t_end, const std::function<bool()> &interrupted) {
  const std::uint64_t slots = bonds_ + (periodic_ ? 0 : 2);
  const double lambda = static_cast<double>(slots) * r_max_;
  const double piece = piece_tries / lambda; // longest span per Poisson draw
  double t = t_;
  while (t < t_end) {
    // the next fixed time: a snapshot, or the end
    bool snap = false;
    double stop = t_end;
    if constexpr (Observe)
      if (next_sample_ < t_end) {
        stop = std::max(next_sample_, t);
        snap = true;
      }
    while (t < stop) {
      const double to = stop - t > piece && !absorbing_ ? t + piece : stop;
      // A span below the resolution of t (rates so high that 2^20 tries take less time than
      // one ulp of t) would never end: refuse instead of spinning.
      if (!(to > t))
        throw invariant_error("kmc: the time t = " + std::to_string(t) +
                              " cannot advance by the span of 2^20 tries (" +
                              std::to_string(piece) + ") at rate " + std::to_string(lambda) +
                              "; lower the rates or kmc.time");
      if (!absorbing_) {
        const std::uint64_t k = poisson(lambda * (to - t));
        std::uint64_t done = 0;
        switch (max_bulk_) {
        case 1:
          done = try_bulk<1, EveryBond>(k);
          break;
        case 2:
          done = try_bulk<2, EveryBond>(k);
          break;
        case 4:
          done = try_bulk<4, EveryBond>(k);
          break;
        default:
          done = try_bulk<8, EveryBond>(k);
          break;
        }
        tries_ += k;
        events_ += done;
        since_asked_ += k + 1; // + 1: stop requests are seen even if no try is drawn
        idle_tries_ = done > 0 ? 0 : idle_tries_ + k;
        // A long run of rejected tries (as many as there are slots) may mean that no transition
        // is possible any more; then the tries are skipped (they would all be rejected).
        if (idle_tries_ >= slots) {
          absorbing_ = !(total_rate() > 0.0);
          idle_tries_ = 0;
        }
      }
      t = to;
      if (asked_to_stop(interrupted)) {
        t_ = t;
        return false;
      }
    }
    if (!snap)
      break;
    // the configuration at the snapshot time
    snapshot();
    // A snapshot interval below the resolution of t (a short kmc.time after a long warm-up of
    // a lattice that no longer moves) would take the same snapshot for ever.
    if (!(next_sample_ + sample_dt_ > next_sample_)) {
      char line[200];
      std::snprintf(line, sizeof line,
                    "kmc: the snapshot interval %.3g cannot advance the time t = %.17g; lower "
                    "kmc.warmup or raise kmc.time",
                    sample_dt_, next_sample_);
      throw invariant_error(line);
    }
    next_sample_ += sample_dt_;
    since_asked_ += n_.size(); // a snapshot costs about as much as one try per site
    if (asked_to_stop(interrupted)) {
      t_ = t;
      return false;
    }
  }
  t_ = std::max(t, t_end);
  return true;
}

ReplicaResult Lattice::result() const {
  ReplicaResult r;
  const std::size_t L = n_.size();
  const double T = t_ - t_obs_;
  const double inv = T > 0.0 ? 1.0 / T : 0.0;
  const double inv_samples = samples_ > 0 ? 1.0 / static_cast<double>(samples_) : 0.0;
  r.density.resize(3 * L);
  for (std::size_t k = 0; k < L; ++k) {
    const double c1 = hist1_[k] + (recent_[k] & 0xffu) + (flushed1_.empty() ? 0.0 : flushed1_[k]);
    const double c2 = hist2_[k] + (recent_[k] >> 8) + (flushed2_.empty() ? 0.0 : flushed2_[k]);
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
