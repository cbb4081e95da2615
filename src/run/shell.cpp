// The run shell: restart checks, output folder and log, triggers, checkpoints, closing lines.
#include "narrows/run/shell.hpp"

#include "narrows/core/error.hpp"
#include "narrows/run/collective.hpp"
#include "narrows/scene/canonical.hpp"
#include "narrows/scene/parse.hpp"

#include <cstdio>
#include <filesystem>
#include <system_error>

namespace narrows::run {

namespace fs = std::filesystem;

scene::Scene scene_of_checkpoint(Options &options, const std::vector<std::string> &sets,
                                 MPI_Comm comm) {
  scene::Scene s;
  collectively(comm, [&] {
    if (options.restart.empty())
      throw input_error("command line: run needs a scene file, or --restart DIR to continue a "
                        "checkpoint's own scene (see narrows --help)");
    const std::string file = io::resolve_restart(options.restart);
    const io::CheckpointInfo info = io::read_checkpoint_header(file, comm);
    s = scene::parse_scene(info.scene_text, file + ":/parameters/scene", sets);
    if (options.out_dir.empty()) {
      const std::string dir = fs::path(file).parent_path().string();
      options.out_dir = dir.empty() ? "." : dir;
    }
  });
  return s;
}

namespace {

// The two texts of the scene a checkpoint stores must be one scene: /parameters/scene (what ran)
// and /parameters/canonical_scene (what a restart compares with). Issue 35: an edited
// /parameters/scene passed while the canonical text was left as it was.
void check_stored_scenes(const io::CheckpointInfo &info, const std::string &file) {
  if (info.canonical_scene.empty()) // an older checkpoint: its scene text is all there is
    return;
  const std::string text = scene::canonical_text(info.scene_text, file + ":/parameters/scene");
  if (text == info.canonical_scene)
    return;
  const auto line_at = [](const std::string &t, std::size_t at) {
    const std::size_t begin = t.rfind('\n', at == 0 ? 0 : at - 1);
    const std::size_t from = begin == std::string::npos || at == 0 ? 0 : begin + 1;
    const std::size_t end = t.find('\n', from);
    return from >= t.size() ? std::string("(nothing)") : t.substr(from, end - from);
  };
  std::size_t at = 0;
  while (at < text.size() && at < info.canonical_scene.size() &&
         text[at] == info.canonical_scene[at])
    ++at;
  throw input_error(file + ": /parameters/scene has '" + line_at(text, at) +
                    "' where /parameters/canonical_scene has '" +
                    line_at(info.canonical_scene, at) +
                    "'; allowed: one scene in both (a checkpoint as narrows run wrote it)");
}

} // namespace

Shell::Shell(const scene::Scene &scene, const Options &options, MPI_Comm comm, RunSpan span)
    : scene_(scene), comm_(comm), span_(std::move(span)), options_(options) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &ranks_);
  dir_ = options.out_dir.empty() ? scene.output.dir : options.out_dir;
  collectively(comm, [&] {
    if (dir_.empty())
      throw input_error("--out '': an empty output directory; allowed: a directory name");
    if (options.restart.empty()) {
      const auto old = io::list_checkpoints(dir_);
      if (!old.empty() && !options.overwrite)
        throw input_error(dir_ + ": holds the checkpoints of a run (" +
                          fs::path(old.back()).filename().string() + "); allowed: --restart " +
                          dir_ +
                          " to continue it, another --out, or "
                          "--overwrite to replace it");
      return;
    }
    restart_file_ = io::resolve_restart(options.restart);
    restart_info_ = io::read_checkpoint_header(restart_file_, comm);
    check_stored_scenes(restart_info_, restart_file_);
    const std::string &stored = restart_info_.canonical_scene.empty()
                                    ? restart_info_.scene_text
                                    : restart_info_.canonical_scene;
    if (const auto d = scene::first_difference(
            scene.canonical, stored, restart_file_ + ":/parameters/scene", span_.may_change))
      throw input_error(
          scene.file + ": " + d->key + " = " + d->given + " but checkpoint " + restart_file_ +
          " has " + d->stored +
          "; allowed: the checkpoint's scene (on a restart only run.steps and "
          "output.* may change" +
          (span_.may_change.empty() ? std::string() : ", and " + span_.may_change.front()) + ")");
    if (restart_info_.step == span_.end) // a chained job resubmitted after the end: not an error
      throw Error(ExitCode::ok, restart_file_ + ": at step " + std::to_string(restart_info_.step) +
                                    " = " + span_.end_key + ": nothing to run, nothing written");
    if (restart_info_.step > span_.end)
      throw input_error(restart_file_ + ": at step " + std::to_string(restart_info_.step) +
                        " and " + span_.end_key + " = " + std::to_string(span_.end) +
                        ": nothing to run; allowed: " + span_.end_key + " above " +
                        std::to_string(restart_info_.step) + " (--set " + span_.end_key + "=...)");
  });
}

Log &Shell::open(std::int64_t continued_from) {
  std::error_code ec;
  if (rank_ == 0) {
    fs::create_directories(dir_, ec);
    if (!ec && !restarting() && options_.overwrite) {
      // The replaced run's checkpoints go, or --restart DIR would continue the old run.
      for (const auto &old : io::list_checkpoints(dir_))
        fs::remove(old, ec);
      io::prune_checkpoints(dir_, 1 << 30); // and its temporary files
    }
  }
  int failed = ec ? 1 : 0;
  MPI_Bcast(&failed, 1, MPI_INT, 0, comm_);
  if (failed)
    throw input_error(dir_ + ": cannot create output directory" +
                      (rank_ == 0 ? " (" + ec.message() + ")" : std::string()));
  char suffix[24] = "";
  if (continued_from >= 0)
    std::snprintf(suffix, sizeof suffix, "-%010lld", static_cast<long long>(continued_from));
  suffix_ = suffix;
  log_ = Log(rank_ == 0, dir_ + "/log" + suffix_ + ".txt");
  log_.line("narrows " NARROWS_VERSION " run " + scene_.file + " on " + std::to_string(ranks_) +
            " rank(s), output in " + dir_);
  return log_;
}

std::string Shell::output_file(const std::string &name) const {
  return dir_ + "/" + name + suffix_ + ".h5";
}

void Shell::start_loop(std::int64_t first) {
  first_ = first;
  clock_.restart();
  since_progress_.restart();
}

bool Shell::stop_requested() {
  stop_ = signals_.requested(comm_);
  return stop_ != 0;
}

void Shell::progress(std::int64_t step, double per_step, const char *rate_unit, const char *what) {
  if (!scene_.output.progress || since_progress_.seconds() <= 10.0)
    return;
  since_progress_.restart();
  log_.line(progress_line(step, first_, span_.end, clock_.seconds(), per_step, rate_unit, what));
}

io::CheckpointInfo Shell::checkpoint_info(std::int64_t step, double time) const {
  io::CheckpointInfo info;
  info.scene_text = scene_.text;
  info.canonical_scene = scene_.canonical;
  info.step = step;
  info.time = time;
  info.seed = scene_.run.seed;
  return info;
}

std::string Shell::checkpoint(std::int64_t step,
                              const std::function<std::string(const std::string &)> &write) {
  const std::string path = io::checkpoint_path(dir_, step);
  const std::string what = write(path);
  if (rank_ == 0)
    io::prune_checkpoints(dir_, scene_.output.checkpoint_keep);
  log_.line("checkpoint " + path + ": " + what);
  return path;
}

void Shell::finish(const std::string &where, const std::string &last) {
  if (stop_ != 0)
    log_.line(std::string("received ") + signal_name(stop_) + ": stopped after " + where +
              ", checkpoint " + last + " written; exit 0 (continue with --restart " + dir_ + ")");
}

void Shell::loop_time(double seconds, std::uint64_t count, const char *count_unit,
                      const std::string &with, double work, const char *rate_unit) {
  log_.line(loop_time_line(seconds, ranks_, count, count_unit, with, work, rate_unit));
}

} // namespace narrows::run
