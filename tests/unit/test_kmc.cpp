// kmc engine: transition names, [kmc] scene validation, conservation, and exactness of the
// continuous-time dynamics against the stationary state of the master equation (small L).
#include "narrows/core/error.hpp"
#include "narrows/engines/kmc/lattice.hpp"
#include "narrows/models/three_state/rates.hpp"
#include "narrows/models/three_state/theory.hpp"
#include "narrows/scene/parse.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace narrows;
using three_state::pair_code;

// ---- names ------------------------------------------------------------------------------------

TEST(KmcRates, PairKeysAndSeedLabelsAgree) {
  // w_24: target label 2 = (0,1), initial label 4 = (1,0): the hop 10 -> 01 (eq 2.5).
  const auto a = three_state::parse_pair_key("10->01");
  const auto b = three_state::parse_pair_key("w24");
  const auto c = three_state::parse_pair_key("w_24");
  ASSERT_TRUE(a && b && c);
  EXPECT_EQ(*a, (std::pair{pair_code(1, 0), pair_code(0, 1)}));
  EXPECT_EQ(*a, *b);
  EXPECT_EQ(*a, *c);
  EXPECT_EQ(three_state::pair_name(a->first, a->second), "10->01");
  EXPECT_EQ(three_state::seed_label(a->first, a->second), "w24");
  // every one of the 72 transitions round-trips through both names
  int n = 0;
  for (int from = 0; from < 9; ++from)
    for (int to = 0; to < 9; ++to) {
      if (from == to)
        continue;
      ++n;
      EXPECT_EQ(three_state::parse_pair_key(three_state::pair_name(from, to)),
                (std::pair{from, to}));
      EXPECT_EQ(three_state::parse_pair_key(three_state::seed_label(from, to)),
                (std::pair{from, to}));
    }
  EXPECT_EQ(n, 72);
  // eq 2.5: 20 -> 11 is w57 (target 11 = label 5, initial 20 = label 7)
  EXPECT_EQ(three_state::parse_pair_key("w57"), (std::pair{pair_code(2, 0), pair_code(1, 1)}));
  for (const char *bad : {"10->10", "w22", "30->01", "w0", "w10", "1->0", "10-01", "w_2"})
    EXPECT_FALSE(three_state::parse_pair_key(bad)) << bad;
}

TEST(KmcRates, BoundaryNames) {
  EXPECT_EQ(three_state::parse_site_key("0->1", true), (std::pair{0, 1}));
  EXPECT_EQ(three_state::parse_site_key("alpha1", true), (std::pair{0, 1}));
  EXPECT_EQ(three_state::parse_site_key("gamma1", true), (std::pair{1, 0}));
  EXPECT_EQ(three_state::parse_site_key("alpha3", true), (std::pair{1, 2}));
  EXPECT_EQ(three_state::parse_site_key("gamma2", true), (std::pair{2, 0}));
  EXPECT_EQ(three_state::parse_site_key("beta1", false), (std::pair{1, 0}));
  EXPECT_EQ(three_state::parse_site_key("delta2", false), (std::pair{0, 2}));
  EXPECT_FALSE(three_state::parse_site_key("beta1", true));
  EXPECT_FALSE(three_state::parse_site_key("alpha1", false));
  EXPECT_FALSE(three_state::parse_site_key("1->1", true));
}

// ---- scenes -------------------------------------------------------------------------------------

const std::string kmc_scene = R"(
[run]
engine = "kmc"
seed = 3
steps = 0

[kmc]
length = 50
boundary = "open"
rates = { "10->01" = 1.0, w42 = 0.25 }
left = { "0->1" = 0.3, gamma1 = 0.1 }
right = { "1->0" = 0.7 }
initial = { kind = "product", probabilities = [0.5, 0.5, 0.0] }
time = 100.0
warmup = 10.0
replicas = 4
)";

std::string bad_kmc(const std::string &text, const std::vector<std::string> &must_contain,
                    const std::vector<std::string> &overrides = {}) {
  try {
    scene::parse_scene(text, "run/bad.toml", overrides);
  } catch (const Error &e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.code(), ExitCode::bad_input) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_NE(msg.find("run/bad.toml"), std::string::npos) << msg;
    for (const auto &s : must_contain)
      EXPECT_NE(msg.find(s), std::string::npos) << "missing '" << s << "' in: " << msg;
    return msg;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return {};
}

std::string replace(std::string text, const std::string &from, const std::string &to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(KmcScene, ParsesTheDesignExample) {
  const auto s = scene::parse_scene(kmc_scene, "run/kmc.toml");
  ASSERT_TRUE(s.kmc);
  const auto &k = *s.kmc;
  EXPECT_EQ(s.run.engine, scene::Engine::kmc);
  EXPECT_EQ(k.length, 50);
  EXPECT_EQ(k.boundary, scene::KmcBoundary::open);
  EXPECT_EQ(k.rates[pair_code(1, 0) * 9 + pair_code(0, 1)], 1.0);
  EXPECT_EQ(k.rates[pair_code(0, 1) * 9 + pair_code(1, 0)], 0.25); // w42: 01 -> 10
  EXPECT_EQ(k.left[0 * 3 + 1], 0.3);
  EXPECT_EQ(k.left[1 * 3 + 0], 0.1);
  EXPECT_EQ(k.right[1 * 3 + 0], 0.7);
  EXPECT_EQ(k.initial, (std::array<double, 3>{0.5, 0.5, 0.0}));
  EXPECT_EQ(k.time, 100.0);
  EXPECT_EQ(k.warmup, 10.0);
  EXPECT_EQ(k.replicas, 4);
  EXPECT_EQ(s.output.observables, (std::vector<std::string>{"current", "density_profile"}));
}

TEST(KmcScene, OverridesReachKmcKeys) {
  const auto s = scene::parse_scene(kmc_scene, "run/kmc.toml",
                                    {"kmc.time=5", "kmc.boundary=periodic", "kmc.left={}",
                                     "kmc.right={}", "output.observables=[\"current\"]"});
  EXPECT_EQ(s.kmc->time, 5.0);
  EXPECT_EQ(s.kmc->boundary, scene::KmcBoundary::periodic);
  EXPECT_EQ(s.output.observables, std::vector<std::string>{"current"});
}

TEST(KmcScene, Errors) {
  bad_kmc(replace(kmc_scene, "w42", "w44"), {"kmc.rates.\"w44\"", "unknown transition", "w_ij"});
  bad_kmc(replace(kmc_scene, "w42 = 0.25", "w24 = 0.25"), {"same transition", "10->01"});
  bad_kmc(replace(kmc_scene, "gamma1", "beta1"), {"kmc.left.\"beta1\"", "alpha1-3"});
  bad_kmc(replace(kmc_scene, "= 0.7", "= -0.7"), {"kmc.right.\"1->0\"", "-0.7", ">= 0"});
  bad_kmc(replace(kmc_scene, "length = 50", "length = 1"), {"kmc.length = 1", "out of range"});
  bad_kmc(replace(kmc_scene, "\"open\"", "\"closed\""), {"kmc.boundary", "open, periodic"});
  bad_kmc(replace(kmc_scene, "\"open\"", "\"periodic\""), {"kmc.left", "needs kmc.boundary"});
  bad_kmc(replace(kmc_scene, "0.5, 0.5, 0.0", "0.5, 0.6, 0.0"),
          {"kmc.initial.probabilities", "sums to"});
  bad_kmc(replace(kmc_scene, "\"product\"", "\"wall\""), {"kmc.initial.kind", "product", "shock"});
  bad_kmc(replace(kmc_scene, "\"product\"", "\"shock\""), {"kmc.initial.probabilities", "site"});
  bad_kmc(replace(kmc_scene, "time = 100.0", "time = 0"), {"kmc.time = 0", "> 0"});
  bad_kmc(replace(kmc_scene, "time = 100.0", "tim = 1"), {"kmc.tim", "did you mean 'kmc.time'"});
  bad_kmc(replace(kmc_scene, "replicas = 4", "replicas = 0"), {"kmc.replicas = 0"});
  bad_kmc(replace(kmc_scene, "[kmc]", "[domain]\nsize = [4, 4]\n[kmc]"), {"[domain]", "mpcd"});
  bad_kmc(replace(kmc_scene, "engine = \"kmc\"", "engine = \"mpcd\"\ndimensions = 2"),
          {"[kmc]", "needs run.engine"});
  bad_kmc(kmc_scene, {"output.observables[0]", "current, density_profile"},
          {"output.observables=[\"temperature\"]"});
  bad_kmc(kmc_scene, {"kmc.rates", "no positive rate"}, {"kmc.rates={}"});
}

// ---- dynamics -----------------------------------------------------------------------------------

// Family 1 (eq 2.5): all ten charge-conserving transitions with the given rates.
scene::Kmc family1(const std::array<double, 10> &w) {
  scene::Kmc m;
  const int pairs[5][2] = {{pair_code(1, 0), pair_code(0, 1)},
                           {pair_code(2, 0), pair_code(0, 2)},
                           {pair_code(1, 2), pair_code(2, 1)},
                           {pair_code(1, 1), pair_code(0, 2)},
                           {pair_code(2, 0), pair_code(1, 1)}};
  for (int p = 0; p < 5; ++p) {
    m.rates[pairs[p][0] * 9 + pairs[p][1]] = w[2 * p];
    m.rates[pairs[p][1] * 9 + pairs[p][0]] = w[2 * p + 1];
  }
  return m;
}

TEST(KmcLattice, PeriodicFamily1ConservesCharge) {
  scene::Kmc m = family1({1.0, 0.5, 0.7, 0.2, 1.3, 0.4, 0.9, 0.6, 0.3, 1.1});
  m.length = 101;
  m.boundary = scene::KmcBoundary::periodic;
  m.initial = {0.3, 0.3, 0.4};
  kmc::Lattice lat(m, 11, 0);
  const auto q0 = lat.total_charge();
  double t = 0.0;
  for (int i = 0; i < 20; ++i) {
    t += 5.0;
    lat.run_until(t);
    EXPECT_EQ(lat.total_charge(), q0);
  }
  EXPECT_GT(lat.events(), 5000u);
}

// Continuity, bond by bond and exactly: with every bond counting its own crossings, the net
// charge Q_k moved across bond k (site k -> k+1) over a window and that across the next bond
// differ by the charge that piled up on the site between them:
// Q_k - Q_(k+1) = C(n_(k+1) at the end) - C(n_(k+1) at the start). (The default lattice derives
// the bond currents from this equation; here they are counted, so the equation is a test.)
TEST(KmcLattice, PeriodicCountedCurrentsObeyContinuityExactly) {
  scene::Kmc m = family1({1.0, 0.5, 0.7, 0.2, 1.3, 0.4, 0.9, 0.6, 0.3, 1.1});
  m.length = 101;
  m.boundary = scene::KmcBoundary::periodic;
  m.initial = {0.3, 0.3, 0.4};
  kmc::Lattice lat(m, 11, 0, {.count_every_bond = true});
  lat.run_until(100.0);
  const double window = 100.0;
  lat.start_observing(window);
  const auto start = lat.state();
  lat.run_until(100.0 + window);
  const auto end = lat.state();
  const auto r = lat.result();
  const std::size_t L = start.size();
  ASSERT_EQ(r.current.size(), L);
  std::int64_t moved = 0;
  for (std::size_t k = 0; k < L; ++k) {
    const std::size_t next = (k + 1) % L; // the site after bond k, and the bond after it
    const auto q = [&](std::size_t b) { return std::llround(r.current[b] * window); };
    EXPECT_NEAR(r.current[k] * window, static_cast<double>(q(k)), 1e-9) << "bond " << k;
    EXPECT_EQ(q(k) - q(next), m.charge[end[next]] - m.charge[start[next]]) << "bond " << k;
    moved += std::abs(q(k));
  }
  EXPECT_GT(moved, static_cast<std::int64_t>(L)); // charge really moved (569 with this seed)
}

// The currents from the continuity equation (conserving rates) equal per-bond counting.
TEST(KmcLattice, ContinuityCurrentsEqualCountedCurrents) {
  for (const auto boundary : {scene::KmcBoundary::open, scene::KmcBoundary::periodic}) {
    scene::Kmc m = family1({1.0, 0.5, 0.7, 0.2, 1.3, 0.4, 0.9, 0.6, 0.3, 1.1});
    m.length = 37;
    m.boundary = boundary;
    m.initial = {0.3, 0.3, 0.4};
    if (boundary == scene::KmcBoundary::open) {
      m.left[0 * 3 + 2] = 0.8;
      m.left[1 * 3 + 0] = 0.3;
      m.right[2 * 3 + 1] = 0.5;
      m.right[0 * 3 + 1] = 0.2;
    }
    kmc::Lattice a(m, 4, 0), b(m, 4, 0, {.count_every_bond = true});
    EXPECT_TRUE(a.conserving());
    for (auto *lat : {&a, &b}) {
      lat->run_until(5.0);
      lat->start_observing(50.0);
      lat->run_until(55.0);
    }
    const auto ra = a.result(), rb = b.result();
    EXPECT_EQ(ra.current, rb.current);
    EXPECT_EQ(ra.density, rb.density);
    EXPECT_NE(ra.mean_current, 0.0); // not vacuous
  }
  scene::Kmc m = family1({1, 1, 1, 1, 1, 1, 1, 1, 1, 1});
  m.rates[pair_code(0, 0) * 9 + pair_code(2, 2)] = 0.1; // C = n not conserved
  m.length = 5;
  EXPECT_FALSE(kmc::Lattice(m, 1, 0).conserving());
}

TEST(KmcLattice, SameSeedSameTrajectoryOtherReplicaDiffers) {
  scene::Kmc m = family1({1, 1, 1, 1, 1, 1, 1, 1, 1, 1});
  m.length = 64;
  m.initial = {0.2, 0.5, 0.3};
  m.left[0 * 3 + 1] = 0.4;
  m.right[2 * 3 + 1] = 0.6;
  kmc::Lattice a(m, 5, 2), b(m, 5, 2), c(m, 5, 3);
  a.run_until(50.0);
  b.run_until(50.0);
  c.run_until(50.0);
  EXPECT_EQ(a.state(), b.state());
  EXPECT_EQ(a.events(), b.events());
  EXPECT_NE(a.state(), c.state());
}

// The stationary distribution of the master equation on L sites, restricted to the
// configurations reachable from the empty lattice (all sites 0), by Gaussian elimination of
// pi Q = 0 with sum pi = 1.
struct Exact {
  std::vector<double> density; // [L][3]
  std::vector<double> current; // [L-1], charge C(n) = n
  double event_rate = 0.0;     // sum_c pi(c) R(c)
};

struct Move {
  int to;      // configuration after
  double rate; // rate
  int bond;    // bulk bond, or -1 at a boundary
  int dq;      // charge moved to the right across `bond`
};

std::vector<Move> moves(const scene::Kmc &m, int c) {
  const int L = static_cast<int>(m.length);
  std::vector<int> n(L);
  for (int k = L - 1, x = c; k >= 0; --k, x /= 3)
    n[k] = x % 3;
  const auto code = [&](const std::vector<int> &v) {
    int x = 0;
    for (int s : v)
      x = 3 * x + s;
    return x;
  };
  std::vector<Move> out;
  for (int k = 0; k + 1 < L; ++k) {
    const int from = 3 * n[k] + n[k + 1];
    for (int to = 0; to < 9; ++to) {
      const double r = m.rates[from * 9 + to];
      if (to == from || r <= 0)
        continue;
      auto v = n;
      v[k] = to / 3;
      v[k + 1] = to % 3;
      out.push_back({code(v), r, k, n[k] - v[k]});
    }
  }
  for (int side = 0; side < 2; ++side) {
    const int k = side == 0 ? 0 : L - 1;
    for (int s2 = 0; s2 < 3; ++s2) {
      const double r = (side == 0 ? m.left : m.right)[n[k] * 3 + s2];
      if (s2 == n[k] || r <= 0)
        continue;
      auto v = n;
      v[k] = s2;
      out.push_back({code(v), r, -1, 0});
    }
  }
  return out;
}

Exact solve_master(const scene::Kmc &m) {
  const int L = static_cast<int>(m.length);
  std::map<int, int> index; // configuration -> row
  std::vector<int> configs{0};
  index[0] = 0;
  for (std::size_t i = 0; i < configs.size(); ++i)
    for (const auto &mv : moves(m, configs[i]))
      if (!index.count(mv.to)) {
        index[mv.to] = static_cast<int>(configs.size());
        configs.push_back(mv.to);
      }
  const int N = static_cast<int>(configs.size());
  const auto at = [N](std::vector<double> &a, int r, int c) -> double & {
    return a[static_cast<std::size_t>(r) * N + c];
  };
  std::vector<double> Q(static_cast<std::size_t>(N) * N, 0.0), out_rate(N, 0.0);
  for (int i = 0; i < N; ++i)
    for (const auto &mv : moves(m, configs[i])) {
      at(Q, index[mv.to], i) += mv.rate;
      at(Q, i, i) -= mv.rate;
      out_rate[i] += mv.rate;
    }
  std::vector<double> rhs(N, 0.0);
  for (int i = 0; i < N; ++i)
    at(Q, N - 1, i) = 1.0;
  rhs[N - 1] = 1.0;
  for (int col = 0; col < N; ++col) {
    int piv = col;
    for (int r = col + 1; r < N; ++r)
      if (std::abs(at(Q, r, col)) > std::abs(at(Q, piv, col)))
        piv = r;
    for (int j = 0; j < N; ++j)
      std::swap(at(Q, col, j), at(Q, piv, j));
    std::swap(rhs[col], rhs[piv]);
    for (int r = 0; r < N; ++r) {
      const double f = r == col ? 0.0 : at(Q, r, col) / at(Q, col, col);
      if (f == 0.0)
        continue;
      for (int j = col; j < N; ++j)
        at(Q, r, j) -= f * at(Q, col, j);
      rhs[r] -= f * rhs[col];
    }
  }
  Exact e;
  e.density.assign(3 * L, 0.0);
  e.current.assign(L - 1, 0.0);
  for (int i = 0; i < N; ++i) {
    const double pi = rhs[i] / at(Q, i, i);
    for (int k = L - 1, x = configs[i]; k >= 0; --k, x /= 3)
      e.density[3 * k + x % 3] += pi;
    e.event_rate += pi * out_rate[i];
    for (const auto &mv : moves(m, configs[i]))
      if (mv.bond >= 0)
        e.current[mv.bond] += pi * mv.rate * mv.dq;
  }
  return e;
}

// Time averages of the simulation against the master equation: any error in the waiting
// times (their distribution or their dependence on the configuration) biases these.
void check_against_master(const scene::Kmc &m, int replicas, double time) {
  const Exact e = solve_master(m);
  const std::size_t L = static_cast<std::size_t>(m.length);
  std::vector<double> sd(3 * L), sd2(3 * L), sj(L - 1), sj2(L - 1);
  double se = 0, se2 = 0;
  for (int r = 0; r < replicas; ++r) {
    kmc::Lattice lat(m, 17, static_cast<std::uint64_t>(r));
    lat.run_until(10.0);
    lat.start_observing(time);
    const auto e0 = lat.events();
    lat.run_until(10.0 + time);
    const auto res = lat.result();
    for (std::size_t i = 0; i < 3 * L; ++i) {
      sd[i] += res.density[i];
      sd2[i] += res.density[i] * res.density[i];
    }
    for (std::size_t i = 0; i + 1 < L; ++i) {
      sj[i] += res.current[i];
      sj2[i] += res.current[i] * res.current[i];
    }
    const double rate = static_cast<double>(lat.events() - e0) / time;
    se += rate;
    se2 += rate * rate;
  }
  const double R = replicas;
  const auto check = [&](double s, double s2, double exact, const std::string &what) {
    const double mean = s / R;
    const double err = std::sqrt(std::max(0.0, s2 / R - mean * mean) / (R - 1));
    EXPECT_NEAR(mean, exact, 4.0 * err + 1e-12) << what << " (error " << err << ")";
  };
  for (std::size_t i = 0; i < 3 * L; ++i)
    check(sd[i], sd2[i], e.density[i],
          "P(n_" + std::to_string(i / 3 + 1) + " = " + std::to_string(i % 3) + ")");
  for (std::size_t i = 0; i + 1 < L; ++i)
    check(sj[i], sj2[i], e.current[i], "current " + std::to_string(i));
  check(se, se2, e.event_rate, "events per unit time");
}

TEST(KmcLattice, TwoSiteTasepMatchesMasterEquation) {
  scene::Kmc m;
  m.length = 2;
  m.rates[pair_code(1, 0) * 9 + pair_code(0, 1)] = 1.0;
  m.left[0 * 3 + 1] = 0.6;
  m.right[1 * 3 + 0] = 0.35;
  m.initial = {1.0, 0.0, 0.0};
  check_against_master(m, 16, 20000.0);
}

TEST(KmcLattice, ThreeSitesAllRatesMatchMasterEquation) {
  // Family 1 bulk plus two non-conserving pair transitions and all 6 + 6 boundary rates.
  scene::Kmc m = family1({1.0, 0.5, 0.7, 0.2, 1.3, 0.4, 0.9, 0.6, 0.3, 1.1});
  m.rates[pair_code(0, 0) * 9 + pair_code(2, 2)] = 0.15;
  m.rates[pair_code(2, 1) * 9 + pair_code(0, 0)] = 0.45;
  m.length = 3;
  for (int i = 0; i < 9; ++i) {
    if (i % 4 == 0)
      continue; // diagonal
    m.left[i] = 0.1 + 0.07 * i;
    m.right[i] = 0.8 - 0.06 * i;
  }
  m.initial = {1.0 / 3, 1.0 / 3, 1.0 / 3};
  check_against_master(m, 16, 10000.0);
}

TEST(KmcTheory, TasepExactCurrent) {
  // alpha = beta = 1: Z_N = Catalan(N + 1), J = (L + 2) / (2 (2L + 1))
  for (int L : {1, 2, 5, 30})
    EXPECT_NEAR(three_state::theory::tasep_open_current(L, 1.0, 1.0),
                (L + 2.0) / (2.0 * (2 * L + 1)), 1e-12);
  // alpha + beta = 1: product measure, J = alpha beta for every L
  for (int L : {1, 3, 10, 400})
    EXPECT_NEAR(three_state::theory::tasep_open_current(L, 0.3, 0.7), 0.21, 1e-10) << L;
  // large L approaches the phase diagram
  EXPECT_NEAR(three_state::theory::tasep_open_current(2000, 0.2, 0.7), 0.16, 1e-9);
  EXPECT_NEAR(three_state::theory::tasep_open_current(2000, 0.8, 0.8), 0.25, 5e-4);
  EXPECT_EQ(three_state::theory::tasep_open_current_limit(0.7, 0.2), 0.7 * 0.0 + 0.2 * 0.8);
}

} // namespace

// The expected work of a replica is bounded by kmc.max_tries (issue 18): rates of 1e19 would
// run for ever; the limit names the numbers and can be lifted.
TEST(KmcScene, ExpectedTriesAboveMaxTriesAreRefused) {
  // 51 slots (50 sites, open) x largest total rate 1e19 x 110 time units.
  bad_kmc(replace(kmc_scene, "\"10->01\" = 1.0", "\"10->01\" = 1e19"),
          {"kmc.max_tries", "5.61e+22 expected tries per replica", "largest total rate 1e+19"});
  EXPECT_NO_THROW(scene::parse_scene(replace(kmc_scene, "\"10->01\" = 1.0", "\"10->01\" = 1e7"),
                                     "run/kmc.toml", {"kmc.max_tries=1e11"}));
  bad_kmc(kmc_scene, {"kmc.max_tries = 1e+03"}, {"kmc.max_tries=1000"});
  bad_kmc(kmc_scene, {"kmc.max_tries"}, {"kmc.max_tries=-1"});
}
