// continuum.mu / vss / vss_fit of the jamming model (see parse_jamming_vss.hpp).
#include "parse_jamming_vss.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

namespace narrows::scene::detail {

namespace {

std::string number_text(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

const char *const vss_allowed_ranges =
    "delta_v >= 0, delta_phi > 0, 0 < phi_c < phi_q <= 1, e1 > 0, e1 + e2 phi_c > 0 (v_ss > 0 "
    "below phi_q)";

// The ranges of eq 6.4's parameters: v_ss positive on [0, phi_q) (the friction sigma / v_ss
// finite), a step of positive width, phi_c < phi_q (the parabola's minimum beyond the step).
// `where(i)` names parameter i in the message.
template <class Where>
void check_ranges(const Checker &c, const std::array<double, 6> &p, const std::string &key,
                  Where where) {
  const double dv = p[0], dphi = p[1], phi_c = p[2], e1 = p[3], e2 = p[4], phi_q = p[5];
  const auto bad = [&](int i, const std::string &rule) {
    c.fail(key, where(i) + " = " + number_text(p[static_cast<std::size_t>(i)]) +
                    " is out of range; allowed: " + rule + " (" + vss_allowed_ranges + ")");
  };
  if (!(dv >= 0.0))
    bad(0, "delta_v >= 0");
  if (!(dphi > 0.0))
    bad(1, "delta_phi > 0");
  if (!(phi_c > 0.0 && phi_c < 1.0))
    bad(2, "0 < phi_c < 1");
  if (!(phi_q > phi_c && phi_q <= 1.0))
    bad(5, "phi_c = " + number_text(phi_c) + " < phi_q <= 1");
  if (!(e1 > 0.0))
    bad(3, "e1 > 0 (v_ss(0) > 0)");
  if (!(e1 + e2 * phi_c > 0.0))
    bad(4, "e1 + e2 phi_c > 0 (v_ss > 0 at phi_c; e1 + e2 phi_c = " + number_text(e1 + e2 * phi_c) +
               ")");
}

void parse_table(const Checker &c, const toml::value &v, Continuum &out) {
  const std::string allowed = "a table { delta_v, delta_phi, phi_c, e1, e2, phi_q } of numbers "
                              "(the parameters of eq 6.4)";
  if (!v.is_table())
    c.wrong_type("continuum.vss", v, allowed);
  for (const auto &[name, x] : sorted(v)) {
    (void)x;
    bool known = false;
    for (const char *n : vss_names)
      known = known || name == n;
    if (!known)
      c.fail("continuum.vss." + name, "unknown key 'continuum.vss." + name +
                                          "'; allowed keys: delta_v, delta_phi, phi_c, e1, e2, "
                                          "phi_q");
  }
  for (std::size_t i = 0; i < 6; ++i) {
    const std::string key = std::string("continuum.vss.") + vss_names[i];
    const toml::value *x = find(&v, vss_names[i]);
    if (x == nullptr)
      c.missing(key, "a finite number (" + allowed + ")");
    out.vss[i] = c.number(*x, key, "a finite number", [](double) { return true; });
    out.vss_error[i] = std::numeric_limits<double>::quiet_NaN();
  }
  check_ranges(c, out.vss, "continuum.vss",
               [](int i) { return std::string("continuum.vss.") + vss_names[i]; });
}

void parse_file(const Checker &c, const toml::value &v, Continuum &out) {
  const std::string key = "continuum.vss_fit";
  const std::string allowed =
      "the path (relative to the scene file) of a JSON object with numbers delta_v, delta_phi, "
      "phi_c, e1, e2, phi_q (optional <name>_error), as tools/vss_fit.py writes";
  const std::string name = c.string(v, key, allowed);
  std::filesystem::path path(name);
  if (path.is_relative())
    path = std::filesystem::path(c.file()).parent_path() / path;
  const std::string head = key + " = \"" + name + "\": " + path.string();
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    c.fail(key, head + " is not a regular file; allowed: " + allowed);
  std::ifstream in(path);
  if (!in)
    c.fail(key, head + ": cannot open; allowed: " + allowed);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception &e) {
    c.fail(key, head + " is not valid JSON (" + e.what() +
                    "; NaN and Infinity are not JSON); allowed: " + allowed);
  }
  if (!j.is_object())
    c.fail(key, head + ": found a JSON " + j.type_name() + " at the top; allowed: " + allowed);
  const auto finite_number = [&](const std::string &k, bool required, double fallback) {
    const auto it = j.find(k);
    if (it == j.end()) {
      if (required)
        c.fail(key, head + " has no key \"" + k + "\"; allowed: " + allowed);
      return fallback;
    }
    if (!it->is_number())
      c.fail(key, head + ": \"" + k + "\" is " + it->dump() + " (" + it->type_name() +
                      "); allowed: a finite number");
    const double x = it->get<double>();
    if (!std::isfinite(x))
      c.fail(key,
             head + ": \"" + k + "\" = " + it->dump() + " is not finite; allowed: a finite number");
    return x;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < 6; ++i) {
    out.vss[i] = finite_number(vss_names[i], true, 0.0);
    out.vss_error[i] = finite_number(std::string(vss_names[i]) + "_error", false, nan);
    if (out.vss_error[i] < 0.0)
      c.fail(key, head + ": \"" + vss_names[i] + "_error\" = " + number_text(out.vss_error[i]) +
                      " is out of range; allowed: a number >= 0");
  }
  check_ranges(c, out.vss, key,
               [&](int i) { return head + ": \"" + std::string(vss_names[i]) + "\""; });
  out.vss_file = name;
  out.vss_path = path.string();
}

} // namespace

void parse_jamming_vss(const Checker &c, const toml::value *sec, Continuum &out) {
  const toml::value *mu = find(sec, "mu"), *vss = find(sec, "vss"), *file = find(sec, "vss_fit");
  const int given = (mu != nullptr) + (vss != nullptr) + (file != nullptr);
  if (given > 1) {
    const char *second = file != nullptr ? "vss_fit" : "vss";
    const char *first = mu != nullptr ? "mu" : "vss";
    c.fail(std::string("continuum.") + second,
           std::string("continuum.") + second + " cannot be mixed with continuum." + first +
               "; allowed: exactly one of continuum.mu (a column of Table 6.2), continuum.vss "
               "(the parameters of eq 6.4) or continuum.vss_fit (a fit file)");
  }
  if (vss != nullptr) {
    out.vss_source = JammingVss::given;
    parse_table(c, *vss, out);
  } else if (file != nullptr) {
    out.vss_source = JammingVss::file;
    parse_file(c, *file, out);
  } else if (mu != nullptr) {
    const std::vector<std::string> names{"infinity", "1", "1/2", "0"};
    const std::string list = "\"infinity\", \"1\", \"1/2\", \"0\"";
    if (!mu->is_string())
      c.wrong_type("continuum.mu", *mu, list);
    std::size_t i = 0;
    while (i < names.size() && mu->as_string().str != names[i])
      ++i;
    if (i == names.size())
      c.fail("continuum.mu", "continuum.mu = " + repr(*mu) + " is not known; allowed: " + list);
    out.fit = static_cast<JammingFit>(i);
  }
}

} // namespace narrows::scene::detail
