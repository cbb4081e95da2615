// The finite-volume scheme of the conservation law rho_t + J(rho)_x = D rho_xx on `cells`
// cells of width dx: MUSCL reconstruction with a TVD limiter (monotonised central or minmod),
// the Rusanov (local Lax-Friedrichs) flux at each face, the diffusion term by central
// differences, and SSP-RK2 (Heun) in time; second order where the solution is smooth. Plain
// loops over one array with two ghost cells on each side: periodic, or held at the reservoir
// densities (open boundary).
#pragma once

#include "narrows/engines/continuum/flux.hpp"
#include "narrows/scene/scene.hpp"

#include <cstdint>
#include <vector>

namespace narrows::continuum {

struct Grid {
  std::int64_t cells = 0;
  double dx = 1.0;
  bool periodic = false;
  double left = 0.0, right = 0.0; // open: reservoir densities in the ghost cells
};

// The largest stable time step: cfl / (max|J'| / dx + 2 D / dx^2).
double stable_dt(double max_speed, double dx, double diffusion, double cfl);

class Scheme {
public:
  Scheme(const Flux &flux, const Grid &grid, double diffusion, scene::ContinuumLimiter limiter);
  // Advances the cell averages u by dt (SSP-RK2).
  void step(std::vector<double> &u, double dt);

private:
  // du/dt of the semi-discrete scheme.
  void rate(const std::vector<double> &u, std::vector<double> &out);

  const Flux &flux_;
  Grid grid_;
  double diffusion_;
  scene::ContinuumLimiter limiter_;
  std::vector<double> ext_, slope_, face_, k_, u1_;
};

} // namespace narrows::continuum
