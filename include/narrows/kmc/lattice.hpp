// One replica of the three-state stochastic lattice gas (seed 000 ch.2) in continuous time.
//
// Algorithm (exact, random-sequential): in a configuration with total rate R the waiting time
// to the next event is Exp(R) and the event is chosen with probability rate/R, independently.
// R is kept exactly from the number of bonds in each of the 9 pair states (plus the two
// boundary sites), so each event draws one exponential waiting time. The event itself is
// chosen by rejection: pick a slot (a bulk bond, or a boundary site) uniformly, accept it with
// probability R(slot state)/R_max and pick the transition from the same uniform number; a
// rejected try is redrawn without advancing time. This needs one byte per site and no lists.
//
// Random numbers: a stateful xoshiro256++ per replica, seeded from Philox (seed, kmc_replica,
// replica), because an event needs several draws (a counter-based draw per try would cost
// more than the event).
//
// Observables are accumulated lazily between warm-up and the end: each site keeps the time of
// its last change and the time spent in states 1 and 2; each bond counts the charge C moved
// across it (C(n_k) - C(n'_k) per transition, i.e. left to right is positive).
#pragma once

#include "narrows/scene/scene.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace narrows::kmc {

// xoshiro256++ (Blackman & Vigna, public domain).
class Xoshiro256 {
public:
  Xoshiro256(std::uint64_t seed, std::uint64_t stream);
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[0] + s_[3], 23) + s_[0];
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  // Uniform in (0, 1] with 53 bits.
  double open01() { return static_cast<double>((next() >> 11) + 1) * 0x1p-53; }

private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::array<std::uint64_t, 4> s_;
};

struct ReplicaResult {
  std::vector<double> current; // per bond, charge per unit time: [L-1] (open) or [L] (periodic)
  std::vector<double> density; // [L][3] occupation probabilities
  double current_left = 0.0;   // from the left reservoir into site 1 (open only)
  double current_right = 0.0;  // from site L into the right reservoir (open only)
  double mean_current = 0.0;   // average of `current` over the bonds
  std::uint64_t events = 0;    // transitions done (warm-up included)
  std::uint64_t tries = 0;     // slot draws, rejected ones included
};

class Lattice {
public:
  // Draws the initial product measure from the replica's generator.
  Lattice(const scene::Kmc &model, std::uint64_t seed, std::uint64_t replica);

  // Advances to time t_end (the last event before it is done, the rest is waiting).
  void run_until(double t_end);
  // Starts the observation window now (zeroes the accumulators).
  void start_observing();
  // The observables over [start_observing, now].
  ReplicaResult result() const;

  double time() const { return t_; }
  double total_rate() const;
  std::uint64_t events() const { return events_; }
  std::uint64_t tries() const { return tries_; }
  const std::vector<std::uint8_t> &state() const { return n_; }
  std::int64_t total_charge() const;
  std::size_t bonds() const { return bonds_; }

private:
  struct Transition {
    double threshold; // cumulative rate up to and including this transition
    std::uint8_t to;  // target pair code (bulk) or state (boundary)
    std::int8_t dq;   // charge moved to the right
  };
  // Classes 0..8 bulk pair codes, 9..11 left site states, 12..14 right site states.
  struct Class {
    double rate = 0.0; // total out-rate (= the last threshold)
    std::array<Transition, 8> t{};
  };
  struct alignas(32) SiteAcc {
    double last = 0.0;  // time of the last change (or of start_observing)
    double occ1 = 0.0;  // time in state 1
    double occ2 = 0.0;  // time in state 2
    std::int64_t q = 0; // charge moved across the bond to the right of this site
  };

  template <bool Observe> void run(double t_end);
  int code(std::size_t bond) const {
    const std::size_t b1 = bond + 1 == n_.size() ? 0 : bond + 1;
    return 3 * n_[bond] + n_[b1];
  }

  const scene::Kmc model_;
  bool periodic_;
  std::size_t bonds_;
  std::vector<std::uint8_t> n_;
  std::array<Class, 15> classes_;
  std::array<std::int64_t, 9> count_{}; // bonds in each pair state
  double r_max_ = 0.0;
  Xoshiro256 rng_;
  double t_ = 0.0;
  double t_obs_ = 0.0;
  bool observing_ = false;
  std::vector<SiteAcc> acc_;
  std::int64_t q_left_ = 0, q_right_ = 0;
  std::uint64_t events_ = 0, tries_ = 0;
};

} // namespace narrows::kmc
