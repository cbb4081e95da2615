// Engine "kmc": replicas over ranks, reduction with error bars, output, check/info, bench.
#include "narrows/kmc/driver.hpp"

#include "narrows/core/error.hpp"
#include "narrows/core/timer.hpp"
#include "narrows/engine/log.hpp"
#include "narrows/io/observables_writer.hpp"
#include "narrows/kmc/lattice.hpp"
#include "narrows/kmc/preset.hpp"
#include "narrows/kmc/rates.hpp"
#include "narrows/kmc/shock.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

namespace narrows::kmc {

namespace {

std::string fmt(const char *format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// " 10->01 (w24) = 1;" (snprintf: GCC 12 warns falsely on chains of string +).
std::string item(const std::string &name, const std::string &label, double rate) {
  char buf[96];
  std::snprintf(buf, sizeof buf, " %s (%s) = %g;", name.c_str(), label.c_str(), rate);
  return buf;
}

// One replica's numbers as one array: current, density, mean, left, right, pair states,
// shock positions.
std::vector<double> pack(const ReplicaResult &r, const std::vector<double> &shock,
                         const std::vector<double> &charge) {
  std::vector<double> v;
  v.reserve(r.current.size() + r.density.size() + 3 + r.pair.size() + shock.size() + charge.size());
  v.insert(v.end(), r.current.begin(), r.current.end());
  v.insert(v.end(), r.density.begin(), r.density.end());
  v.push_back(r.mean_current);
  v.push_back(r.current_left);
  v.push_back(r.current_right);
  v.insert(v.end(), r.pair.begin(), r.pair.end());
  v.insert(v.end(), shock.begin(), shock.end());
  v.insert(v.end(), charge.begin(), charge.end());
  return v;
}

} // namespace

Summary run_replicas(const scene::Kmc &model, std::uint64_t seed, MPI_Comm comm,
                     ReplicaOptions options) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  Summary s;
  s.replicas = model.replicas;
  const std::size_t L = static_cast<std::size_t>(model.length);
  const std::size_t bonds = model.boundary == scene::KmcBoundary::periodic ? L : L - 1;
  const std::size_t samples = model.samples > 0 ? static_cast<std::size_t>(model.samples) + 1 : 0;
  const std::size_t n_pair = options.pairs ? 9 * bonds : 0;
  const std::size_t n_charge = options.charge ? samples * L : 0;
  const std::size_t width = bonds + 3 * L + 3 + n_pair + samples + n_charge;
  for (std::size_t i = 0; i < samples; ++i)
    s.shock_time.push_back(model.time * static_cast<double>(i) / static_cast<double>(samples - 1));

  Stopwatch clock;
  std::vector<std::vector<double>> mine; // this rank's replicas, in replica order
  std::uint64_t events = 0, tries = 0;
  LatticeOptions lo;
  lo.pair_histogram = options.pairs;
  for (std::int64_t r = rank; r < model.replicas; r += ranks) {
    Lattice lattice(model, seed, static_cast<std::uint64_t>(r), lo);
    lattice.run_until(model.warmup);
    lattice.start_observing(model.time);
    std::vector<double> shock, charge;
    charge.reserve(n_charge);
    for (std::size_t i = 0; i < samples; ++i) {
      lattice.run_until(model.warmup + s.shock_time[i]);
      shock.push_back(
          static_cast<double>(shock_position(lattice.state(), model.initial, model.initial_right)));
      if (options.charge)
        for (const auto n : lattice.state())
          charge.push_back(model.charge[n]);
    }
    lattice.run_until(model.warmup + model.time);
    const ReplicaResult res = lattice.result();
    events += res.events;
    tries += res.tries;
    mine.push_back(pack(res, shock, charge));
  }
  double seconds = clock.seconds();
  MPI_Allreduce(&seconds, &s.seconds, 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(&events, &s.events, 1, MPI_UINT64_T, MPI_SUM, comm);
  MPI_Allreduce(&tries, &s.tries, 1, MPI_UINT64_T, MPI_SUM, comm);

  // Rank 0 takes the replicas in replica order (Welford's running mean and squared deviations),
  // so the sums are done in one order whatever the number of ranks. Messages from one rank
  // arrive in the order they were sent, which is replica order.
  if (rank != 0) {
    for (const auto &v : mine)
      MPI_Send(v.data(), static_cast<int>(width), MPI_DOUBLE, 0, 0, comm);
    return s;
  }
  std::vector<double> mean(width, 0.0), m2(width, 0.0), buf(width);
  std::size_t next_mine = 0;
  for (std::int64_t r = 0; r < model.replicas; ++r) {
    const int owner = static_cast<int>(r % ranks);
    const double *x = nullptr;
    if (owner == 0) {
      x = mine[next_mine++].data();
    } else {
      MPI_Recv(buf.data(), static_cast<int>(width), MPI_DOUBLE, owner, 0, comm, MPI_STATUS_IGNORE);
      x = buf.data();
    }
    const double n = static_cast<double>(r + 1);
    for (std::size_t i = 0; i < width; ++i) {
      const double d = x[i] - mean[i];
      mean[i] += d / n;
      m2[i] += d * (x[i] - mean[i]);
    }
  }
  const double R = static_cast<double>(model.replicas);
  std::vector<double> err(width, 0.0);
  if (model.replicas > 1)
    for (std::size_t i = 0; i < width; ++i)
      err[i] = std::sqrt(m2[i] / (R - 1.0) / R);
  const auto slice = [&](const std::vector<double> &v, std::size_t from, std::size_t n) {
    return std::vector<double>(v.begin() + static_cast<std::ptrdiff_t>(from),
                               v.begin() + static_cast<std::ptrdiff_t>(from + n));
  };
  s.current = slice(mean, 0, bonds);
  s.current_error = slice(err, 0, bonds);
  s.density = slice(mean, bonds, 3 * L);
  s.density_error = slice(err, bonds, 3 * L);
  const std::size_t tail = bonds + 3 * L;
  s.mean_current = mean[tail];
  s.mean_current_error = err[tail];
  s.current_left = mean[tail + 1];
  s.current_left_error = err[tail + 1];
  s.current_right = mean[tail + 2];
  s.current_right_error = err[tail + 2];
  s.pair = slice(mean, tail + 3, n_pair);
  s.pair_error = slice(err, tail + 3, n_pair);
  const std::size_t sh = tail + 3 + n_pair;
  s.shock_mean = slice(mean, sh, samples);
  s.shock_mean_error = slice(err, sh, samples);
  for (std::size_t i = 0; i < samples; ++i) {
    const double var = model.replicas > 1 ? m2[sh + i] / (R - 1.0) : 0.0;
    s.shock_var.push_back(var);
    s.shock_var_error.push_back(model.replicas > 1 ? var * std::sqrt(2.0 / (R - 1.0)) : 0.0);
  }
  s.charge = slice(mean, sh + samples, n_charge);
  s.charge_error = slice(err, sh + samples, n_charge);
  return s;
}

std::vector<std::string> describe(const scene::Scene &scene) {
  const scene::Kmc &k = *scene.kmc;
  const bool open = k.boundary == scene::KmcBoundary::open;
  std::vector<std::string> out;
  out.push_back("engine kmc: three-state lattice gas, " + std::to_string(k.length) + " sites, " +
                (open ? "open boundaries" : "periodic"));
  std::string bulk = "bulk rates:";
  for (int from = 0; from < 9; ++from)
    for (int to = 0; to < 9; ++to)
      if (k.rates[from * 9 + to] > 0.0)
        bulk += item(pair_name(from, to), seed_label(from, to), k.rates[from * 9 + to]);
  out.push_back(bulk);
  if (open)
    for (int side = 0; side < 2; ++side) {
      std::string line = side == 0 ? "left (site 1) rates:" : "right (site L) rates:";
      const auto &t = side == 0 ? k.left : k.right;
      bool any = false;
      for (int from = 0; from < 3; ++from)
        for (int to = 0; to < 3; ++to)
          if (t[from * 3 + to] > 0.0) {
            line +=
                item(site_name(from, to), boundary_label(side == 0, from, to), t[from * 3 + to]);
            any = true;
          }
      out.push_back(any ? line : line + " none");
    }
  const auto probs = [](const std::array<double, 3> &p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", p[0], p[1], p[2]);
    return std::string(buf);
  };
  if (k.initial_kind == scene::KmcInitial::shock)
    out.push_back("initial: shock measure (eq 2.23) with P(0, 1, 2) = " + probs(k.initial) +
                  " on sites 1.." + std::to_string(k.shock_site) + " and " +
                  probs(k.initial_right) + " on the rest; shock position sampled " +
                  std::to_string(k.samples) +
                  " times (maximum-likelihood split between the two measures)");
  else
    out.push_back("initial: product measure P(0, 1, 2) = " + probs(k.initial));
  for (const auto &line : analyse(k).lines)
    out.push_back(line);
  out.push_back("time: warm-up " + fmt("%g", k.warmup) + ", observed " + fmt("%g", k.time) + "; " +
                std::to_string(k.replicas) + " replica(s), seeds from (run.seed = " +
                std::to_string(scene.run.seed) + ", replica)");
  out.push_back("current counts C(n) = (" + std::to_string(k.charge[0]) + ", " +
                std::to_string(k.charge[1]) + ", " + std::to_string(k.charge[2]) +
                ") moved left to right across each bond, per unit time");
  const double bytes = static_cast<double>(k.length) * (1.0 + 32.0 + 4.0 * 8.0);
  out.push_back("memory per replica: about " + fmt("%.3g", bytes / 1048576.0) + " MiB");
  out.push_back("dynamics: continuous time, exact Exp(R) waiting times, events chosen by "
                "rejection over bonds; xoshiro256++ per replica");
  return out;
}

void run_scene(const scene::Scene &scene, const std::string &out_dir, MPI_Comm comm) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const scene::Kmc &k = *scene.kmc;
  const std::string dir = out_dir.empty() ? scene.output.dir : out_dir;
  engine::make_output_dir(dir, comm);
  engine::Log log(rank == 0, dir + "/log.txt");
  log.line("narrows " NARROWS_VERSION " run " + scene.file + " on " + std::to_string(ranks) +
           " rank(s), output in " + dir);
  for (const auto &line : describe(scene))
    log.line(line);
  for (const auto &w : analyse(k).warnings)
    log.warn(w);
  if (k.replicas == 1)
    log.warn("kmc.replicas = 1: no error bars (the *_error series are zero)");
  if (k.replicas % ranks != 0)
    log.warn(std::to_string(k.replicas) + " replicas on " + std::to_string(ranks) +
             " ranks: some ranks idle at the end");

  // Rank 0 opens the output first, so a bad directory fails before the work.
  std::unique_ptr<io::ObservablesWriter> writer;
  if (rank == 0)
    writer = std::make_unique<io::ObservablesWriter>(dir + "/observables.h5", scene.text);

  const auto &o = scene.output.observables;
  const auto wants = [&](const char *name) {
    return std::find(o.begin(), o.end(), name) != o.end();
  };
  ReplicaOptions options;
  options.pairs = wants("pair_correlation");
  options.charge = wants("charge_profile") && k.samples > 0;
  const Summary s = run_replicas(k, scene.run.seed, comm, options);

  if (rank == 0) {
    const double t = k.time;
    if (wants("current")) {
      std::vector<double> bins(s.current.size());
      for (std::size_t b = 0; b < bins.size(); ++b)
        bins[b] = static_cast<double>(b) + 1.5; // bond between sites b+1 and b+2 (1-based)
      writer->append_profile("current", 0, t, bins, s.current, 1);
      writer->append_profile("current_error", 0, t, bins, s.current_error, 1);
      writer->append_scalar("current_mean", 0, t, s.mean_current);
      writer->append_scalar("current_mean_error", 0, t, s.mean_current_error);
      if (k.boundary == scene::KmcBoundary::open) {
        const double jb[2] = {s.current_left, s.current_right};
        const double eb[2] = {s.current_left_error, s.current_right_error};
        writer->append_vector("current_boundary", 0, t, jb);
        writer->append_vector("current_boundary_error", 0, t, eb);
      }
    }
    if (wants("density_profile")) {
      std::vector<double> bins(static_cast<std::size_t>(k.length));
      for (std::size_t i = 0; i < bins.size(); ++i)
        bins[i] = static_cast<double>(i) + 1.0; // sites 1..L
      writer->append_profile("density_profile", 0, t, bins, s.density, 3);
      writer->append_profile("density_profile_error", 0, t, bins, s.density_error, 3);
    }
    if (options.pairs) {
      // Connected correlation P(n_k = a, n_(k+1) = b) - P(n_k = a) P(n_(k+1) = b) of the
      // replica means; its error is that of the pair probability (the product of two means
      // over all snapshots and replicas is far more precise).
      const std::size_t bonds = s.current.size(), L = static_cast<std::size_t>(k.length);
      std::vector<double> corr(9 * bonds), bins(bonds);
      for (std::size_t b = 0; b < bonds; ++b) {
        bins[b] = static_cast<double>(b) + 1.5;
        const std::size_t b2 = b + 1 == L ? 0 : b + 1;
        for (int c = 0; c < 9; ++c)
          corr[9 * b + c] =
              s.pair[9 * b + c] - s.density[3 * b + c / 3] * s.density[3 * b2 + c % 3];
      }
      writer->append_profile("pair_correlation", 0, t, bins, corr, 9);
      writer->append_profile("pair_correlation_error", 0, t, bins, s.pair_error, 9);
    }
    if (options.charge) {
      const std::size_t L = static_cast<std::size_t>(k.length);
      std::vector<double> bins(L);
      for (std::size_t i = 0; i < L; ++i)
        bins[i] = static_cast<double>(i) + 1.0;
      for (std::size_t i = 0; i < s.shock_time.size(); ++i) {
        const auto at = [&](const std::vector<double> &v) {
          return std::vector<double>(v.begin() + static_cast<std::ptrdiff_t>(i * L),
                                     v.begin() + static_cast<std::ptrdiff_t>((i + 1) * L));
        };
        const auto step = static_cast<std::int64_t>(i);
        writer->append_profile("charge_profile", step, s.shock_time[i], bins, at(s.charge), 1);
        writer->append_profile("charge_profile_error", step, s.shock_time[i], bins,
                               at(s.charge_error), 1);
      }
    }
    if (k.preset != scene::KmcPreset::none) {
      // The preset's hydrodynamic flux j(density) (eq 2.48 with 2.59, or eq 2.126), for plots
      // and for tools/kmc_plot.py's solver of the hydrodynamic equation (eq 2.60).
      const bool f1 = k.preset == scene::KmcPreset::family1;
      std::vector<double> dens(401), flux(401);
      for (std::size_t i = 0; i < dens.size(); ++i) {
        const double u = static_cast<double>(i) / 400.0;
        dens[i] = f1 ? -1.0 + 2.0 * u : u;
        flux[i] = hydrodynamic_flux(k, dens[i]);
      }
      writer->append_profile("current_theory", 0, t, dens, flux, 1);
      const PresetReport rep = analyse(k);
      if (rep.shock) {
        const double theory[2] = {-rep.v_s, rep.d_s}; // velocity to the right, diffusion
        writer->append_vector("shock_theory", 0, t, theory);
      }
    }
    for (std::size_t i = 0; i < s.shock_time.size(); ++i) {
      const auto step = static_cast<std::int64_t>(i);
      writer->append_scalar("shock_position", step, s.shock_time[i], s.shock_mean[i]);
      writer->append_scalar("shock_position_error", step, s.shock_time[i], s.shock_mean_error[i]);
      writer->append_scalar("shock_position_variance", step, s.shock_time[i], s.shock_var[i]);
      writer->append_scalar("shock_position_variance_error", step, s.shock_time[i],
                            s.shock_var_error[i]);
    }
    writer->flush();
  }
  if (!s.shock_time.empty() && rank == 0) {
    // Drift to the right and diffusion from the first and the last sample.
    const std::size_t n = s.shock_time.size() - 1;
    const double T = s.shock_time[n];
    const double v = (s.shock_mean[n] - s.shock_mean[0]) / T;
    const double v_err = std::hypot(s.shock_mean_error[n], s.shock_mean_error[0]) / T;
    const double D = (s.shock_var[n] - s.shock_var[0]) / (2.0 * T);
    const double D_err = std::hypot(s.shock_var_error[n], s.shock_var_error[0]) / (2.0 * T);
    char line[256];
    std::snprintf(line, sizeof line,
                  "shock: velocity to the right %.5g +- %.2g, diffusion %.5g +- %.2g (first to "
                  "last sample)",
                  v, v_err, D, D_err);
    log.line(line);
    const PresetReport rep = analyse(k);
    if (rep.shock) {
      std::snprintf(line, sizeof line,
                    "shock theory: velocity to the right %.5g, diffusion %.5g (seed v_s = %.5g "
                    "to the left, D_s = %.5g)",
                    -rep.v_s, rep.d_s, rep.v_s, rep.d_s);
      log.line(line);
    }
  }
  char buf[256];
  std::snprintf(buf, sizeof buf, "mean current per bond J = %.6g +- %.2g (%lld replicas)",
                s.mean_current, s.mean_current_error, static_cast<long long>(k.replicas));
  log.line(buf);
  std::snprintf(buf, sizeof buf, "events %llu, tries per event %.3g",
                static_cast<unsigned long long>(s.events),
                s.events ? static_cast<double>(s.tries) / static_cast<double>(s.events) : 0.0);
  log.line(buf);
  std::snprintf(buf, sizeof buf,
                "Loop time of %.4g s on %d ranks for %llu events with %lld sites x %lld "
                "replicas (%.4g events/s)",
                s.seconds, ranks, static_cast<unsigned long long>(s.events),
                static_cast<long long>(k.length), static_cast<long long>(k.replicas),
                s.seconds > 0 ? static_cast<double>(s.events) / s.seconds : 0.0);
  log.line(buf);
}

int command(const scene::Scene &scene, bool check, bool info, const std::string &restart,
            const std::string &out_dir, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (check || info) {
    if (rank == 0) {
      if (check)
        std::cout << scene.file << ": scene is valid\n";
      for (const auto &line : describe(scene))
        std::cout << line << '\n';
      for (const auto &w : analyse(*scene.kmc).warnings)
        std::cout << "warning: " << w << '\n';
    }
    return 0;
  }
  if (!restart.empty())
    throw input_error("--restart " + restart +
                      ": checkpoint/restart of engine kmc is not available in this version yet");
  run_scene(scene, out_dir, comm);
  return 0;
}

void run_bench(std::ostream &out, double sites, bool json) {
  struct Case {
    const char *name;
    scene::Kmc model;
  };
  const std::int64_t L = static_cast<std::int64_t>(sites);
  std::vector<Case> cases;
  {
    scene::Kmc m;
    m.length = L;
    m.boundary = scene::KmcBoundary::periodic;
    m.rates[pair_code(1, 0) * 9 + pair_code(0, 1)] = 1.0;
    m.initial = {0.5, 0.5, 0.0};
    cases.push_back({"tasep-periodic-half", m});
  }
  {
    // Family 1 (eq 2.5) with all ten rates 1, open, one third of each state.
    scene::Kmc m;
    m.length = L;
    const int pairs[5][2] = {{pair_code(1, 0), pair_code(0, 1)},
                             {pair_code(2, 0), pair_code(0, 2)},
                             {pair_code(1, 2), pair_code(2, 1)},
                             {pair_code(1, 1), pair_code(0, 2)},
                             {pair_code(2, 0), pair_code(1, 1)}};
    for (const auto &p : pairs) {
      m.rates[p[0] * 9 + p[1]] = 1.0;
      m.rates[p[1] * 9 + p[0]] = 1.0;
    }
    m.left[0 * 3 + 1] = 0.5;
    m.right[1 * 3 + 0] = 0.5;
    m.initial = {1.0 / 3, 1.0 / 3, 1.0 / 3};
    cases.push_back({"family1-open-all-ones", m});
  }
  if (json)
    out << "{\"kmc\": [";
  bool first = true;
  for (auto &c : cases) {
    Lattice lattice(c.model, 1, 0);
    // Warm up for ~2 events per site, then time ~2e7 events with observables on.
    const double r0 = lattice.total_rate();
    lattice.run_until(2.0 * static_cast<double>(L) / r0);
    const double span = 2.0e7 / lattice.total_rate();
    lattice.start_observing(span);
    const double t0 = lattice.time();
    const std::uint64_t e0 = lattice.events(), tr0 = lattice.tries();
    Stopwatch clock;
    lattice.run_until(t0 + span);
    const double sec = clock.seconds();
    const double ev = static_cast<double>(lattice.events() - e0);
    const double tries = static_cast<double>(lattice.tries() - tr0);
    if (json) {
      out << (first ? "" : ", ") << "{\"case\": \"" << c.name << "\", \"sites\": " << L
          << ", \"events_per_s\": " << ev / sec << ", \"tries_per_event\": " << tries / ev << "}";
    } else {
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "kmc %-24s L = %.3g: %.3g events/s on one core (%.3g tries/event, %.3g s)",
                    c.name, sites, ev / sec, tries / ev, sec);
      out << buf << '\n';
    }
    first = false;
  }
  if (json)
    out << "]}\n";
}

} // namespace narrows::kmc
