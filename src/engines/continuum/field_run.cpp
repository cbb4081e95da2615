// The run loop of the continuum models.
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

void run_fields(const scene::Scene &scene, const run::Options &options, MPI_Comm comm,
                FieldModel &model) {
  const scene::Continuum &m = *scene.continuum;
  const std::size_t n = model.points;
  run::Shell shell(scene, options, comm, {model.steps, "continuum.time", {}});
  const int rank = shell.rank();
  std::int64_t step = 0;
  const bool restarting = shell.restarting();
  if (restarting)
    run::collectively(comm, [&] {
      const std::string &file = shell.restart_file();
      const auto dt = io::read_checkpoint_array(file, "continuum/time_step", 1, comm);
      if (dt[0] != model.dt)
        throw input_error(file + ": /continuum/time_step = " + format("%.17g", dt[0]) +
                          " but this scene's time step is " + format("%.17g", model.dt) +
                          "; allowed: the checkpoint of this scene");
      for (auto &[name, field] : model.fields) {
        *field = io::read_checkpoint_array(file, "continuum/" + name, n, comm);
        for (std::size_t i = 0; i < n; ++i)
          if (!std::isfinite((*field)[i]))
            throw input_error(file + ": /continuum/" + name + "[" + std::to_string(i) +
                              "] is not finite; allowed: finite values");
      }
      step = shell.restart_info().step;
    });

  run::Log &log = shell.open(restarting ? step : -1);
  for (const auto &line : model.lines)
    log.line(line);
  const auto time_of = [&](std::int64_t s) { return static_cast<double>(s) * model.dt; };
  if (restarting)
    log.line("restarted from " + shell.restart_file() + " at step " + std::to_string(step) +
             format(" (t = %.6g)", time_of(step)));

  std::unique_ptr<io::ObservablesWriter> writer;
  if (rank == 0)
    writer = std::make_unique<io::ObservablesWriter>(shell.output_file("observables"), scene.text);
  const auto sample = [&](std::int64_t s) {
    model.sample(writer.get(), s, time_of(s));
    if (writer)
      writer->flush();
  };
  const auto save = [&](std::int64_t s) {
    return shell.checkpoint(s, [&](const std::string &path) {
      io::CheckpointInfo info = shell.checkpoint_info(s, time_of(s));
      info.dimensions = 1;
      info.box = {m.length, 1.0, 1.0};
      std::vector<io::CheckpointArray> arrays{{"continuum/time_step", {model.dt}}};
      for (const auto &[name, field] : model.fields)
        arrays.push_back({"continuum/" + name, *field});
      io::write_checkpoint(path, info, {}, comm, arrays);
      return "step " + std::to_string(s) + format(", t = %.6g", time_of(s));
    });
  };

  if (!restarting)
    sample(0);
  const std::int64_t first = step;
  const std::string per_step = std::string(model.point) + "-steps";
  const std::string rate = per_step + "/s";
  shell.start_loop(first);
  while (step < model.steps) {
    model.step(model.dt);
    ++step;
    if (step % model.per_sample == 0) {
      model.check(step);
      sample(step);
    }
    if (shell.checkpoint_due(step))
      save(step);
    if ((step % 64 == 0 || step % model.per_sample == 0) && step < model.steps &&
        shell.stop_requested())
      break;
    shell.progress(step, static_cast<double>(n), rate.c_str());
  }
  const double seconds = shell.loop_seconds();
  const std::string last = save(step);
  if (shell.stopped()) {
    shell.finish("step " + std::to_string(step), last);
    return;
  }
  model.summary(log, step);
  const auto steps_done = static_cast<std::uint64_t>(step - first);
  shell.loop_time(seconds, steps_done, "steps", std::to_string(n) + " " + model.point + "s",
                  static_cast<double>(steps_done) * static_cast<double>(n), per_step.c_str());
}

} // namespace narrows::continuum
