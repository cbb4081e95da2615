// The engine of the continuum models in the run loop.
#include "narrows/engines/continuum/field_run.hpp"

#include "narrows/core/error.hpp"
#include "narrows/io/checkpoint.hpp"
#include "narrows/run/collective.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

namespace narrows::continuum {

std::string format(const char *format, double a, double b, double c, double d) {
  char buf[400];
  std::snprintf(buf, sizeof buf, format, a, b, c, d);
  return buf;
}

bool wants(const scene::Scene &scene, const char *name) {
  const auto &o = scene.output.observables;
  return std::find(o.begin(), o.end(), name) != o.end();
}

double memory_bytes(const scene::Continuum &m) {
  const auto cells = static_cast<double>(m.cells);
  switch (m.model) {
  case scene::ContinuumModel::jamming:
    return 40.0 * 8.0 * cells; // phi, v and the spectral solver's stages
  case scene::ContinuumModel::segregation:
    return 8.0 * 8.0 * cells * static_cast<double>(m.segregation.kinds.size());
  default:
    return 7.0 * 8.0 * cells; // the density and the scheme's work arrays
  }
}

void check_memory(const scene::Scene &scene, MPI_Comm comm) {
  const double need = memory_bytes(*scene.continuum), have = run::memory_per_rank(comm);
  run::collectively(comm, [&] { // nodes may differ in memory: every rank refuses alike
    if (need > have)
      throw input_error(scene.file + ": continuum.cells = " +
                        std::to_string(scene.continuum->cells) + " needs about " +
                        format("%.3g MiB per rank (every rank holds the whole grid), this machine "
                               "has %.3g MiB per rank",
                               need / 1048576.0, have / 1048576.0) +
                        "; allowed: fewer continuum.cells or fewer ranks per node");
  });
}

namespace {

class FieldEngine final : public run::Engine {
public:
  FieldEngine(const scene::Scene &scene, MPI_Comm comm, std::unique_ptr<FieldModel> model)
      : scene_(scene), comm_(comm), model_(std::move(model)),
        per_step_(std::string(model_->point) + "-steps"), rate_(per_step_ + "/s") {}

  run::RunSpan span() const override { return {model_->steps, "continuum.time", {}}; }

  void start(run::Shell &shell) override {
    if (!shell.restarting())
      return;
    FieldModel &model = *model_;
    const std::size_t n = model.points;
    run::collectively(comm_, [&] {
      const std::string &file = shell.restart_file();
      const auto dt = io::read_checkpoint_array(file, "continuum/time_step", 1, comm_);
      if (dt[0] != model.dt)
        throw input_error(file + ": /continuum/time_step = " + format("%.17g", dt[0]) +
                          " but this scene's time step is " + format("%.17g", model.dt) +
                          "; allowed: the checkpoint of this scene");
      // The time is the step's (time_of writes it so): a step edited alone is refused.
      const io::CheckpointInfo &info = shell.restart_info();
      if (info.time != time_of(info.step))
        throw input_error(file + ": /parameters/time = " + format("%.17g", info.time) +
                          " but /parameters/step = " + std::to_string(info.step) +
                          format(" is t = %.17g", time_of(info.step)) +
                          "; allowed: /parameters/time = /parameters/step x "
                          "/continuum/time_step (one state)");
      for (auto &[name, field] : model.fields) {
        *field = io::read_checkpoint_array(file, "continuum/" + name, n, comm_);
        for (std::size_t i = 0; i < n; ++i)
          if (!std::isfinite((*field)[i]))
            throw input_error(file + ": /continuum/" + name + "[" + std::to_string(i) +
                              "] is not finite; allowed: finite values");
      }
      if (const std::string bad = model.restored_out_of_range(); !bad.empty())
        throw input_error(file + ": /continuum/" + bad);
      step_ = shell.restart_info().step;
    });
  }

  void open(run::Shell &shell, run::Log &log) override {
    for (const auto &line : model_->lines)
      log.line(line);
    if (shell.restarting())
      log.line("restarted from " + shell.restart_file() + " at step " + std::to_string(step_) +
               format(" (t = %.6g)", time_of(step_)));
    if (shell.rank() == 0)
      writer_ =
          std::make_unique<io::ObservablesWriter>(shell.output_file("observables"), scene_.text);
    if (writer_ && !(model_->parameters.empty() && model_->parameter_texts.empty()))
      writer_->write_parameters("continuum", model_->parameters, model_->parameter_texts);
    if (!shell.restarting())
      sample();
  }

  std::int64_t step() const override { return step_; }
  bool advance() override {
    model_->step(model_->dt);
    ++step_;
    return true;
  }
  // At the model's samples, which fall on steps (its plan), not at output.every.
  bool observe_due(const run::Shell &) const override { return step_ % model_->per_sample == 0; }
  void observe() override {
    model_->check(step_);
    sample();
  }

  std::string write_checkpoint(run::Shell &shell, const std::string &path) override {
    io::CheckpointInfo info = shell.checkpoint_info(step_, time_of(step_));
    info.dimensions = 1;
    info.box = {scene_.continuum->length, 1.0, 1.0};
    std::vector<io::CheckpointArray> arrays{{"continuum/time_step", {model_->dt}}};
    for (const auto &[name, field] : model_->fields)
      arrays.push_back({"continuum/" + name, *field});
    io::write_checkpoint(path, info, {}, comm_, arrays);
    return "step " + std::to_string(step_) + format(", t = %.6g", time_of(step_));
  }

  run::Progress progress() const override {
    return {static_cast<double>(model_->points), rate_.c_str()};
  }

  void summary(run::Log &log, const run::Loop &) override { model_->summary(log, step_); }

  run::LoopTime loop_time(const run::Loop &loop) const override {
    const auto steps = static_cast<std::uint64_t>(loop.steps);
    const std::size_t n = model_->points;
    return {steps, "steps", std::to_string(n) + " " + model_->point + "s",
            static_cast<double>(steps) * static_cast<double>(n), per_step_.c_str()};
  }

private:
  double time_of(std::int64_t s) const { return static_cast<double>(s) * model_->dt; }
  void sample() {
    model_->sample(writer_.get(), step_, time_of(step_));
    if (writer_)
      writer_->flush();
  }

  const scene::Scene &scene_;
  MPI_Comm comm_;
  std::unique_ptr<FieldModel> model_;
  std::string per_step_, rate_; // "cell-steps", "cell-steps/s"
  std::int64_t step_ = 0;
  std::unique_ptr<io::ObservablesWriter> writer_;
};

} // namespace

std::unique_ptr<run::Engine> field_engine(const scene::Scene &scene, MPI_Comm comm,
                                          std::unique_ptr<FieldModel> model) {
  return std::make_unique<FieldEngine>(scene, comm, std::move(model));
}

} // namespace narrows::continuum
