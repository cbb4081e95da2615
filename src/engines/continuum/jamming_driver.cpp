// Engine "continuum", model "jamming" (see continuum/jamming_driver.hpp).
#include "narrows/engines/continuum/jamming_driver.hpp"

#include "narrows/core/error.hpp"
#include "narrows/engines/continuum/field_run.hpp"
#include "narrows/engines/continuum/jamming_model.hpp"
#include "narrows/engines/continuum/jamming_plan.hpp"
#include "narrows/engines/continuum/jamming_solver.hpp"
#include "narrows/engines/continuum/jamming_stability.hpp"
#include "narrows/io/checkpoint.hpp"
#include "narrows/io/observables_writer.hpp"
#include "narrows/run/collective.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

namespace narrows::continuum {

namespace {

// "delta_v = ..., ..., phi_q = ...; e3 = ..." with the fit file's errors where it gives them.
std::string vss_parameter_text(const scene::Continuum &m) {
  static const char *const names[] = {"delta_v", "delta_phi", "phi_c", "e1", "e2", "phi_q"};
  const VssFit f = vss_fit_of(m);
  const double p[] = {f.dv, f.dphi, f.phi_c, f.e1, f.e2, f.phi_q};
  std::string s;
  for (int i = 0; i < 6; ++i) {
    s += (i ? ", " : "") + std::string(names[i]) + format(" = %.12g", p[i]);
    if (m.vss_source == scene::JammingVss::file && std::isfinite(m.vss_error[i]))
      s += format(" +- %.3g", m.vss_error[i]);
  }
  return s + format("; e3 = %.12g (continuity at phi_c)", f.e3);
}

double mean_of(const std::vector<double> &x) {
  double s = 0.0;
  for (double y : x)
    s += y;
  return s / static_cast<double>(x.size());
}

} // namespace

std::vector<std::string> describe_jamming(const scene::Scene &scene) {
  const scene::Continuum &m = *scene.continuum;
  const JammingModel model(m);
  const JammingPlan p = plan_of(scene, make_jamming_plan);
  std::vector<std::string> out;
  out.push_back("engine continuum: jamming model phi_t + (phi v)_x = D phi_xx, v_t + v v_x = "
                "sigma - xi(phi) v (Kanehl (thesis) eq 6.2-6.6), D = " +
                format("%g, sigma = %g", m.diffusion, m.drive));
  out.push_back("friction: " + model.describe());
  out.push_back("v_ss parameters (eq 6.4) from " + vss_source_text(m) + ": " +
                vss_parameter_text(m));
  out.push_back("grid: " + std::to_string(m.cells) + " points x_i = i dx, dx = " +
                format("%g", p.dx) + " on [0, " + format("%g", m.length) + "), periodic");
  switch (m.initial) {
  case scene::ContinuumInitial::sine:
    out.push_back("initial: phi = " +
                  format("%g + %g sin(2 pi %g x / %g)", m.mean, m.amplitude,
                         static_cast<double>(m.mode), m.length) +
                  ", v = v_ss(phi)");
    break;
  case scene::ContinuumInitial::random:
    out.push_back("initial: phi = " +
                  format("%g + %g u_i, u_i uniform in (-1, 1), seed ", m.mean, m.amplitude) +
                  std::to_string(m.seed) + ", v = v_ss(phi)");
    break;
  case scene::ContinuumInitial::eigenmode:
    out.push_back(
        "initial: phi = " +
        format("%g + %g sum_n cos(2 pi n x / %g + theta_n) over ", m.mean, m.amplitude, m.length) +
        std::to_string(m.modes.size()) +
        " modes n, each with v on its growing eigenvector (eq 6.10-6.11), phases from "
        "seed " +
        std::to_string(m.seed));
    break;
  default:
    out.push_back(std::string("initial: the given phi") +
                  (m.velocity.empty() ? ", v = v_ss(phi)" : " and v"));
    break;
  }
  std::vector<double> phi, v;
  jamming_initial(m, phi, v);
  const double phi0 = mean_of(phi);
  const double dk = 2.0 * std::numbers::pi / m.length;
  const double k_edge = unstable_band_edge(model, phi0, 200.0 * dk + 20.0);
  if (k_edge > 0.0) {
    double best = 0.0, best_k = 0.0;
    for (int i = 1; i <= 1000; ++i) {
      const double k = k_edge * i / 1000.0;
      const double g = growth_rate(model, phi0, k).real();
      if (g > best) {
        best = g;
        best_k = k;
      }
    }
    out.push_back("stability (eq 6.11) of phi = " +
                  format("%g, v = %g: unstable band 0 < k < %.6g", phi0, model.vss(phi0), k_edge) +
                  format(" (modes n < %.4g of 2 pi n / length); fastest k = %.4g grows at %.4g",
                         k_edge / dk, best_k, best));
  } else {
    out.push_back("stability (eq 6.11) of phi = " +
                  format("%g, v = %g: homogeneous flow is linearly stable", phi0, model.vss(phi0)));
  }
  if (phi0 >= model.fit().phi_q)
    out.push_back(
        "warning: the mean phi = " +
        format("%g is at or beyond phi_q = %g, where the fit's v_ss (eq 6.4) reaches 0 and "
               "rises again: outside the range of the thesis' data (fig 6.8)",
               phi0, model.fit().phi_q));
  out.push_back("stability boundary in the (phi, drive) plane: flow at phi = " +
                format("%g is unstable to long waves for drive < %.6g (phi^2 v_ss'^2 v_ss / D)",
                       phi0, critical_drive(model, phi0)));
  out.push_back("scheme: pseudo-spectral (FFTW), 2/3 rule (modes |n| < " +
                std::to_string((m.cells + 2) / 3) +
                "), Strang splitting: exact friction relaxation, IF-RK4 transport with exact "
                "diffusion (second order in time)");
  out.push_back("time step: dt = " + format("%.6g (CFL %g: speed bound %.6g; Courant number %.4g)",
                                            p.dt, m.cfl, p.speed_bound, p.courant));
  out.push_back("time: " + format("%g", m.time) + " in " + std::to_string(p.steps) + " steps; " +
                std::to_string(m.samples) + " samples (every " + std::to_string(p.per_sample) +
                " steps) and t = 0");
  out.push_back("ranks: every rank advances the same points (no decomposition); memory about " +
                format("%.3g MiB", 40.0 * 8.0 * static_cast<double>(m.cells) / 1048576.0));
  return out;
}

namespace {

// The jamming model's fields phi, v on the pseudo-spectral solver.
class Jamming final : public FieldModel {
public:
  explicit Jamming(const scene::Scene &scene)
      : scene_(scene), p_(plan_of(scene, make_jamming_plan)), jamming_(*scene.continuum),
        n_(static_cast<std::size_t>(scene.continuum->cells)),
        solver_(jamming_, n_, scene.continuum->length), bins_(jamming_points(p_)) {
    jamming_initial(*scene.continuum, phi_, v_);
    dt = p_.dt;
    steps = p_.steps;
    per_sample = p_.per_sample;
    points = n_;
    point = "point";
    lines = describe_jamming(scene);
    fields = {{"density", &phi_}, {"velocity", &v_}};
    const scene::Continuum &m = *scene.continuum;
    const VssFit &f = jamming_.fit();
    parameters = {{"delta_v", f.dv}, {"delta_phi", f.dphi}, {"phi_c", f.phi_c},
                  {"e1", f.e1},      {"e2", f.e2},          {"phi_q", f.phi_q},
                  {"e3", f.e3},      {"drive", m.drive},    {"diffusion", m.diffusion}};
    static const char *const names[] = {"delta_v", "delta_phi", "phi_c", "e1", "e2", "phi_q"};
    if (m.vss_source == scene::JammingVss::file)
      for (int i = 0; i < 6; ++i)
        if (std::isfinite(m.vss_error[i]))
          parameters.push_back({std::string(names[i]) + "_error", m.vss_error[i]});
    parameter_texts = {{"vss_source", vss_source_text(m)}};
  }

  void step(double dt) override { solver_.step(phi_, v_, dt); }
  void check(std::int64_t step) const override {
    for (std::size_t i = 0; i < n_; ++i)
      if (!std::isfinite(phi_[i]) || !std::isfinite(v_[i]) || std::abs(v_[i]) * p_.dt > p_.dx)
        throw invariant_error(scene_.file + ": phi or v at point " + std::to_string(i) +
                              " is not finite or beyond the Courant limit at step " +
                              std::to_string(step) + format(" (phi = %g, v = %g)", phi_[i], v_[i]) +
                              "; allowed: a smaller continuum.cfl or more continuum.cells");
  }
  std::string restored_out_of_range() const override {
    for (std::size_t i = 0; i < n_; ++i) {
      // An area fraction, at which the steady velocity v_ss (eq 6.4) and so the friction
      // sigma / v_ss are finite and > 0.
      const double vss = jamming_.vss(phi_[i]);
      if (!(phi_[i] >= 0.0 && phi_[i] <= 1.0 && vss > 0.0 && std::isfinite(vss)))
        return "density[" + std::to_string(i) + "] = " + format("%.17g", phi_[i]) +
               "; allowed: an area fraction 0 to 1 at which v_ss(phi) > 0 (here " +
               format("%.6g", vss) + ")";
      if (!(std::abs(v_[i]) * p_.dt <= p_.dx))
        return "velocity[" + std::to_string(i) + "] = " + format("%.17g", v_[i]) +
               "; allowed: |v| dt <= dx, " + format("|v| <= %.17g", p_.dx / p_.dt) +
               " (the run's Courant limit)";
    }
    return {};
  }
  void sample(io::ObservablesWriter *writer, std::int64_t s, double t) override {
    if (writer == nullptr)
      return;
    if (wants(scene_, "density"))
      writer->append_profile("density", s, t, bins_, phi_, 1);
    if (wants(scene_, "velocity"))
      writer->append_profile("velocity", s, t, bins_, v_, 1);
  }
  void summary(run::Log &log, std::int64_t step) const override {
    const auto [lo, hi] = std::minmax_element(phi_.begin(), phi_.end());
    log.line(format("phi at t = %.6g: mean %.12g (mass / length), min %.6g, max %.6g",
                    static_cast<double>(step) * p_.dt, mean_of(phi_), *lo, *hi));
  }

private:
  const scene::Scene &scene_;
  const JammingPlan p_;
  const JammingModel jamming_;
  const std::size_t n_;
  std::vector<double> phi_, v_;
  JammingSolver solver_;
  const std::vector<double> bins_;
};

} // namespace

std::unique_ptr<FieldModel> make_jamming(const scene::Scene &scene) {
  return std::make_unique<Jamming>(scene);
}

} // namespace narrows::continuum
