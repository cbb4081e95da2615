// The FHP lattice gas of one MPI rank: a slab of columns of the triangular lattice with one
// halo column on each side, stepped by propagation + collision.
//
// Geometry: site (x, y), x in [0, size[0]), y in [0, size[1]) (size[1] even), sits at
// (x + (y mod 2)/2, y sqrt(3)/2); periodic in x and y. Link i of a site points along
// c_i = (cos(pi i/3), sin(pi i/3)); its neighbour along link i is, with o = y mod 2:
//   0: (x+1, y)  1: (x+o, y+1)  2: (x-1+o, y+1)  3: (x-1, y)  4: (x-1+o, y-1)  5: (x+o, y-1)
// State: one byte per site (fhp_model.hpp: bit i = link i, bit 6 = rest particle), the state
// after the collision of step time(). Rank r owns columns [first_column(), first_column() +
// local_columns()) of parallel::Slabs over size[0].
//
// Every random draw is a pure function of (seed, step, global site), so the lattice after
// any number of steps is bitwise the same on any number of ranks.
#pragma once

#include "narrows/engines/lgca/fhp_model.hpp"
#include "narrows/parallel/slabs.hpp"

#include <mpi.h>

#include <array>
#include <cstdint>
#include <vector>

namespace narrows::lgca {

// A solid disc of sites (bounce-back) centred at (x, y) in lattice coordinates.
struct Obstacle {
  double x = 0.0, y = 0.0, radius = 0.0;
};

struct FhpParams {
  FhpModel model = FhpModel::fhp_i;
  int size_x = 0, size_y = 0;
  std::uint64_t seed = 0;
  bool walls = false; // rows 0 and size_y - 1 are solid (no-slip bounce-back)
  double force = 0.0; // probability per fluid site and step of flipping link 3 to link 0
  std::vector<Obstacle> obstacles;
};

class FhpLattice {
public:
  FhpLattice(const FhpParams &params, MPI_Comm comm);

  // Fills the fluid sites: link i occupied with probability d + (rho/3) c_i.u(y) (moving
  // links; the rest link with d), rho = links * d, u = (amplitude sin(2 pi y/size_y), 0).
  // Sets time() to 0.
  void initialise(double density, double amplitude);

  // One step: halo exchange, propagation, collision (and the body force); time() + 1.
  void step();

  std::int64_t time() const { return time_; }
  void set_time(std::int64_t t) { time_ = t; }

  const FhpParams &params() const { return params_; }
  const CollisionTable &table() const { return table_; }
  const parallel::Slabs &slabs() const { return slabs_; }
  MPI_Comm comm() const { return slabs_.comm(); }
  int size_x() const { return params_.size_x; }
  int size_y() const { return params_.size_y; }
  int first_column() const { return slabs_.first_column(); }
  int local_columns() const { return nx_; }

  // Post-collision states of row y: local_columns() bytes, entry i is global column
  // first_column() + i. The mutable form is for restoring a checkpoint.
  const std::uint8_t *row(int y) const { return cur_.data() + index(0, y); }
  std::uint8_t *row(int y) { return cur_.data() + index(0, y); }
  std::uint8_t site(int x_local, int y) const { return cur_[index(x_local, y)]; }
  bool solid(int x_local, int y) const { return !solid_.empty() && solid_[index(x_local, y)] != 0; }
  bool has_solids() const { return !solid_.empty(); }
  // Fluid (non-solid) sites of the whole lattice.
  std::int64_t fluid_sites() const { return fluid_sites_; }

private:
  std::size_t index(int x_local, int y) const {
    return static_cast<std::size_t>(y) * stride_ + 1 + static_cast<std::size_t>(x_local);
  }
  void exchange_halos();
  void chirality_bits(int y, std::uint64_t step, std::vector<std::uint64_t> &bits) const;
  void apply_force(int y, std::uint64_t step, std::uint8_t *row) const;

  FhpParams params_;
  CollisionTable table_;
  std::array<std::uint8_t, 128> bounce_{};
  parallel::Slabs slabs_;
  int nx_ = 0;
  std::size_t stride_ = 0;
  std::vector<std::uint8_t> cur_, next_, solid_;
  std::int64_t time_ = 0;
  std::int64_t fluid_sites_ = 0;
};

} // namespace narrows::lgca
