// kmc presets (issue 7, acceptance 4): Tabatabaei's derived constants, the residuals of its
// conditions, warnings when they fail, and the generated boundary rates - checked against the
// full master equation of a short open chain.
#include "narrows/models/three_state/preset.hpp"
#include "narrows/models/three_state/rates.hpp"
#include "narrows/models/three_state/shock.hpp"
#include "narrows/scene/parse.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace narrows;

namespace {

// Family 1 on the product-measure manifold (eq 2.36 holds; r = 1), as run/kmc_family1_product.
scene::Kmc family1() {
  scene::Kmc m;
  m.length = 5;
  m.boundary = scene::KmcBoundary::periodic; // open only where a test gives boundary rates
  m.preset = scene::KmcPreset::family1;
  const auto set = [&m](const char *key, double v) {
    const auto t = three_state::parse_pair_key(key);
    m.rates[t->first * 9 + t->second] = v;
  };
  set("w24", 0.2), set("w42", 1.0), set("w37", 0.5), set("w73", 1.7), set("w86", 0.8);
  set("w68", 0.3), set("w35", 0.4), set("w53", 0.5), set("w57", 0.5), set("w75", 0.6);
  return m;
}

// Family 2 on the shock manifold, as run/kmc_family2_shock (p = 1, q = 0.2, c = 0.5).
scene::Kmc family2(double h3 = 0.9) {
  scene::Kmc m;
  m.length = 5;
  m.boundary = scene::KmcBoundary::periodic;
  m.preset = scene::KmcPreset::family2;
  m.c = 0.5;
  m.rates = three_state::family2_rates({0.15, 0.1, h3, 0.5, 0.5, 0.8},
                                       {0.1, 0.1, 0.1, 0.2, 0.2, 0.2, 0.1, 0.1, 0.1}, m.c);
  return m;
}

bool has_warning(const three_state::PresetReport &rep, const std::string &part) {
  for (const auto &w : rep.warnings)
    if (w.find(part) != std::string::npos)
      return true;
  return false;
}

// Stationarity defect |G P| (max over configurations) of the product measure p on an open
// chain of L sites, from the full master equation (3^L states).
double master_equation_defect(const scene::Kmc &m, const std::array<double, 3> &p) {
  const int L = static_cast<int>(m.length);
  int states = 1;
  for (int i = 0; i < L; ++i)
    states *= 3;
  const auto digit = [](int x, int k) {
    for (int i = 0; i < k; ++i)
      x /= 3;
    return x % 3;
  };
  std::vector<int> pow3(L + 1, 1);
  for (int i = 1; i <= L; ++i)
    pow3[i] = 3 * pow3[i - 1];
  std::vector<double> P(states), GP(states, 0.0);
  for (int x = 0; x < states; ++x) {
    P[x] = 1.0;
    for (int k = 0; k < L; ++k)
      P[x] *= p[digit(x, k)];
  }
  const auto move = [&](int from, int to, double rate) {
    GP[to] += rate * P[from];
    GP[from] -= rate * P[from];
  };
  for (int x = 0; x < states; ++x) {
    for (int k = 0; k + 1 < L; ++k) {
      const int a = digit(x, k), b = digit(x, k + 1);
      for (int to = 0; to < 9; ++to) {
        const double w = m.rates[(3 * a + b) * 9 + to];
        if (w > 0.0)
          move(x, x + (to / 3 - a) * pow3[k] + (to % 3 - b) * pow3[k + 1], w);
      }
    }
    for (int side = 0; side < 2; ++side) {
      const int k = side == 0 ? 0 : L - 1;
      const int s = digit(x, k);
      for (int to = 0; to < 3; ++to) {
        const double w = (side == 0 ? m.left : m.right)[s * 3 + to];
        if (w > 0.0 && to != s)
          move(x, x + (to - s) * pow3[k], w);
      }
    }
  }
  double defect = 0.0;
  for (double g : GP)
    defect = std::max(defect, std::abs(g));
  return defect;
}

} // namespace

TEST(KmcPresets, Family1ConstantsMatchTheSeed) {
  const scene::Kmc m = family1();
  const auto p = three_state::preset_marginal(m.preset, three_state::family1_ratio(m.rates), 0.8);
  const auto fit = three_state::bulk_fit(m.rates, p, three_state::vacancy_state(m.preset));
  EXPECT_LT(fit.residual, 1e-14);
  EXPECT_NEAR(fit.d[0], 0.2 - 1.0, 1e-12);                    // F = w24 - w42 (eq 2.33)
  EXPECT_NEAR(fit.d[2], 0.8 - 0.3, 1e-12);                    // F' = w86 - w68 (eq 2.34)
  EXPECT_DOUBLE_EQ(three_state::family1_ratio(m.rates), 1.0); // (0.4 + 0.6) / (0.5 + 0.5)
  // eq 2.47 and 2.48 agree on the manifold
  scene::Kmc mz = m;
  mz.fugacity = {0.8};
  const auto rep = three_state::analyse(mz);
  EXPECT_TRUE(rep.warnings.empty());
  EXPECT_NEAR(rep.branches[0].current, rep.branches[0].current_247, 1e-12);
}

TEST(KmcPresets, Family2ConstantsMatchTheSeed) {
  const scene::Kmc m = family2();
  const auto p = three_state::preset_marginal(m.preset, m.c, 0.2);
  const auto fit = three_state::bulk_fit(m.rates, p, three_state::vacancy_state(m.preset));
  scene::Kmc mz = m;
  mz.fugacity = {0.2, 1.0};
  const auto rep = three_state::analyse(mz);
  EXPECT_TRUE(rep.warnings.empty()) << rep.warnings.front();
  EXPECT_LT(fit.residual, 1e-14);
  EXPECT_NEAR(fit.d[1], -rep.f, 1e-12);  // d(A) = -E (eq 2.93)
  EXPECT_NEAR(fit.d[2], -rep.fp, 1e-12); // d(B) = -E'
  // eq 2.115-2.116 from the shock hopping rates eq 2.112-2.113
  EXPECT_NEAR(rep.v_s, rep.d1 - rep.d2, 1e-12);
  EXPECT_NEAR(rep.d_s, 0.5 * (rep.d1 + rep.d2), 1e-12);
}

TEST(KmcPresets, WarnsWithResidualsOffTheManifolds) {
  scene::Kmc m = family1();
  const auto t = three_state::parse_pair_key("w73");
  m.rates[t->first * 9 + t->second] = 1.5; // eq 2.36 now misses by 0.2 (times w35 + w75 = 1)
  m.fugacity = {0.8};
  const auto rep = three_state::analyse(m);
  ASSERT_TRUE(has_warning(rep, "eq 2.36")) << rep.warnings.size();
  EXPECT_NEAR(rep.residuals[0].value, -0.2, 1e-12);
  EXPECT_TRUE(has_warning(rep, "stationary in the bulk"));

  scene::Kmc m2 = family2(1.0); // h3 + c r4 = 1.1 but h6 + r4 = 1.0: off eq 2.109 by 0.1
  m2.fugacity = {0.2, 1.0};
  const auto rep2 = three_state::analyse(m2);
  EXPECT_TRUE(has_warning(rep2, "(eq 2.109) does not hold: residual 0.1"));
  EXPECT_TRUE(has_warning(rep2, "eq 2.111"));
  EXPECT_TRUE(has_warning(rep2, "eq 2.94"));

  // Boundary rates that do not fit the fugacity are reported too.
  scene::Kmc m3 = family1();
  m3.boundary = scene::KmcBoundary::open;
  m3.fugacity = {0.8};
  m3.left[0 * 3 + 1] = 1.0;
  const auto rep3 = three_state::analyse(m3);
  EXPECT_TRUE(has_warning(rep3, "left boundary rates"));
  EXPECT_TRUE(has_warning(rep3, "right boundary rates"));
}

// The generated boundary rates make the product measure an exact stationary state of the
// whole open chain: checked on the full master equation of 5 sites (243 configurations).
TEST(KmcPresets, GeneratedBoundaryRatesMakeTheProductMeasureExact) {
  for (scene::Kmc m : {family1(), family2()}) {
    m.boundary = scene::KmcBoundary::open;
    m.fugacity = {0.7};
    m.boundary_from_fugacity = true;
    m.boundary_coupling = 0.3;
    three_state::apply_preset(m, false, false);
    const auto rep = three_state::analyse(m);
    EXPECT_TRUE(rep.warnings.empty()) << rep.warnings.front();
    EXPECT_LT(master_equation_defect(m, m.initial), 1e-15);
    // and the check does detect a wrong boundary
    scene::Kmc bad = m;
    bad.left[1] += 0.1;
    EXPECT_GT(master_equation_defect(bad, bad.initial), 1e-4);
  }
}

TEST(KmcPresets, ShockPositionEstimator) {
  const std::array<double, 3> left{0.8, 0.1, 0.1}, right{1.0, 0.0, 0.0};
  // right branch all state 0: the shock sits after the last site in another state
  EXPECT_EQ(three_state::shock_position({1, 0, 2, 0, 0, 0}, left, right), 3);
  EXPECT_EQ(three_state::shock_position({0, 0, 0}, left, right), 0);
  const std::array<double, 3> lo{0.9, 0.05, 0.05}, hi{0.1, 0.45, 0.45};
  EXPECT_EQ(three_state::shock_position({0, 0, 0, 0, 1, 2, 1, 1}, lo, hi), 4);
}

TEST(KmcPresets, SceneErrorsNameTheKey) {
  const std::string head = "[run]\nengine = \"kmc\"\nsteps = 0\n[kmc]\nlength = 10\ntime = 1.0\n";
  const auto error_of = [](const std::string &text) {
    try {
      scene::parse_scene(text, "s.toml");
    } catch (const std::exception &e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_of(head + "preset = \"family1\"\nfugacity = 1.0\nrates = { w95 = 1.0 }\n")
                .find("not a transition of family 1"),
            std::string::npos);
  EXPECT_NE(error_of(head + "preset = \"family2\"\nfugacity = 1.0\nparameters = { h1 = 1.0 }\n")
                .find("kmc.parameters.c"),
            std::string::npos);
  EXPECT_NE(error_of(head + "rates = { w24 = 1.0 }\nfugacity = 1.0\n").find("kmc.fugacity"),
            std::string::npos);
  EXPECT_NE(error_of(head + "preset = \"family1\"\nrates = { w24 = 1.0 }\nfugacity = 1.0\n"
                            "initial = { kind = \"shock\", site = 3 }\n")
                .find("kmc.initial.left"),
            std::string::npos);
}
