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
// Random numbers: stateful xoshiro256++ generators per replica, seeded from Philox (seed,
// kmc_replica, replica), because an event needs several draws (a counter-based draw per try
// would cost more than the event). Event choices are drawn one try ahead so the state byte of
// the next slot can be prefetched (at L = 1e6 the state does not fit in L2).
//
// Observables over the observation window:
// - current: the charge C moved across each bond, C(n_k) - C(n'_k) per transition (left to
//   right positive). When every bulk transition conserves C (the usual case) only the
//   boundary transitions (open) or the bond L -> 1 (periodic) are counted and the other bonds
//   follow exactly from the lattice continuity equation: Q_k = Q_(k-1) + C_k(start) - C_k(end).
//   Otherwise (or on request) every bond keeps its own counter.
// - density (and on request the pair state of each bond): averaged over snapshots of the whole
//   lattice at fixed times t_start + (i + 1/2) dt (unbiased for the time average; dt = L / R
//   at the start of the window, about one snapshot per L events, at most window / 1000).
// Neither touches per-site memory in the event loop, which then only reads and writes the one
// byte per site of the state.
#pragma once

#include "narrows/scene/scene.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace narrows::kmc {

// xoshiro256++ (Blackman & Vigna, public domain).
class Xoshiro256 {
public:
  // Substream 0 chooses events, 1 draws waiting times (so the event choice can be drawn one
  // try ahead and its site prefetched).
  Xoshiro256(std::uint64_t seed, std::uint64_t stream, std::uint32_t substream = 0);
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
  std::vector<double> pair;    // [bonds][9] P(n_k, n_(k+1)) by pair code (if asked for)
  double current_left = 0.0;   // from the left reservoir into site 1 (open only)
  double current_right = 0.0;  // from site L into the right reservoir (open only)
  double mean_current = 0.0;   // average of `current` over the bonds
  std::uint64_t events = 0;    // transitions done (warm-up included)
  std::uint64_t tries = 0;     // slot draws, rejected ones included
};

struct LatticeOptions {
  bool count_every_bond = false; // per-bond current counters even when C is conserved
  bool pair_histogram = false;   // snapshots also count the pair state of every bond
};

class Lattice {
public:
  // Draws the initial product measure from the replica's generator.
  Lattice(const scene::Kmc &model, std::uint64_t seed, std::uint64_t replica,
          LatticeOptions options = {});

  // Advances to time t_end (the last event before it is done, the rest is waiting). If
  // `interrupted` is given it is asked every 2^20 events; when it answers true the run stops
  // there and returns false (the replica is then unfinished and should be dropped).
  bool run_until(double t_end, const std::function<bool()> &interrupted = {});
  // Starts the observation window now; `window` (its planned length) sets the snapshot
  // interval so that a short window still gets >= 1000 snapshots.
  void start_observing(double window);
  // The observables over [start_observing, now].
  ReplicaResult result() const;

  double time() const { return t_; }
  double total_rate() const; // recomputed from the bond counts
  std::uint64_t events() const { return events_; }
  std::uint64_t tries() const { return tries_; }
  const std::vector<std::uint8_t> &state() const { return n_; }
  std::int64_t total_charge() const;
  std::size_t bonds() const { return bonds_; }
  bool conserving() const { return conserving_; } // every bulk transition conserves C

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

  template <bool Observe, bool EveryBond>
  bool run(double t_end, const std::function<bool()> &interrupted);
  void snapshot();
  void flush_histogram();
  int code(std::size_t bond) const {
    const std::size_t b1 = bond + 1 == n_.size() ? 0 : bond + 1;
    return 3 * n_[bond] + n_[b1];
  }

  scene::Kmc model_;
  bool periodic_;
  bool conserving_ = true;
  bool every_bond_;
  std::size_t bonds_;
  std::vector<std::uint8_t> n_;
  std::array<Class, 15> classes_;
  std::array<std::int64_t, 9> count_{}; // bonds in each pair state
  double r_max_ = 0.0;
  double rate_ = 0.0; // total rate, kept incrementally and resynchronised from count_
  Xoshiro256 rng_, rng_time_;
  std::uint64_t ahead_ = 0; // the next event-choice draw, already taken from rng_
  double t_ = 0.0;
  std::uint64_t events_ = 0, tries_ = 0;

  // observation
  bool observing_ = false;
  double t_obs_ = 0.0;
  double sample_dt_ = 1.0, next_sample_ = 0.0;
  std::uint64_t samples_ = 0;
  std::uint32_t pending_ = 0;                // snapshots in hist1_/hist2_ not yet flushed
  std::vector<std::uint32_t> hist1_, hist2_; // snapshots with n_k = 1, 2
  bool pairs_ = false;
  std::vector<std::uint32_t> hist_pair_; // snapshots with bond k in pair state c: [k * 9 + c]
  std::vector<double> flushed_pair_;
  std::vector<double> flushed1_, flushed2_; // older snapshot counts (rarely used)
  std::vector<std::uint8_t> n_start_;       // state at start_observing (conserving current)
  std::vector<std::int64_t> q_bond_;        // per-bond counters (every_bond or not conserving)
  std::int64_t q_left_ = 0, q_right_ = 0, q_wrap_ = 0;
};

} // namespace narrows::kmc
