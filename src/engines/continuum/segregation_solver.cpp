// Finite volumes and RK4 for the segregation model (see continuum/segregation_solver.hpp).
#include "narrows/engines/continuum/segregation_solver.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::continuum {

SegregationSolver::SegregationSolver(const SegregationModel &model, std::size_t cells)
    : model_(model), n_(model.kinds()), cells_(cells),
      h_(2.0 * model.half_width() / static_cast<double>(cells)) {
  const double w = model.half_width();
  for (std::size_t j = 0; j < cells; ++j)
    centres_.push_back(-w + (static_cast<double>(j) + 0.5) * h_);
  for (std::size_t j = 1; j < cells; ++j)
    faces_.push_back(-w + static_cast<double>(j) * h_);
  x_.resize(n_ * cells);
  t_.resize(n_ * cells);
  for (auto &k : k_)
    k.resize(n_ * cells);
}

bool SegregationSolver::rate(const std::vector<double> &x, std::vector<double> &out) const {
  std::fill(out.begin(), out.end(), 0.0);
  double phi[max_segregation_kinds], d[max_segregation_kinds];
  double m[max_segregation_kinds * max_segregation_kinds], b[max_segregation_kinds];
  bool sound = true;
  for (std::size_t f = 1; f < cells_; ++f) { // between cells f - 1 and f
    for (std::size_t i = 0; i < n_; ++i) {
      const double l = x[i * cells_ + f - 1], r = x[i * cells_ + f];
      phi[i] = 0.5 * (l + r);
      d[i] = (r - l) / h_;
    }
    sound = sound && model_.admissible(phi);
    model_.coefficients(phi, faces_[f - 1], m, b);
    for (std::size_t i = 0; i < n_; ++i) {
      double j = b[i];
      for (std::size_t k = 0; k < n_; ++k)
        j += m[i * n_ + k] * d[k];
      j = -j / h_; // the current over the cell width
      out[i * cells_ + f - 1] -= j;
      out[i * cells_ + f] += j;
    }
  }
  return sound;
}

void SegregationSolver::step(std::vector<std::vector<double>> &phi, double dt) {
  const std::size_t size = n_ * cells_;
  for (std::size_t i = 0; i < n_; ++i)
    for (std::size_t j = 0; j < cells_; ++j)
      x_[i * cells_ + j] = phi[i][j];
  rate(x_, k_[0]);
  for (std::size_t q = 0; q < size; ++q)
    t_[q] = x_[q] + 0.5 * dt * k_[0][q];
  rate(t_, k_[1]);
  for (std::size_t q = 0; q < size; ++q)
    t_[q] = x_[q] + 0.5 * dt * k_[1][q];
  rate(t_, k_[2]);
  for (std::size_t q = 0; q < size; ++q)
    t_[q] = x_[q] + dt * k_[2][q];
  rate(t_, k_[3]);
  for (std::size_t i = 0; i < n_; ++i)
    for (std::size_t j = 0; j < cells_; ++j) {
      const std::size_t q = i * cells_ + j;
      phi[i][j] = x_[q] + dt / 6.0 * (k_[0][q] + 2.0 * k_[1][q] + 2.0 * k_[2][q] + k_[3][q]);
    }
}

} // namespace narrows::continuum
