// One replica of the three-state stochastic lattice gas (Tabatabaei (2008) ch.2) in continuous
// time.
//
// Algorithm (exact, random-sequential, by uniformisation): tries come as a Poisson process of
// rate Lambda = slots * R_max in time. A try picks a slot (a bulk bond, or a boundary site)
// uniformly and makes the transition of its state with probability rate/R_max (else nothing
// happens), so every transition of every slot happens at its own rate, exactly as in the
// master equation. Between two fixed times the number of tries is Poisson(Lambda * span):
// one Poisson draw per interval replaces the Exp(R) waiting time per event, and the
// configuration at every fixed time (snapshots, the end of run_until) has exactly the law of
// the continuous-time process. Tries per unit time are Lambda either way, so this does as many
// tries as drawing Exp(R) per event and rejecting; what it saves is the logarithm and the
// division per event, the bookkeeping of R, and the unpredictable branch of each try (a try is
// a table look-up and a store, accepted or not). One byte per site and no lists.
//
// Random numbers: stateful xoshiro256++ generators per replica, seeded from Philox (seed,
// kmc_replica, replica). Substream 0 draws the tries (one 64-bit number: the slot is the high
// word of x * slots, the low word a uniform fraction that decides acceptance and the
// transition); substream 1 draws the Poisson numbers of tries.
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
  // Substream 0 draws the tries, 1 the Poisson numbers of tries.
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

  // Advances to time t_end. If `interrupted` is given it is asked about every 2^20 tries (or
  // their worth of snapshots); when it answers true the run stops there and returns false (the
  // replica is then unfinished and should be dropped).
  bool run_until(double t_end, const std::function<bool()> &interrupted = {});
  // Starts the observation window now; `window` (its planned length) sets the snapshot
  // interval so that a short window still gets >= 1000 snapshots.
  void start_observing(double window);
  // The observables over [start_observing, now].
  ReplicaResult result() const;

  double time() const { return t_; }
  double total_rate() const; // summed over the lattice (O(L))
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
    int count = 0;     // transitions
    std::array<Transition, 8> t{};
    // The try's uniform fraction f (64 bits) picks transition m when m thresholds are below
    // it: f > up[j] for j < m (up[j] = cumulative rate / R_max * 2^64 - 1), and nothing when
    // m = count. Unused entries are the largest value, so they never count.
    std::array<std::uint64_t, 8> up{};
  };

  template <bool Observe, bool EveryBond>
  bool run(double t_end, const std::function<bool()> &interrupted);
  // `count` tries; returns the transitions done. M: transitions counted per try (>= the most
  // of any bulk class).
  template <int M, bool EveryBond> std::uint64_t try_bulk(std::uint64_t count);
  std::uint64_t edge_try(std::uint64_t slot, std::uint64_t f); // slots >= L - 1
  std::uint64_t poisson(double mean);
  // Asks `interrupted` once the work since it was last asked reaches 2^20 tries (a snapshot
  // counts as one try per site).
  bool asked_to_stop(const std::function<bool()> &interrupted);
  void snapshot();
  void flush_histogram();
  void add_recent(); // recent_ into hist1_/hist2_
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
  int max_bulk_ = 1; // most transitions of a bulk class, rounded up to 1, 2, 4 or 8
  // Bulk try outcome by 9 * code + m (m as above): the two state bytes after it (the same
  // bytes when m is past the last transition) and the charge moved to the right.
  std::array<std::uint16_t, 81> next_pair_{};
  std::array<std::int8_t, 81> next_dq_{};
  double r_max_ = 0.0;
  Xoshiro256 rng_, rng_time_;
  double t_ = 0.0;
  std::uint64_t events_ = 0, tries_ = 0;
  bool absorbing_ = false;        // no transition is possible any more (checked, not assumed)
  std::uint64_t idle_tries_ = 0;  // tries since the last transition
  std::uint64_t since_asked_ = 0; // tries since `interrupted` was last asked

  // observation
  bool observing_ = false;
  double t_obs_ = 0.0;
  double sample_dt_ = 1.0, next_sample_ = 0.0;
  std::uint64_t samples_ = 0;
  std::uint32_t pending_ = 0;                // snapshots in hist1_/hist2_ not yet flushed
  std::vector<std::uint32_t> hist1_, hist2_; // snapshots with n_k = 1, 2
  // The latest (at most 255) snapshots, not yet in hist1_/hist2_: per site the count with
  // n_k = 1 in the low byte, n_k = 2 in the high byte. A snapshot then reads 3 bytes per site
  // and writes 2, where two 4-byte counters read and wrote 16 (snapshots are bandwidth-bound
  // and dominate short observation windows).
  std::vector<std::uint16_t> recent_;
  std::uint32_t recent_count_ = 0;
  bool pairs_ = false;
  std::vector<std::uint32_t> hist_pair_; // snapshots with bond k in pair state c: [k * 9 + c]
  std::vector<double> flushed_pair_;
  std::vector<double> flushed1_, flushed2_; // older snapshot counts (rarely used)
  std::vector<std::uint8_t> n_start_;       // state at start_observing (conserving current)
  std::vector<std::int64_t> q_bond_;        // per-bond counters (every_bond or not conserving)
  std::int64_t q_left_ = 0, q_right_ = 0, q_wrap_ = 0;
};

} // namespace narrows::kmc
