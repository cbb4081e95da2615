// The colloid statistics of an MPCD run (see the header).
#include "narrows/engines/mpcd/colloid_statistics.hpp"

#include "narrows/analysis/segregation_evolution.hpp"
#include "narrows/core/error.hpp"
#include "narrows/core/timer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace narrows::mpcd {

namespace {

bool wants(const scene::Scene &s, const char *name) {
  const auto &o = s.output.observables;
  return std::find(o.begin(), o.end(), name) != o.end();
}

// Multiples of `every` in [lo, hi].
std::size_t multiples(std::int64_t lo, std::int64_t hi, std::int64_t every) {
  if (hi < lo)
    return 0;
  const std::int64_t first = (lo + every - 1) / every, last = hi / every;
  return last >= first ? static_cast<std::size_t>(last - first + 1) : 0;
}

} // namespace

ColloidStatistics::ColloidStatistics(const MpcdSimulation &sim) {
  const auto &s = sim.scene();
  if (!s.colloids)
    return;
  const auto &spec = *s.colloids;
  vacf_ = wants(s, "colloid_vacf");
  diffusion_ = wants(s, "colloid_diffusion");
  msd_ = wants(s, "colloid_msd");
  angular_ = wants(s, "colloid_angular_vacf");
  correlations_wanted_ = vacf_ || diffusion_ || msd_ || angular_;
  kde_wanted_ = wants(s, "density_kde");
  velocity_wanted_ = wants(s, "colloid_velocity_profile");
  evolution_wanted_ = wants(s, "evolution");
  window_ = s.output.kde_window;
  if (!active())
    return;
  int rank = 0;
  MPI_Comm_rank(sim.comm(), &rank);
  accumulate_ = rank == 0;
  from_ = std::max(spec.statistics_from, sim.step() + 1); // the state after a step
  every_ = spec.correlation_every;
  for (std::int64_t id = 0; id < spec.count; ++id)
    kind_.push_back(spec.kind_of(static_cast<std::uint64_t>(id)));
  const auto &box = sim.box();
  for (int k = 0; k < box.dim; ++k)
    period_[k] = k == 1 && box.walls_y ? 0.0 : box.length[k];
  // Every rank holds the accumulators (their sizes, for reading a checkpoint); rank 0 fills them.
  if (correlations_wanted_)
    correlations_.emplace(
        kind_, spec.kind_count(), box.dim, static_cast<std::size_t>(spec.max_lag / every_),
        static_cast<double>(every_) * s.fluid.dt, multiples(from_, s.run.steps, every_));
  window_start_ = spec.statistics_from;
  observe_every_ = s.output.every;
  dt_ = s.fluid.dt;
  per_kind_.assign(spec.kind_count(), 0.0);
  for (const std::size_t k : kind_)
    per_kind_[k] += 1.0;
  const double ly = box.length[1];
  const auto bins =
      static_cast<std::size_t>(std::clamp(std::ceil(4.0 * ly / spec.kde_width), 8.0, 100000.0));
  if (kde_wanted_ && window_ == 0)
    kde_.emplace(spec.kind_count(), ly, !box.walls_y, spec.kde_width, bins,
                 multiples(from_, s.run.steps, s.output.every));
  if ((kde_wanted_ && window_ > 0) || velocity_wanted_)
    windows_.emplace(spec.kind_count(), ly, !box.walls_y, spec.kde_width, bins);
}

void ColloidStatistics::after_step(const MpcdSimulation &sim) {
  if (!correlations_wanted_ || sim.step() < from_ || sim.step() % every_ != 0)
    return;
  const colloids::Colloids c = sim.gather_colloids(); // collective
  if (accumulate_)
    correlations_->add(c, period_);
}

void ColloidStatistics::on_observe(const MpcdSimulation &sim, io::ObservablesWriter *writer) {
  if (!(kde_ || windows_) || sim.step() < from_)
    return;
  Stopwatch watch;
  const colloids::Colloids c = sim.gather_colloids(); // collective
  if (!accumulate_)
    return;
  if (kde_)
    kde_->add(c.x[1], kind_);
  if (!windows_)
    return;
  if (window_ == 0) { // one window, the whole run, written at the end
    windows_->add(c.x[1], c.v[0], kind_);
    return;
  }
  ++window_samples_;
  const analysis::WindowSchedule schedule{window_start_, window_, observe_every_};
  const std::int64_t t = sim.step(), w = schedule.index(t);
  if (w != open_ && windows_->samples() > 0 && writer) // a window left open by another scene
    close_window(*writer);
  open_ = w;
  windows_->add(c.x[1], c.v[0], kind_);
  sample_seconds_ += watch.seconds();
  if (schedule.closes(t) && writer) {
    watch.restart();
    close_window(*writer);
    close_seconds_ += watch.seconds();
    ++open_;
  }
}

void ColloidStatistics::close_window(io::ObservablesWriter &writer) {
  const std::int64_t end =
      analysis::WindowSchedule{window_start_, window_, observe_every_}.end(open_);
  const double time = static_cast<double>(end) * dt_;
  const std::size_t kinds = windows_->kinds(), bins = windows_->bins();
  const auto centres = windows_->centres();
  const std::vector<hsize_t> shape{kinds, bins};
  if (kde_wanted_) {
    const auto f = windows_->density();
    const double samples = static_cast<double>(windows_->samples());
    writer.append_field("density_kde", end, time, shape, f, {{"samples", {}, {&samples, 1}}},
                        {{"bins", centres}, {"width", {windows_->width()}}, {"counts", per_kind_}});
    if (evolution_wanted_) {
      if (reference_.empty())
        reference_ = f;
      // The total number density sum_k N_k F_k, and each kind's F_k alone.
      std::vector<double> c(bins, 0.0), c0(bins, 0.0), by_kind(kinds);
      for (std::size_t k = 0; k < kinds; ++k) {
        for (std::size_t j = 0; j < bins; ++j) {
          c[j] += per_kind_[k] * f[k * bins + j];
          c0[j] += per_kind_[k] * reference_[k * bins + j];
        }
        const std::span<const double> fk(f.data() + k * bins, bins),
            rk(reference_.data() + k * bins, bins);
        by_kind[k] = analysis::evolution_parameter(fk, rk);
      }
      const double delta = analysis::evolution_parameter(c, c0);
      writer.append_field("evolution", end, time, {}, {&delta, 1}, {{"by_kind", {kinds}, by_kind}},
                          {});
      delta_time_.push_back(time);
      delta_.push_back(delta);
    }
  }
  if (velocity_wanted_)
    writer.append_field("colloid_velocity_profile", end, time, shape, windows_->velocity(),
                        {{"weight", shape, windows_->weight()}}, {{"bins", centres}});
  windows_->clear();
  ++windows_closed_;
}

std::string ColloidStatistics::window_cost_line() const {
  if (window_ == 0 || !windows_ || !accumulate_ || window_samples_ == 0)
    return {};
  char text[320];
  const double closed = static_cast<double>(windows_closed_);
  std::snprintf(text, sizeof text,
                "kde windows: %.3g ms per sample on rank 0 (colloids gathered, kernel sums), %.3g "
                "ms per window closed (profiles%s written); %lld windows of %lld steps",
                1e3 * sample_seconds_ / static_cast<double>(window_samples_),
                closed > 0 ? 1e3 * close_seconds_ / closed : 0.0,
                evolution_wanted_ ? ", Delta" : "", static_cast<long long>(windows_closed_),
                static_cast<long long>(window_));
  return text;
}

std::string ColloidStatistics::steady_line() const {
  if (!evolution_wanted_ || !accumulate_)
    return {};
  const analysis::SteadyCheck s = analysis::steady_check(delta_time_, delta_);
  char text[320];
  if (!s.judged)
    std::snprintf(text, sizeof text,
                  "evolution: %zu density_kde windows, too few to judge the steady state (at "
                  "least 4)",
                  delta_.size());
  else
    std::snprintf(text, sizeof text,
                  "evolution: %s after %zu windows: Delta = %.4g at t = %.6g, slope %.3g +- %.3g "
                  "per time unit over the last %zu windows (steady when |slope| <= 2 sigma)",
                  s.steady ? "steady" : "NOT steady", delta_.size(), delta_.back(),
                  delta_time_.back(), s.slope, s.sigma, s.points);
  return text;
}

// The windows' state: the open window's index, the first window's profiles (0 and zeros before
// it closed), the number of Delta values, the window's sums.
std::vector<double> ColloidStatistics::window_state() const {
  const std::size_t n = windows_->kinds() * windows_->bins();
  std::vector<double> s{static_cast<double>(open_), reference_.empty() ? 0.0 : 1.0};
  if (reference_.empty())
    s.resize(2 + n, 0.0);
  else
    s.insert(s.end(), reference_.begin(), reference_.end());
  s.push_back(static_cast<double>(delta_.size()));
  const auto sums = windows_->state();
  s.insert(s.end(), sums.begin(), sums.end());
  return s;
}

std::vector<io::CheckpointArray> ColloidStatistics::checkpoint_arrays() const {
  std::vector<io::CheckpointArray> out;
  if (correlations_)
    out.push_back({"colloid_statistics/correlations",
                   accumulate_ ? correlations_->state() : std::vector<double>{}});
  if (kde_)
    out.push_back(
        {"colloid_statistics/density_kde", accumulate_ ? kde_->state() : std::vector<double>{}});
  if (windows_) {
    out.push_back(
        {"colloid_statistics/kernel_window", accumulate_ ? window_state() : std::vector<double>{}});
    // Delta(t) of the closed windows, after their count (never empty).
    std::vector<double> series;
    if (accumulate_) {
      series.push_back(static_cast<double>(delta_.size()));
      series.insert(series.end(), delta_time_.begin(), delta_time_.end());
      series.insert(series.end(), delta_.begin(), delta_.end());
    }
    out.push_back({"colloid_statistics/evolution", series});
  }
  return out;
}

void ColloidStatistics::restore(const std::string &checkpoint, MPI_Comm comm) {
  const auto refuse = [&](const std::string &name) {
    throw input_error(checkpoint + ": /" + name +
                      " holds sample counts that are not whole numbers >= 0; allowed: the "
                      "sums of a run of this scene");
  };
  const auto take = [&](const std::string &name, auto &accumulator) {
    if (!accumulator || !io::has_checkpoint_array(checkpoint, name, comm))
      return;
    const auto values =
        io::read_checkpoint_array(checkpoint, name, accumulator->state().size(), comm);
    if (!accumulator->restore(values))
      refuse(name);
  };
  take("colloid_statistics/correlations", correlations_);
  take("colloid_statistics/density_kde", kde_);
  const std::string window = "colloid_statistics/kernel_window",
                    series = "colloid_statistics/evolution";
  if (!windows_ || !io::has_checkpoint_array(checkpoint, window, comm))
    return;
  const std::size_t n = windows_->kinds() * windows_->bins();
  const auto s = io::read_checkpoint_array(checkpoint, window, window_state().size(), comm);
  const auto whole = [](double x) { return x >= 0.0 && x == std::floor(x); };
  if (!whole(s[0]) || !(s[1] == 0.0 || s[1] == 1.0) || !whole(s[2 + n]) ||
      !windows_->restore(
          std::vector<double>(s.begin() + 3 + static_cast<std::ptrdiff_t>(n), s.end())))
    refuse(window);
  open_ = static_cast<std::int64_t>(s[0]);
  reference_.clear();
  if (s[1] == 1.0)
    reference_.assign(s.begin() + 2, s.begin() + 2 + static_cast<std::ptrdiff_t>(n));
  const auto count = static_cast<std::size_t>(s[2 + n]);
  delta_time_.clear();
  delta_.clear();
  if (count > 0 && io::has_checkpoint_array(checkpoint, series, comm)) {
    const auto d = io::read_checkpoint_array(checkpoint, series, 1 + 2 * count, comm);
    if (d[0] != static_cast<double>(count))
      refuse(series);
    delta_time_.assign(d.begin() + 1, d.begin() + 1 + static_cast<std::ptrdiff_t>(count));
    delta_.assign(d.begin() + 1 + static_cast<std::ptrdiff_t>(count), d.end());
  }
}

void ColloidStatistics::write(io::ObservablesWriter &writer, std::int64_t step, double time) const {
  using Beside = std::vector<std::pair<std::string, std::vector<double>>>;
  if (!accumulate_)
    return;
  if (correlations_) {
    const double kinds = static_cast<double>(correlations_->kinds());
    const double samples = static_cast<double>(correlations_->samples());
    const auto put = [&](const char *name, const analysis::ColloidTimeCorrelations::Result &r,
                         Beside extra) {
      Beside beside{{"lags", r.lags},
                    {"error", r.error},
                    {"value_by_kind", r.by_kind},
                    {"error_by_kind", r.error_by_kind},
                    {"kinds", {kinds}},
                    {"samples", {samples}}};
      beside.insert(beside.end(), extra.begin(), extra.end());
      writer.write_result(name, step, time, r.value, beside);
    };
    if (vacf_)
      put("colloid_vacf", correlations_->vacf(), {});
    if (diffusion_)
      put("colloid_diffusion", correlations_->diffusion(), {});
    if (msd_)
      put("colloid_msd", correlations_->msd(), {});
    if (angular_) {
      const auto rot = correlations_->rotational_diffusion();
      put("colloid_angular_vacf", correlations_->angular_vacf(),
          {{"integral", rot.value},
           {"integral_error", rot.error},
           {"integral_by_kind", rot.by_kind}});
    }
  }
  if (kde_)
    writer.write_result("density_kde", step, time, kde_->value(),
                        {{"error", kde_->error()},
                         {"bins", kde_->centres()},
                         {"width", {kde_->width()}},
                         {"counts", per_kind_},
                         {"samples", {static_cast<double>(kde_->samples())}}},
                        {per_kind_.size(), kde_->bins()}, {"error"});
  // Without windows the velocity profile is one window, the whole run chain.
  if (velocity_wanted_ && window_ == 0) {
    const std::vector<hsize_t> shape{windows_->kinds(), windows_->bins()};
    writer.append_field("colloid_velocity_profile", step, time, shape, windows_->velocity(),
                        {{"weight", shape, windows_->weight()}}, {{"bins", windows_->centres()}});
  }
}

} // namespace narrows::mpcd
