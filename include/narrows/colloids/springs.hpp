// Linear springs with Coulomb friction (Kanehl (thesis) §4.2.3, eq 4.39-4.42, fig 4.6), the
// contacts of `[colloids] contacts = "spring"`. Two overlapping bodies (colloid-colloid, or colloid
// and a wall at rest at y = 0 or y = L_y) feel
//   normal:      F_n = -k_n delta_n n           (delta_n the overlap, n towards the partner)
//   tangential:  F_t = -k_t xi                  (xi the tangential spring of the contact)
// on the first body and the opposite on the second, with torques r n x F_t on both (lever arm
// the radius, towards the contact). The spring xi lives as long as the contact (contact
// history, contact_history.hpp). Each sub-step it is first turned into the current tangent
// plane keeping its length (eq 4.40), then stretched by the tangential relative velocity of
// the contact points times the sub-step (eq 4.39), and cut back to |F_t| = mu |F_n| when it is
// longer (Coulomb, eq 4.41-4.42: the contact slides). mu = 0: no tangential force; mu = inf:
// never slides. Separate mu colloid-colloid and colloid-wall. The thesis has no damping: sigma of
// its Table 6.1 is the pressure gradient of the drive; the fluid damps the collisions.
//
// Integration: velocity Verlet sub-steps (half kick, drift, springs updated with the half-step
// relative velocity at the new positions, forces, half kick). Forces are pure functions of the
// positions and springs, so the force of the first half kick of an MPCD step is recomputed
// from the state the last step left (the same bits, on any number of ranks and on restart),
// or kept from the end of the last step when no row, position or spring has changed since.
//
// Parallel model: each rank computes every pair it holds (owned and ghost rows, each pair once
// in the order of its ids) and moves every row, its ghosts too, through the sub-steps without
// a message; the ghost shell (coupling/no_slip.cpp) is wide enough that the owned rows and the
// ghosts the fluid meets come out exact: the same bits as one rank. The contact history of a
// pair lives with its colloid of the smaller id (contact_history.hpp); the ghosts bring copies
// of theirs for the step.
#pragma once

#include "narrows/colloids/colloids.hpp"
#include "narrows/colloids/contact_history.hpp"
#include "narrows/colloids/forces.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

namespace narrows::colloids {

struct SpringParams {
  double kn = 2500.0, kt = 2500.0; // kT / a^2 (Kanehl (thesis) Table 6.1)
  double mu_cc = 1.0, mu_cw = 1.0; // infinity: never slides
  int substeps = 10;               // velocity-Verlet sub-steps per MPCD step
};

inline constexpr double never_slides = std::numeric_limits<double>::infinity();

class SpringContacts {
public:
  SpringContacts(const SpringParams &params, const mpcd::Box &box);

  // Numbers per row of the sums: the force (dim) and the torque (1 in 2D, 3 in 3D).
  int stride() const { return dim_ == 2 ? 3 : 6; }

  // Contact forces and torques of the current positions into sums() (fixed point, [row *
  // stride + j], every row of c; ghost rows hold what goes back to their owners). `owned`:
  // rows before it are this rank's. With `step` > 0 the springs are first advanced by that
  // time with the current velocities (turned, stretched, capped) and `h` becomes the set of
  // current contacts of this rank; with 0, `h` is read only.
  void compute(const Colloids &c, std::size_t owned, ContactHistory &h, double step);
  const std::vector<std::int64_t> &sums() const { return sums_; }
  std::vector<std::int64_t> &sums() { return sums_; }

  // Moves the first `owned` rows of c over time dt in params().substeps velocity-Verlet
  // sub-steps under the contact forces (plus `external`, a constant force [a * dim + k] on
  // each owned row, if given). Positions end wrapped along the periodic axes. On several ranks
  // `owned` is every row, ghosts too: each rank computes every pair it holds and moves its
  // ghosts itself (the ghost shell of coupling/no_slip.cpp, no messages within the step);
  // contact_updates() counts the contacts whose owner (the smaller id) is among the first
  // `counted` rows (default: owned), so that each contact is counted on one rank.
  void advance(Colloids &c, std::size_t owned, ContactHistory &h, double dt,
               const std::vector<double> *external = nullptr,
               std::size_t counted = std::numeric_limits<std::size_t>::max());

  // Elastic energy of the contacts of c (all rows owned) with springs h: sum of k_n delta^2 / 2
  // + k_t |xi|^2 / 2 (for tests; the wall and pair contacts alike).
  double elastic_energy(const Colloids &c, const ContactHistory &h) const;

  // Contacts this rank computed since the start (pairs and wall contacts, summed over the
  // sub-steps), and those that slid.
  std::uint64_t contact_updates() const { return updates_; }
  std::uint64_t sliding_updates() const { return sliding_; }
  const SpringParams &params() const { return params_; }

  // Times the pair list below was built, and the seconds spent on the contact forces (the
  // kernel: which slots touch, their springs and forces, the sums), for benchmarks.
  std::uint64_t pair_list_builds() const { return builds_; }
  // Times the contact forces were evaluated (advance: one per sub-step, one more at the start
  // of a step unless it could start from the forces the last step ended with).
  std::uint64_t force_evaluations() const { return evaluations_; }
  double force_seconds() const { return force_seconds_; }

private:
  template <int D, bool WallsY>
  void compute(const Colloids &c, std::size_t owned, ContactHistory &h, double step);
  template <int D, bool WallsY>
  void advance(Colloids &c, std::size_t owned, ContactHistory &h, double dt,
               const std::vector<double> *external);
  // The contact forces of the slots that touch into sums_; with step > 0 their springs are
  // advanced first (and those of slots that no longer touch dropped).
  template <int D, bool WallsY> void forces(const Colloids &c, double step);
  template <bool WallsY> void forces_2d(const Colloids &c, double step); // (forces' 2D path)
  // h's springs into the slots (the rest zero); false if that changed a slot's spring or the
  // slots are new.
  bool load_springs(const ContactHistory &h);
  void store_springs(ContactHistory &h) const; // the touching slots into h, in key order
  // same_rows: the rows are known to be those of the last call (only positions changed); rows
  // before `from` are known to have moved at most sqrt(worst) since the list was built.
  template <int D, bool WallsY>
  bool pairs_fresh(const Colloids &c, std::size_t owned, bool same_rows = false,
                   std::size_t from = 0, double worst = 0.0) const;
  template <int D, bool WallsY> void build_pairs(const Colloids &c, std::size_t owned);
  // Kicks the owned rows by h under sums_ (and `external`), twice if `twice` (the same forces),
  // then moves them by v drift (if drift > 0), wrapped along the periodic axes, in one pass.
  // Returns the largest squared displacement of an owned row since the list was built (as
  // pairs_fresh measures it; infinite after a jump by more than a period; 0 without a drift).
  template <int D, bool WallsY>
  double kick_drift(Colloids &c, std::size_t owned, double h, bool twice, double drift,
                    const std::vector<double> *external);
  template <int D, bool WallsY, bool External, bool Moves>
  double kick_drift(Colloids &c, std::size_t owned, double h, bool twice, double drift,
                    const double *external);
  // The positions of the last forces of a step, so that the next step starts from its sums
  // when nothing changed in between.
  void keep_end(const Colloids &c);
  bool same_positions_as_end(const Colloids &c) const;

  SpringParams params_;
  mpcd::Box box_;
  int dim_;
  CellList cells_;
  double cell_cut_ = -1.0;
  std::vector<int> cell_of_;
  std::vector<std::uint32_t> partners_;
  // Verlet list: the pairs (i, j) this rank computes (i the row of the smaller id, owned) whose
  // centres were within r_i + r_j + skin when it was built from the cell list. It holds every
  // touching pair while no row has moved more than skin / 2 since and the rows (ids, radii,
  // owned count) are the same; otherwise it is built again. The contacts found are the same
  // as a cell-list search every call, so are the results, bit for bit.
  // Slot q: rows pair_i_[q] and pair_j_[q] (or a wall), key (slot_owner_, slot_partner_) in
  // ascending order, its spring, and whether it touched at the last update.
  std::vector<std::uint32_t> pair_i_, pair_j_;
  std::vector<std::uint64_t> slot_owner_, slot_partner_;
  std::array<std::vector<double>, 3> slot_xi_;
  std::vector<std::uint8_t> slot_touch_;
  // The slots touching at the current call, with their forces, torques per unit lever arm and
  // whether they slid (scratch of forces()).
  // (slot, rows i and j, kind 0 pair, 1 lower wall, 2 upper wall, spring).
  std::vector<std::uint64_t> hits_;
  struct Slot { // a pair or wall contact of the list being built, with its key
    std::uint64_t owner, partner;
    std::uint32_t i, j;
  };
  std::vector<Slot> build_scratch_; // (kept: no allocation per build once warm)
  std::vector<std::uint64_t> hit_i_, hit_j_;
  std::vector<std::int64_t> hit_kind_, hit_slides_; // (one width: vectorised)
  std::array<std::vector<double>, 3> hit_xi_, hit_force_, hit_torque_;
  // (2D: the separation x_j - x_i and its square, r_i + r_j or the wall overlap, the lever arms;
  // the forces and torques in fixed point)
  std::array<std::vector<double>, 3> hit_sep_;
  std::vector<double> hit_reach_;
  std::array<std::vector<double>, 2> hit_arm_;
  std::array<std::vector<std::int64_t>, 4> hit_fixed_;
  std::array<std::vector<double>, 3> built_x_;
  std::vector<std::uint64_t> built_id_;
  std::vector<double> built_radius_;
  std::size_t built_owned_ = 0;
  double skin_ = 0.0;
  bool built_ = false;
  std::uint64_t builds_ = 0, evaluations_ = 0;
  double force_seconds_ = 0.0;
  std::vector<std::int64_t> sums_;
  std::vector<double> inertia_;         // moments of inertia of the owned rows (advance)
  std::vector<std::uint8_t> rare_axes_; // (kick_drift: the axes a row jumped along)
  std::array<std::vector<double>, 3> end_x_;
  bool end_kept_ = false; // end_x_ holds the positions of the last forces() call
  std::uint64_t updates_ = 0, sliding_ = 0;
  std::size_t counted_rows_ = 0; // contacts whose owner row is below it count in updates_
};

} // namespace narrows::colloids
