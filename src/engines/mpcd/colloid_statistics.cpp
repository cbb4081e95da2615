// The colloid statistics of an MPCD run (see the header).
#include "narrows/engines/mpcd/colloid_statistics.hpp"

#include "narrows/core/error.hpp"

#include <algorithm>
#include <cmath>
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
  if (kde_wanted_) {
    const double ly = box.length[1];
    const double bins = std::clamp(std::ceil(4.0 * ly / spec.kde_width), 8.0, 100000.0);
    kde_.emplace(spec.kind_count(), ly, !box.walls_y, spec.kde_width,
                 static_cast<std::size_t>(bins), multiples(from_, s.run.steps, s.output.every));
  }
}

void ColloidStatistics::after_step(const MpcdSimulation &sim) {
  if (!correlations_wanted_ || sim.step() < from_ || sim.step() % every_ != 0)
    return;
  const colloids::Colloids c = sim.gather_colloids(); // collective
  if (accumulate_)
    correlations_->add(c, period_);
}

void ColloidStatistics::on_observe(const MpcdSimulation &sim) {
  if (!kde_wanted_ || sim.step() < from_)
    return;
  const colloids::Colloids c = sim.gather_colloids(); // collective
  if (accumulate_)
    kde_->add(c.x[1], kind_);
}

std::vector<io::CheckpointArray> ColloidStatistics::checkpoint_arrays() const {
  std::vector<io::CheckpointArray> out;
  if (correlations_)
    out.push_back({"colloid_statistics/correlations",
                   accumulate_ ? correlations_->state() : std::vector<double>{}});
  if (kde_)
    out.push_back(
        {"colloid_statistics/density_kde", accumulate_ ? kde_->state() : std::vector<double>{}});
  return out;
}

void ColloidStatistics::restore(const std::string &checkpoint, MPI_Comm comm) {
  const auto take = [&](const std::string &name, auto &accumulator) {
    if (!accumulator || !io::has_checkpoint_array(checkpoint, name, comm))
      return;
    const auto values =
        io::read_checkpoint_array(checkpoint, name, accumulator->state().size(), comm);
    if (!accumulator->restore(values))
      throw input_error(checkpoint + ": /" + name +
                        " holds sample counts that are not whole numbers >= 0; allowed: the "
                        "sums of a run of this scene");
  };
  take("colloid_statistics/correlations", correlations_);
  take("colloid_statistics/density_kde", kde_);
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
  if (kde_) {
    std::vector<double> per_kind(*std::max_element(kind_.begin(), kind_.end()) + 1, 0.0);
    for (const std::size_t k : kind_)
      per_kind[k] += 1.0;
    writer.write_result("density_kde", step, time, kde_->value(),
                        {{"error", kde_->error()},
                         {"bins", kde_->centres()},
                         {"width", {kde_->width()}},
                         {"counts", per_kind},
                         {"samples", {static_cast<double>(kde_->samples())}}},
                        {per_kind.size(), kde_->bins()}, {"error"});
  }
}

} // namespace narrows::mpcd
