// The curves of the observable collective_diffusivity (continuum/segregation_curves.hpp) against
// values computed here from the thesis' formulas, written out again, not from the model's code:
// - 2D at c_L = c_S, a_L / a_S = 2 (Kanehl (thesis) fig 5.3): the number fractions are 1/2, so
//   gamma of eq 5.20 = (2 + 4)^2 / 4 / ((4 + 16) / 2) = 0.9 at every phi, S = (1 - phi)^2 /
//   (1 - 0.1 phi) (eq 5.19 read as (1 - phi)^2), and at phi = 0.5 by hand S = 0.25 / 0.95;
// - the monodisperse limits: one kind, or two kinds of one radius (gamma = 1, Delta = 0):
//   S = (1 - phi)^2 in 2D, (1 - phi)^4 / (1 + 2 phi)^2 in 3D (eq 5.21);
// - 3D at c_L = c_S, alpha = 1/2, phi = 0.3 by hand from eq 5.22: q = x + (1 - x) alpha^3 =
//   0.5625, Delta = 0.1 (2.3 * 1.5 + 0.8 * 0.625) = 0.395, S = 0.7^4 / (1.6^2 - 0.395);
// - the off-diagonal D_C^ij / (K_d D_0^i) = phi_i / ((1 - phi_j)^2 S) of eq 5.28, eta / eta_0 =
//   (1 - phi / phi_M)^-2 of eq 5.29 (4 at phi_M / 2), the grid k phi_M / 200, the scale K_d D_0^i;
// - and that the model's current uses exactly these D_C: at the centre (gdot = 0, Poiseuille)
//   M of J = -(M phi' + b) is D_C, bit for bit.
// Tolerances: 1e-13 relative, a few roundings of double arithmetic (S is a ratio of polynomials
// of phi of degree <= 4 with coefficients of order 1; values up to ~40).
#include "narrows/engines/continuum/segregation_curves.hpp"
#include "narrows/engines/continuum/segregation_model.hpp"
#include "narrows/scene/parse.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace narrows;
using namespace narrows::continuum;

namespace {

scene::Segregation model_of(int dims, double a0, double f0, double a1 = 0.0, double f1 = 0.0) {
  char text[1000];
  int k = std::snprintf(text, sizeof text,
                        "[run]\nengine = \"continuum\"\n[continuum]\nmodel = \"segregation\"\n"
                        "dimensions = %d\nhalf_width = 40.0\ncells = 20\ncentre_speed = 0.3\n"
                        "k_d = 2.5\ntime = 1.0\n[[continuum.kind]]\nradius = %.17g\n"
                        "fraction = %.17g\ndiffusivity = 0.002\n",
                        dims, a0, f0);
  if (f1 > 0.0)
    std::snprintf(text + k, sizeof text - static_cast<std::size_t>(k),
                  "[[continuum.kind]]\nradius = %.17g\nfraction = %.17g\ndiffusivity = 0.001\n", a1,
                  f1);
  return scene::parse_scene(text, "curves.toml").continuum->segregation;
}

void near(double got, double want, const std::string &what) {
  EXPECT_NEAR(got, want, 1e-13 * std::max(1.0, std::abs(want))) << what;
}

} // namespace

TEST(SegregationCurves, Fig5_3In2DAtEqualNumberConcentrations) {
  // c_L = c_S with a_L = 2 a_S: phi_L / phi_S = 4; mean 0.1 + 0.4.
  const SegregationModel model(model_of(2, 2.0, 0.1, 4.0, 0.4));
  const double phi_half[2] = {0.1, 0.4};
  near(model.structure_factor(phi_half), 0.25 / 0.95, "S(0.5) by hand");
  const SegregationCurves c = segregation_curves(model);
  ASSERT_EQ(c.phi.size(), 200u);
  ASSERT_EQ(c.value.size(), 200u * 4);
  near(c.composition[0], 0.2, "f_S");
  near(c.composition[1], 0.8, "f_L");
  near(c.scale[0], 2.5 * 0.002, "K_d D_0^S");
  near(c.scale[1], 2.5 * 0.001, "K_d D_0^L");
  for (std::size_t k = 0; k < 200; ++k) {
    const double phi = 0.82 * static_cast<double>(k) / 200.0;
    near(c.phi[k], phi, "grid");
    const double s = (1.0 - phi) * (1.0 - phi) / (1.0 - 0.1 * phi);
    const std::string at = " at phi = " + std::to_string(phi);
    near(c.structure[k], s, "S" + at);
    near(c.value[k * 4 + 0], 1.0 / s, "D_C^SS" + at);
    near(c.value[k * 4 + 3], 1.0 / s, "D_C^LL" + at);
    near(c.value[k * 4 + 1], 0.2 * phi / ((1.0 - 0.8 * phi) * (1.0 - 0.8 * phi) * s),
         "D_C^SL" + at);
    near(c.value[k * 4 + 2], 0.8 * phi / ((1.0 - 0.2 * phi) * (1.0 - 0.2 * phi) * s),
         "D_C^LS" + at);
    const double u = 1.0 - phi / 0.82;
    near(c.viscosity[k], 1.0 / (u * u), "eta" + at);
  }
  near(c.viscosity[100], 4.0, "eta(phi_M / 2) = 4 eta_0");
  EXPECT_LT(c.phi.back(), 0.82);
  std::printf("fig 5.3: D_C / (K_d D_0) = %.4f at phi = %.4f, %.4f at %.4f, %.4f at %.4f\n",
              c.value[61 * 4], c.phi[61], c.value[122 * 4], c.phi[122], c.value[199 * 4],
              c.phi[199]);
}

TEST(SegregationCurves, MonodisperseLimits) {
  for (const int dims : {2, 3}) {
    const double phi_m = dims == 2 ? 0.82 : 0.64;
    const SegregationModel one(model_of(dims, 2.0, 0.3));
    const SegregationModel same(model_of(dims, 2.0, 0.1, 2.0, 0.2)); // two kinds, one radius
    const SegregationCurves a = segregation_curves(one), b = segregation_curves(same);
    ASSERT_EQ(a.value.size(), 200u);
    ASSERT_EQ(b.value.size(), 800u);
    for (std::size_t k = 0; k < 200; ++k) {
      const double phi = phi_m * static_cast<double>(k) / 200.0;
      const double s = dims == 2 ? (1.0 - phi) * (1.0 - phi)
                                 : std::pow(1.0 - phi, 4) / ((1.0 + 2.0 * phi) * (1.0 + 2.0 * phi));
      const std::string at = std::to_string(dims) + "D at phi = " + std::to_string(phi);
      near(a.structure[k], s, "one kind " + at);
      near(a.value[k], 1.0 / s, "one kind " + at);
      near(b.structure[k], s, "two kinds of one radius " + at);
      near(b.value[k * 4 + 3], 1.0 / s, "two kinds of one radius " + at);
    }
  }
}

TEST(SegregationCurves, ThreeDimensionsByHand) {
  // c_L = c_S, a_L = 2 a_S in 3D: phi_L / phi_S = 8; phi = 0.3.
  const SegregationModel model(model_of(3, 2.0, 0.3 / 9.0, 4.0, 2.4 / 9.0));
  const double phi[2] = {0.3 / 9.0, 2.4 / 9.0};
  near(model.structure_factor(phi), 0.2401 / (2.56 - 0.395), "S(0.3) by hand");
}

TEST(SegregationCurves, TheCurrentUsesTheseDiffusivities) {
  const SegregationModel model(model_of(2, 2.0, 0.1, 4.0, 0.4));
  const double phi[2] = {0.2, 0.35};
  double dc[4], m[4], b[2];
  model.collective_diffusivity(phi, dc);
  model.coefficients(phi, 0.0, m, b);
  for (int i = 0; i < 4; ++i)
    EXPECT_EQ(m[i], dc[i]) << i;
  const double s = model.structure_factor(phi);
  near(dc[0], 2.5 * 0.002 / s, "D_C^SS");
  near(dc[1], 2.5 * 0.002 / s * 0.2 / (0.65 * 0.65), "D_C^SL");
}
