// The segregation model's time-dependent profiles (Kanehl (thesis) eq 5.30, phi_i_t = -J_i_y):
// finite volumes of width h = 2w / cells across [-w, w], the current of eq 5.14 at each interior
// face from the mean and the difference of its two cells (J = -(M (phi_R - phi_L) / h + b) with M,
// b at the face; second order), no current through the walls (the total of each kind is kept to
// rounding), classical RK4 in time as in the thesis (sec 5.2.4).
#pragma once

#include "narrows/engines/continuum/segregation_model.hpp"

#include <cstddef>
#include <vector>

namespace narrows::continuum {

class SegregationSolver {
public:
  SegregationSolver(const SegregationModel &model, std::size_t cells);

  double cell() const { return h_; }
  const std::vector<double> &centres() const { return centres_; }
  const std::vector<double> &faces() const { return faces_; } // the cells - 1 interior faces

  // One RK4 step of phi[i][cell] (one vector per kind).
  void step(std::vector<std::vector<double>> &phi, double dt);
  // d phi / dt of the kind-major state x[i * cells + j]; false if a face leaves the domain.
  bool rate(const std::vector<double> &x, std::vector<double> &out) const;

private:
  const SegregationModel &model_;
  std::size_t n_, cells_;
  double h_;
  std::vector<double> centres_, faces_;
  std::vector<double> x_, t_, k_[4];
};

} // namespace narrows::continuum
