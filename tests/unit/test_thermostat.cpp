// Per-layer rescaling thermostat (Tabatabaei (2008) eq 3.53-3.54): cell momenta are kept, and each
// layer's kinetic energy relative to the cell means becomes (d/2)(N - C) kT.
#include "narrows/core/fixed_point.hpp"
#include "narrows/engines/mpcd/kernels/cell_grid.hpp"
#include "narrows/engines/mpcd/kernels/thermostat.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using namespace narrows;

TEST(LayerThermostat, KeepsCellMomentaAndSetsEachLayerToKT) {
  for (const int dim : {2, 3}) {
    mpcd::Box box = mpcd::make_periodic_box(dim, {8, 6, 4});
    box.walls_y = true;
    mpcd::Fluid f;
    f.dim = dim;
    std::mt19937_64 gen(11);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    std::normal_distribution<double> normal(0.0, 1.0);
    const std::size_t n = dim == 2 ? 400 : 1600;
    f.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      f.id[i] = i;
      for (int k = 0; k < dim; ++k)
        f.x[k][i] = u01(gen) * box.length[k];
      // hot (kT = 3 ... 8, depending on y) with a shear flow
      const double sigma = std::sqrt(3.0 + f.x[1][i]);
      for (int k = 0; k < dim; ++k)
        f.v[k][i] = sigma * normal(gen) + (k == 0 ? 0.2 * f.x[1][i] : 0.0);
    }
    mpcd::CellGrid grid(box);
    grid.set_shift({0.1, 0.3, -0.2});
    mpcd::bin_particles(f, grid);
    const std::size_t nc = grid.size(), nx = grid.cells[0], ny = grid.cells[1];
    auto cell_momenta = [&] {
      std::vector<double> p(nc * dim, 0.0);
      for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < dim; ++k)
          p[f.cell[i] * dim + k] += f.v[k][i];
      return p;
    };
    const auto p0 = cell_momenta();
    mpcd::LayerSums scratch;
    mpcd::rescale_layers(f, grid, 1.0, scratch, MPI_COMM_NULL);
    const auto p1 = cell_momenta();
    for (std::size_t j = 0; j < p0.size(); ++j)
      EXPECT_NEAR(p1[j], p0[j], 1e-10) << "cell " << j / dim;
    // Per layer: sum (v - u_cell)^2 = d (N - C) kT with kT = 1.
    std::vector<double> e(ny, 0.0), count(ny, 0.0), cells(ny, 0.0);
    std::vector<double> cn(nc, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      cn[f.cell[i]] += 1.0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t c = f.cell[i], l = (c / nx) % ny;
      for (int k = 0; k < dim; ++k) {
        const double r = f.v[k][i] - p1[c * dim + k] / cn[c];
        e[l] += r * r;
      }
      count[l] += 1.0;
    }
    for (std::size_t c = 0; c < nc; ++c)
      cells[(c / nx) % ny] += cn[c] > 0 ? 1.0 : 0.0;
    int layers = 0;
    for (std::size_t l = 0; l < ny; ++l) {
      const double dof = dim * (count[l] - cells[l]);
      if (dof <= 0)
        continue;
      ++layers;
      EXPECT_NEAR(e[l] / dof, 1.0, 1e-9) << "layer " << l << " dim " << dim;
    }
    EXPECT_GE(layers, 6);
  }
}

TEST(MonteCarloThermostat, DrivesCellTemperaturesToKTAndKeepsCellMomenta) {
  // A hot 2D fluid (kT = 3) in 64 x 64 cells, n = 10; only the thermostat acts, 400 times. Its
  // stationary law for a cell's relative energy E is the Boltzmann one of d(n - 1) degrees of
  // freedom, mean (d/2)(n - 1) kT with kT = 1. Mean over ~4000 cells of E / ((d/2)(n - 1)):
  // relative spread sqrt(2 / (d (n - 1))) ~ 0.33 per cell, so ~0.006 for the mean; 0.03 is 5
  // sigma. (From kT = 3 the walk needs ~60 accepted steps of ~0.05 in ln zeta: 400 is ample.)
  const int dim = 2;
  mpcd::Box box = mpcd::make_periodic_box(dim, {64, 64, 1});
  mpcd::Fluid f;
  f.dim = dim;
  std::mt19937_64 gen(5);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, std::sqrt(3.0));
  const std::size_t n = 64 * 64 * 10;
  f.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    f.id[i] = i;
    for (int k = 0; k < dim; ++k) {
      f.x[k][i] = u01(gen) * box.length[k];
      f.v[k][i] = normal(gen) + (k == 0 ? 0.5 * std::sin(f.x[1][i]) : 0.0);
    }
  }
  mpcd::CellGrid grid(box);
  grid.set_shift({0.0, 0.0, 0.0});
  mpcd::bin_particles(f, grid);
  const std::size_t nc = grid.size();
  auto cell_stats = [&](std::vector<double> &p, std::vector<double> &e, std::vector<double> &cn) {
    p.assign(nc * dim, 0.0), e.assign(nc, 0.0), cn.assign(nc, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      cn[f.cell[i]] += 1.0;
      for (int k = 0; k < dim; ++k)
        p[f.cell[i] * dim + k] += f.v[k][i];
    }
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < dim; ++k) {
        const double r = f.v[k][i] - p[f.cell[i] * dim + k] / cn[f.cell[i]];
        e[f.cell[i]] += 0.5 * r * r;
      }
  };
  std::vector<double> p0, e0, cn, p1, e1;
  cell_stats(p0, e0, cn);
  mpcd::LayerSums scratch;
  for (std::uint64_t step = 0; step < 400; ++step)
    mpcd::monte_carlo_cells(f, grid, 1.0, 0.1, 77, step, scratch);
  cell_stats(p1, e1, cn);
  double ratio = 0.0, before = 0.0;
  int cells = 0;
  for (std::size_t c = 0; c < nc; ++c) {
    for (int k = 0; k < dim; ++k)
      EXPECT_NEAR(p1[c * dim + k], p0[c * dim + k], 1e-9);
    if (cn[c] < 2)
      continue;
    ratio += e1[c] / (0.5 * dim * (cn[c] - 1.0));
    before += e0[c] / (0.5 * dim * (cn[c] - 1.0));
    ++cells;
  }
  ratio /= cells;
  before /= cells;
  std::printf("mean cell kT: %.4f before, %.4f after 400 Monte Carlo steps (target 1)\n", before,
              ratio);
  EXPECT_NEAR(before, 3.0, 0.15); // the start was hot
  EXPECT_NEAR(ratio, 1.0, 0.03);
}
