// Engine "continuum", model "segregation" (see continuum/segregation_driver.hpp).
#include "narrows/engines/continuum/segregation_driver.hpp"

#include "narrows/core/error.hpp"
#include "narrows/engines/continuum/field_run.hpp"
#include "narrows/engines/continuum/segregation_curves.hpp"
#include "narrows/engines/continuum/segregation_model.hpp"
#include "narrows/engines/continuum/segregation_plan.hpp"
#include "narrows/engines/continuum/segregation_solver.hpp"
#include "narrows/io/observables_writer.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::continuum {

namespace {

// The total number density up to a constant (c_i ~ phi_i / a_i^d), for Delta of eq 5.31.
double number_density(const scene::Segregation &s, const double *phi) {
  double c = 0.0;
  for (std::size_t i = 0; i < s.kinds.size(); ++i)
    c += phi[i] / std::pow(s.kinds[i].radius, s.dimensions);
  return c;
}

} // namespace

std::vector<std::string> describe_segregation(const scene::Scene &scene) {
  const scene::Continuum &m = *scene.continuum;
  const scene::Segregation &s = m.segregation;
  const SegregationModel model(s);
  const SegregationPlan p = plan_of(scene, make_segregation_plan);
  const std::size_t n = model.kinds();
  std::vector<std::string> out;
  out.push_back("engine continuum: segregation model phi_i_t = -J_i_y, J_i = -phi_i A_ij [K_c "
                "(phi_j gdot)_y + K_eta phi_j gdot eta_y / eta] - D_C^ij phi_j_y "
                "(Kanehl (thesis) eq 5.13-5.30), " +
                std::to_string(s.dimensions) + "D, " + std::to_string(n) +
                (n == 1 ? " kind" : " kinds"));
  out.push_back("constants: " +
                format("K_c = %g, K_eta = %g, K_d = %g (K_eta/K_c = %.4g, ", s.k_c, s.k_eta, s.k_d,
                       s.k_eta / s.k_c) +
                format("K_d/K_c = %.4g)", s.k_d / s.k_c));
  for (std::size_t i = 0; i < n; ++i) {
    const auto &k = s.kinds[i];
    out.push_back("kind " + std::to_string(i) +
                  format(": radius %g, mean fraction %g, D_0 = %g, Peclet a^3 v0 / (w^2 D_0) = ",
                         k.radius, k.fraction, k.diffusivity) +
                  format("%.4g (eq 5.1)", model.peclet(i)));
  }
  if (n == 2)
    out.push_back("coupling matrix (eq 5.13): " +
                  format("A_00 = %.6g, A_01 = %.6g, A_10 = %.6g, A_11 = %.6g", model.coupling(0, 0),
                         model.coupling(0, 1), model.coupling(1, 0), model.coupling(1, 1)));
  out.push_back("collective diffusion: D_C^ii = K_d D_0^i / S(phi), D_C^ij = D_C^ii phi_i / (1 - "
                "phi_j)^2 (eq 5.23-5.28), S of eq " +
                std::string(s.dimensions == 2 ? "5.19-5.20 (Boublik, 2D)" : "5.21-5.22 (3D)"));
  out.push_back(format("viscosity: eta = eta_0 (1 - phi / %g)^-2 (eq 5.29)", s.max_packing));
  out.push_back(
      s.shear == scene::SegregationShear::poiseuille
          ? format("shear rate: Poiseuille, gdot = 2 v0 |y| / w^2 with v0 = %g", s.centre_speed)
          : format("shear rate: viscous, gdot = 2 v0 |y| eta(%g) / (w^2 eta(phi)) with v0 = %g "
                   "(constant pressure gradient)",
                   model.kinds() == 1 ? s.kinds[0].fraction
                                      : s.kinds[0].fraction + s.kinds[1].fraction,
                   s.centre_speed));
  out.push_back("grid: " + std::to_string(m.cells) + " cells of h = " + format("%g", p.h) +
                " across [-" + format("%g, %g", s.half_width, s.half_width) +
                "], walls without current; initial: uniform at the mean fractions");
  if (p.steady.ok) {
    const auto &phi = p.steady.phi;
    const std::size_t last = phi.size() / n - 1;
    for (std::size_t i = 0; i < n; ++i)
      out.push_back("steady state kind " + std::to_string(i) +
                    format(": phi(0) = %.6g, phi(w) = %.6g, c(0)/c_mean = %.5g, ", phi[i],
                           phi[last * n + i], phi[i] / s.kinds[i].fraction) +
                    format("migration/diffusion K_c a^2 gdot phi / (K_d D_0) at the wall %.4g",
                           model.migration_ratio(i, &phi[last * n], s.half_width)));
    out.push_back("steady state: RK4 from the centre to the wall in " + std::to_string(last) +
                  " steps, centre values by Newton's method (" +
                  std::to_string(p.steady.iterations) + " iterations" +
                  format(", means within %.2g)", p.steady.mass_error));
  } else {
    out.push_back("steady state: none found (" + p.steady.failure +
                  "); the time step comes from the uniform start only");
  }
  out.push_back("scheme: finite volumes, the current of eq 5.14 at each face from its two cells "
                "(second order), RK4 in time (Kanehl (thesis) sec 5.2.4)");
  out.push_back(
      "time step: dt = " +
      format("%.6g (cfl %g: dt (%.4g / h^2 + %.4g / h) = ", p.dt, m.cfl, p.diffusive, p.drift) +
      format("%.4g with the largest |M| row sum and drift speed of the start and the "
             "steady state)",
             p.number));
  out.push_back("time: " + format("%g", m.time) + " in " + std::to_string(p.steps) + " steps; " +
                std::to_string(m.samples) + " samples (every " + std::to_string(p.per_sample) +
                " steps) and t = 0");
  out.push_back("ranks: every rank advances the same cells (no decomposition); memory about " +
                format("%.3g MiB", 8.0 * 8.0 * static_cast<double>(m.cells * n) / 1048576.0));
  return out;
}

namespace {

// The segregation model's fractions phi_i of every kind on its RK4 solver.
class Segregation final : public FieldModel {
public:
  explicit Segregation(const scene::Scene &scene)
      : scene_(scene), s_(scene.continuum->segregation), p_(plan_of(scene, make_segregation_plan)),
        segregation_(s_), n_(segregation_.kinds()),
        cells_(static_cast<std::size_t>(scene.continuum->cells)), solver_(segregation_, cells_),
        phi_(n_), bins_(solver_.centres()), row_(cells_ * n_), c0_(cells_) {
    for (std::size_t i = 0; i < n_; ++i)
      phi_[i].assign(cells_, s_.kinds[i].fraction);
    if (p_.steady.ok)
      steady_ = steady_at(p_.steady, bins_);
    for (std::size_t j = 0; j < cells_; ++j) {
      double x[max_segregation_kinds];
      for (std::size_t i = 0; i < n_; ++i)
        x[i] = s_.kinds[i].fraction;
      c0_[j] = number_density(s_, x);
    }
    dt = p_.dt;
    steps = p_.steps;
    per_sample = p_.per_sample;
    points = cells_;
    lines = describe_segregation(scene);
    for (std::size_t i = 0; i < n_; ++i)
      fields.push_back({"fraction_" + std::to_string(i), &phi_[i]});
  }

  void step(double dt) override { solver_.step(phi_, dt); }
  void check(std::int64_t step) const override {
    for (std::size_t j = 0; j < cells_; ++j) {
      double x[max_segregation_kinds];
      for (std::size_t i = 0; i < n_; ++i)
        x[i] = phi_[i][j];
      if (!segregation_.admissible(x))
        throw invariant_error(scene_.file + ": the fractions in cell " + std::to_string(j) +
                              " are negative, not finite or at close packing (phi_M = " +
                              format("%g", s_.max_packing) + ") at step " + std::to_string(step) +
                              "; allowed: a smaller continuum.cfl or more continuum.cells");
    }
  }
  std::string restored_out_of_range() const override {
    for (std::size_t j = 0; j < cells_; ++j) {
      double x[max_segregation_kinds];
      for (std::size_t i = 0; i < n_; ++i)
        x[i] = phi_[i][j];
      if (!segregation_.admissible(x)) {
        std::size_t i = 0;
        double total = 0.0;
        for (std::size_t k = 0; k < n_; ++k) {
          total += x[k];
          if (x[k] < 0.0)
            i = k;
        }
        return "fraction_" + std::to_string(i) + "[" + std::to_string(j) +
               "] = " + format("%.17g", x[i]) + format(" (all kinds %.17g)", total) +
               "; allowed: fractions >= 0 whose sum is below close packing phi_M = " +
               format("%.6g", s_.max_packing);
      }
    }
    // The no-flux walls conserve each kind: its mean fraction stays the scene's.
    for (std::size_t i = 0; i < n_; ++i) {
      double sum = 0.0;
      for (std::size_t j = 0; j < cells_; ++j)
        sum += phi_[i][j];
      const double mean = sum / static_cast<double>(cells_), given = s_.kinds[i].fraction;
      if (!(std::abs(mean - given) <= 1e-6 * given))
        return "fraction_" + std::to_string(i) + format(" has the mean %.17g", mean) +
               "; allowed: " + format("%.17g", given) +
               ", the kind's fraction in the scene (the walls conserve each kind)";
    }
    return {};
  }
  void sample(io::ObservablesWriter *writer, std::int64_t st, double t) override {
    if (writer == nullptr)
      return;
    const std::size_t n = n_, cells = cells_;
    for (std::size_t j = 0; j < cells; ++j)
      for (std::size_t i = 0; i < n; ++i)
        row_[j * n + i] = phi_[i][j];
    if (wants(scene_, "density"))
      writer->append_profile("density", st, t, bins_, row_, n);
    if (wants(scene_, "evolution")) {
      double num = 0.0, den = 0.0;
      for (std::size_t j = 0; j < cells; ++j) {
        const double c = number_density(s_, &row_[j * n]);
        num += (c - c0_[j]) * (c - c0_[j]);
        den += c0_[j] * c0_[j];
      }
      writer->append_scalar("evolution", st, t, num / den);
    }
    if (wants(scene_, "steady_density") && p_.steady.ok && !steady_written_) {
      writer->write_result("steady_density", st, t, steady_, {{"bins", bins_}}, {cells, n});
      steady_written_ = true;
    }
    if (wants(scene_, "collective_diffusivity") && !curves_written_) {
      const SegregationCurves c = segregation_curves(segregation_);
      writer->write_result("collective_diffusivity", st, t, c.value,
                           {{"bins", c.phi},
                            {"structure_factor", c.structure},
                            {"viscosity", c.viscosity},
                            {"composition", c.composition},
                            {"scale", c.scale}},
                           {c.phi.size(), n, n});
      curves_written_ = true;
    }
  }
  void summary(run::Log &log, std::int64_t step) const override {
    for (std::size_t i = 0; i < n_; ++i) {
      double mean = 0.0, off = 0.0;
      for (std::size_t j = 0; j < cells_; ++j) {
        mean += phi_[i][j] / static_cast<double>(cells_);
        if (p_.steady.ok)
          off = std::max(off, std::abs(phi_[i][j] - steady_[j * n_ + i]));
      }
      log.line("kind " + std::to_string(i) +
               format(" at t = %.6g: mean phi %.12g (fraction %g)",
                      static_cast<double>(step) * p_.dt, mean, s_.kinds[i].fraction) +
               (p_.steady.ok ? format(", largest |phi - steady| %.3g", off) : std::string()));
    }
  }

private:
  const scene::Scene &scene_;
  const scene::Segregation &s_;
  const SegregationPlan p_;
  const SegregationModel segregation_;
  const std::size_t n_, cells_;
  SegregationSolver solver_;
  std::vector<std::vector<double>> phi_;
  const std::vector<double> &bins_;
  std::vector<double> steady_;
  std::vector<double> row_, c0_;
  bool steady_written_ = false, curves_written_ = false;
};

} // namespace

std::unique_ptr<FieldModel> make_segregation(const scene::Scene &scene) {
  return std::make_unique<Segregation>(scene);
}

} // namespace narrows::continuum
