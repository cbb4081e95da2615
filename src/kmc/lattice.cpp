// One replica of the three-state lattice gas: rejection-chosen events, exact Exp(R) waiting
// times (see kmc/lattice.hpp).
#include "narrows/kmc/lattice.hpp"

#include "narrows/core/rng.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::kmc {

Xoshiro256::Xoshiro256(std::uint64_t seed, std::uint64_t stream) {
  const auto a = rng::draw(seed, rng::Purpose::kmc_replica, 0, stream);
  const auto b = rng::draw(seed, rng::Purpose::kmc_replica, 1, stream);
  s_ = {(std::uint64_t{a[0]} << 32) | a[1], (std::uint64_t{a[2]} << 32) | a[3],
        (std::uint64_t{b[0]} << 32) | b[1], (std::uint64_t{b[2]} << 32) | b[3]};
  if ((s_[0] | s_[1] | s_[2] | s_[3]) == 0)
    s_[0] = 0x9E3779B97F4A7C15ull; // the one forbidden state
}

Lattice::Lattice(const scene::Kmc &model, std::uint64_t seed, std::uint64_t replica)
    : model_(model), periodic_(model.boundary == scene::KmcBoundary::periodic),
      bonds_(static_cast<std::size_t>(periodic_ ? model.length : model.length - 1)),
      n_(static_cast<std::size_t>(model.length)), rng_(seed, replica),
      acc_(static_cast<std::size_t>(model.length)) {
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
    }
    c.rate = sum;
  }
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

  for (auto &s : n_) {
    const double u = rng_.open01();
    s = u <= model.initial[0] ? 0 : (u <= model.initial[0] + model.initial[1] ? 1 : 2);
    if (model.initial[s] == 0.0) // rounding at the edge of an empty state: never pick it
      s = static_cast<std::uint8_t>(model.initial[1] > 0.0 ? 1 : (model.initial[0] > 0 ? 0 : 2));
  }
  for (std::size_t b = 0; b < bonds_; ++b)
    ++count_[code(b)];
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

void Lattice::start_observing() {
  for (auto &a : acc_)
    a = SiteAcc{t_, 0.0, 0.0, 0};
  q_left_ = q_right_ = 0;
  t_obs_ = t_;
  observing_ = true;
}

void Lattice::run_until(double t_end) {
  if (observing_)
    run<true>(t_end);
  else
    run<false>(t_end);
}

template <bool Observe> void Lattice::run(double t_end) {
  const std::size_t L = n_.size();
  const std::uint64_t slots = bonds_ + (periodic_ ? 0 : 2);
  const double r_max = r_max_;
  std::uint8_t *n = n_.data();
  SiteAcc *acc = acc_.data();
  double t = t_;
  std::uint64_t events = 0, tries = 0;

  // Time spent in the old state of a site that changes now.
  const auto leave = [&](std::size_t site, int old_state) {
    if constexpr (Observe) {
      SiteAcc &a = acc[site];
      const double held = t - a.last;
      a.last = t;
      if (old_state == 1)
        a.occ1 += held;
      else if (old_state == 2)
        a.occ2 += held;
    }
  };

  while (true) {
    const double rate = total_rate();
    if (!(rate > 0.0)) { // absorbing state: nothing happens any more
      t = t_end;
      break;
    }
    const double dt = -std::log(rng_.open01()) / rate;
    if (t + dt >= t_end) {
      t = t_end;
      break;
    }
    t += dt;
    ++events;
    for (;;) {
      ++tries;
      // One 64-bit draw gives both the slot (high word of x * slots) and a uniform fraction
      // (low word) that decides acceptance and the transition.
      const unsigned __int128 p = static_cast<unsigned __int128>(rng_.next()) * slots;
      const std::uint64_t slot = static_cast<std::uint64_t>(p >> 64);
      const double v = static_cast<double>(static_cast<std::uint64_t>(p)) * 0x1p-64 * r_max;
      if (slot < bonds_) {
        const std::size_t k = slot;
        const std::size_t k2 = k + 1 == L ? 0 : k + 1;
        const int a = n[k], b = n[k2];
        const Class &c = classes_[3 * a + b];
        if (!(v < c.rate))
          continue;
        int m = 0;
        while (!(v < c.t[m].threshold))
          ++m;
        const int to = c.t[m].to;
        const int a2 = to / 3, b2 = to % 3;
        --count_[3 * a + b];
        ++count_[to];
        if (a2 != a) {
          if (k > 0 || periodic_) {
            const std::size_t kl = k == 0 ? L - 1 : k - 1;
            --count_[3 * n[kl] + a];
            ++count_[3 * n[kl] + a2];
          }
          leave(k, a);
          n[k] = static_cast<std::uint8_t>(a2);
        }
        if (b2 != b) {
          if (k2 + 1 < L || periodic_) {
            const std::size_t kr = k2 + 1 == L ? 0 : k2 + 1;
            --count_[3 * b + n[kr]];
            ++count_[3 * b2 + n[kr]];
          }
          leave(k2, b);
          n[k2] = static_cast<std::uint8_t>(b2);
        }
        if constexpr (Observe)
          acc[k].q += c.t[m].dq;
        break;
      }
      const bool left = slot == bonds_;
      const std::size_t site = left ? 0 : L - 1;
      const int s = n[site];
      const Class &c = classes_[(left ? 9 : 12) + s];
      if (!(v < c.rate))
        continue;
      int m = 0;
      while (!(v < c.t[m].threshold))
        ++m;
      const int s2 = c.t[m].to;
      if (left) {
        --count_[3 * s + n[1]];
        ++count_[3 * s2 + n[1]];
        if constexpr (Observe)
          q_left_ += c.t[m].dq;
      } else {
        --count_[3 * n[L - 2] + s];
        ++count_[3 * n[L - 2] + s2];
        if constexpr (Observe)
          q_right_ += c.t[m].dq;
      }
      leave(site, s);
      n[site] = static_cast<std::uint8_t>(s2);
      break;
    }
  }
  t_ = t;
  events_ += events;
  tries_ += tries;
}

ReplicaResult Lattice::result() const {
  ReplicaResult r;
  const std::size_t L = n_.size();
  const double T = t_ - t_obs_;
  const double inv = T > 0.0 ? 1.0 / T : 0.0;
  r.density.resize(3 * L);
  for (std::size_t k = 0; k < L; ++k) {
    const SiteAcc &a = acc_[k];
    const double held = t_ - a.last;
    const double occ1 = a.occ1 + (n_[k] == 1 ? held : 0.0);
    const double occ2 = a.occ2 + (n_[k] == 2 ? held : 0.0);
    r.density[3 * k + 0] = (T - occ1 - occ2) * inv;
    r.density[3 * k + 1] = occ1 * inv;
    r.density[3 * k + 2] = occ2 * inv;
  }
  r.current.resize(bonds_);
  std::int64_t total = 0;
  for (std::size_t b = 0; b < bonds_; ++b) {
    r.current[b] = static_cast<double>(acc_[b].q) * inv;
    total += acc_[b].q;
  }
  r.mean_current = static_cast<double>(total) * inv / static_cast<double>(bonds_);
  r.current_left = static_cast<double>(q_left_) * inv;
  r.current_right = static_cast<double>(q_right_) * inv;
  r.events = events_;
  r.tries = tries_;
  return r;
}

} // namespace narrows::kmc
