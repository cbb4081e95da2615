// A colloidal disc in the FHP lattice gas with the Ladd-Frenkel moving-boundary rules
// (van der Hoef & Frenkel §4.2, eq 23-27), moving or held in place (§4.3).
//
// The disc is the set of sites within `radius` of its centre; the lattice gas fills inside
// and outside. A boundary link joins an outside site A and an inside site B (or the reverse)
// along link k; its two slots are the post-collision particle of A on link k (heading to B)
// and that of B on link k + 3 (heading to A). Before the next propagation each boundary link
// either exchanges its slots (both particles are reflected back to their own side: bounce-
// back) or keeps them (the particle crosses). With the local wall velocity v = U + w x r at
// the middle of the link and i the link of the pair with x_i = c_i.v > 0, eq 23: the particle
// moving along -i (against the wall) is always reflected, the one moving along i is crossing
// with probability p_i = (c^2/D) 4 x_i / (x_i + c^2/D)^2 (eq 27, c = 1, D = 2), reflected
// otherwise; v = 0 gives plain bounce-back. Each reflection moves 2 c momentum from the fluid
// to the colloid, so fluid + colloid momentum is conserved exactly: momenta are kept as
// integers in units of (1/2, sqrt(3)/2) (c_k = (a_k / 2, b_k sqrt(3) / 2) with integer a, b).
// The torque of the same momentum changes about the centre drives the angular velocity
// (moment of inertia M R^2 / 2). Rule draws are a pure function of (seed, step, link index),
// links numbered in the order (global y, global x, k) of their site A.
//
// Moving (held = false): after the rules the centre advances by the new U (continuous
// coordinates, periodic) and the orientation by w. Because the gas fills inside and outside,
// covering or uncovering a site moves no mass or momentum: only the set of boundary links
// changes. It is rebuilt from the disc's bounding box (plus one ring of sites), and only when
// the centre has moved farther than the smallest distance of a site from the circle since the
// last rebuild (otherwise no site can have crossed it). Held (§4.3): the disc stays at its
// position, its velocity evolves from the momentum exchange (the velocity whose VACF and
// integral, the virtual displacement, the paper measures).
//
// MPI slabs: the colloid is replicated on every rank. apply() gathers the post-collision
// states of the boundary links' end sites (a few per link) to all ranks with one MPI_BOR
// reduction (non-owners give 0), applies the rules identically everywhere and writes back the
// sites each rank owns, so the colloid state is the same on every rank and the lattice is
// bitwise the one of a single rank.
#pragma once

#include "narrows/engines/lgca/fhp_lattice.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace narrows::lgca {

struct ColloidParams {
  double x = 0.0, y = 0.0; // centre (Cartesian: row y of sites is at y sqrt(3)/2)
  double radius = 2.5, mass = 680.0;
  double vx = 0.0, vy = 0.0; // initial velocity
  bool held = true;
  std::uint64_t seed_for_rules = 0; // the run's seed
};

// Momentum in units (1/2, sqrt(3)/2): P = (units[0] / 2, units[1] sqrt(3) / 2).
using MomentumUnits = std::array<std::int64_t, 2>;

class FhpColloid {
public:
  FhpColloid(const ColloidParams &params, const FhpLattice &lattice);

  // The boundary rule on the post-collision state of lattice.time(), before the next step;
  // then (moving disc) the centre advances by the new velocity. Collective on lattice.comm().
  void apply(FhpLattice &lattice);

  const ColloidParams &params() const { return params_; }
  MomentumUnits momentum() const { return momentum_; }
  std::array<double, 2> velocity() const;
  double omega() const { return omega_; }
  // The centre, wrapped into [0, size_x) x [0, size_y sqrt(3)/2), and the orientation angle
  // (the sum of omega over the steps; 0 for a held disc).
  std::array<double, 2> position() const { return {x_, y_}; }
  double angle() const { return angle_; }
  // The velocity of the disc together with the lattice gas inside it, (P + P_in) / (M + N_in):
  // reflections on the inner side of the boundary links only move momentum between the two,
  // so this is the velocity the outside fluid exchanges momentum with (the one measured).
  // Collective.
  std::array<double, 2> composite_velocity(const FhpLattice &lattice) const;
  // M + the number of gas particles inside the disc: the mass that moves with composite_velocity.
  // Collective.
  double composite_mass(const FhpLattice &lattice) const;
  // The centre-of-mass velocity of fluid + colloid, (P_fluid + P) / (N + M) (collective). Without
  // walls, obstacles and body force it is conserved exactly, and it is the velocity the held
  // colloid's fluctuates about: a random initial state gives it |V| ~ (N kT)^(1/2) / (N + M),
  // which a time average of U(0).U(t) sees as a plateau |V|^2 and the virtual displacement as a
  // drift V t (D(t) ~ |V|^2 t / 4). The colloid averages are taken of U - V.
  std::array<double, 2> centre_of_mass_velocity(const FhpLattice &lattice) const;
  int boundary_links() const { return static_cast<int>(links_.size()); }
  int inside_sites() const { return static_cast<int>(inside_.size()); }
  // How often the set of covered sites was recomputed, and how often it had changed (then the
  // boundary links were rebuilt), since construction.
  std::int64_t geometry_checks() const { return checks_; }
  std::int64_t geometry_rebuilds() const { return rebuilds_; }
  // Restoring a checkpoint: momentum, angular velocity, centre and angle.
  void set_state(const MomentumUnits &p, double omega, const std::array<double, 2> &position,
                 double angle);

private:
  struct Link {
    int a, b;      // end sites: indices into sites_ (A, B its neighbour along link k)
    int k;         // 0, 1 or 2
    double mx, my; // middle of the link (Cartesian, unwrapped from site A)
  };
  struct Site {
    int x, y; // global
  };
  // Recomputes the covered sites if the centre may have crossed a site since the last time;
  // rebuilds links_ and sites_ if they changed (always when `force`).
  void update_geometry(bool force);

  ColloidParams params_;
  int size_x_ = 0, size_y_ = 0;
  double lx_ = 0.0, ly_ = 0.0;
  double x_ = 0.0, y_ = 0.0, angle_ = 0.0;
  std::vector<Link> links_;
  std::vector<Site> sites_;  // end sites of the links, in (y, x) order
  std::vector<Site> inside_; // sites of the disc, in (y, x) order
  std::vector<std::uint8_t> patch_;
  std::vector<int> col_at_, row_at_; // rebuild scratch: box index of a global column / row
  double x0_ = 0.0, y0_ = 0.0, margin_ = -1.0; // centre and its free distance at the last check
  std::int64_t checks_ = 0, rebuilds_ = 0;
  MomentumUnits momentum_{};
  double omega_ = 0.0, inertia_ = 0.0;
};

// Total fluid momentum of the lattice in the same units (collective).
MomentumUnits fluid_momentum(const FhpLattice &lattice);

} // namespace narrows::lgca
