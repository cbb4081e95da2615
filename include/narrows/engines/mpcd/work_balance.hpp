// Slabs balanced by work (issue 36 item 3). Each rank counts what it did in each step: the fluid
// particles it holds, the colloids it owns, the spring contacts' updates (sub-steps times
// contacts), the fluid particles it bounced back off colloids and the ghost particles it made in
// the cells colloids cut. Weighted by the measured cost of one of each (WorkWeights), they give
// the rank's counted work, in fluid particle-steps; max/mean over the ranks is the imbalance. To
// balance, the work is estimated per cell column (the fluid by its particles' columns, each
// colloid and contact at its centre's column, with the run's mean bounce-backs and ghost
// particles per colloid) and the slab boundaries are put where the running sum of it crosses
// r/R of the total (balanced_first_columns). The slabs decide only which rank computes what:
// the results are bitwise the same (the MPCD step is rank-count independent).
#pragma once

#include <vector>

namespace narrows::mpcd {

// Counted items times steps.
struct WorkCounts {
  double fluid = 0.0;    // fluid particles held after each step
  double colloids = 0.0; // colloids owned after each step
  double contacts = 0.0; // spring contact updates (sub-steps times contacts, ghosts' included)
  double bounces = 0.0;  // fluid particles bounced back off colloids
  double ghosts = 0.0;   // ghost particles made in cells cut by colloids
  WorkCounts &operator+=(const WorkCounts &o);
  // The weighted sum, in fluid particle-steps.
  double work() const;
};

// The cost of one item of each count in fluid particle-steps, measured on the Table 6.1 channel
// (run/pulses_table6_1.toml: 1098 disks, 187150 fluid particles; 1 rank, 200 steps, a 2-core
// machine at load ~10, so only the ratios mean something): the fluid's share of the loop, 8.79 s
// of 27.36 s, per particle-step (2.35e-7 s); the no-slip coupling's stage timers divided by
// their counts: motion + lookup + hand-over per colloid-step (1.18 s / 219600 = 5.4e-6 s),
// contacts per contact update (0.338 s / 2.09e6), bounce-back per bounced particle (4.95 s /
// 627282 = 7.9e-6 s: the search for the fluid inside colloids dominates it), ghost sums +
// responses + solve + fluid shift per ghost particle (12.1 s / 4.95e7).
struct WorkWeights {
  static constexpr double fluid = 1.0;
  static constexpr double colloid = 23.0;
  static constexpr double contact = 0.7;
  static constexpr double bounce = 34.0;
  static constexpr double ghost = 1.0;
  // Per colloid-step, where the run has not counted them yet (the start), the same run's means:
  // 2.86 bounce-backs, 225 ghost particles and 9.5 contact updates. A colloid costs ~360 fluid
  // particle-steps, less than the ~490 fluid particles its disk (a = 2.5, n = 25) displaces.
  static constexpr double bounces_per_colloid = 2.86;
  static constexpr double ghosts_per_colloid = 225.0;
  static constexpr double contact_updates_per_colloid = 9.5;
};

// max/mean of per-rank values (1 if they are all zero).
double imbalance(const std::vector<double> &per_rank);

// The first column of each of `ranks` slabs over work.size() columns, each slab at least
// `min_columns` wide, with the boundaries where the running sum of `work` (>= 0 per column)
// comes closest to r/ranks of the total; with `shares` (one per rank, >= 0, not all zero) to
// the sum of the shares of ranks before r over the sum of all (a rank twice as fast takes twice
// the work).
std::vector<int> balanced_first_columns(const std::vector<double> &work, int ranks,
                                        int min_columns = 1,
                                        const std::vector<double> &shares = {});

// The shares of balanced_first_columns that even the ranks' busy time: each rank's counted work
// per busy second over the same steps. Equal shares (empty) if any rank has no work or time
// measured.
std::vector<double> speed_shares(const std::vector<double> &work, const std::vector<double> &busy);

} // namespace narrows::mpcd
