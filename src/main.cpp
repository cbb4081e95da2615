// The narrows command line: run, check, info, bench (README.md, "Using it"; docs/architecture.md).
#include "narrows/colloids/dem_bench.hpp"
#include "narrows/core/error.hpp"
#include "narrows/engines/continuum/bench.hpp"
#include "narrows/engines/continuum/driver.hpp"
#include "narrows/engines/kmc/driver.hpp"
#include "narrows/engines/lgca/driver.hpp"
#include "narrows/engines/mpcd/bench.hpp"
#include "narrows/engines/mpcd/driver.hpp"
#include "narrows/run/collective.hpp"
#include "narrows/run/drive.hpp"
#include "narrows/run/shell.hpp"
#include "narrows/run/stop_signals.hpp"
#include "narrows/scene/parse.hpp"

#include <CLI/CLI.hpp>
#include <mpi.h>

#include <csignal>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

int rank_of_world() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

// First line only: every user-facing error is one line.
std::string one_line(const std::string &s) {
  const auto nl = s.find('\n');
  return nl == std::string::npos ? s : s.substr(0, nl);
}

// The engines: what `check` / `info` print (after the refusals a run would make; warnings as
// "warning: ..." lines), and the engine `run` drives (run/drive.hpp).
struct EngineEntry {
  narrows::scene::Engine engine;
  std::vector<std::string> (*check)(const narrows::scene::Scene &, MPI_Comm);
  std::unique_ptr<narrows::run::Engine> (*make)(const narrows::scene::Scene &,
                                                const narrows::run::Options &, MPI_Comm);
};
const EngineEntry engines[] = {
    {narrows::scene::Engine::mpcd, narrows::mpcd::check_lines, narrows::mpcd::make_engine},
    {narrows::scene::Engine::lgca, narrows::lgca::check_lines, narrows::lgca::make_engine},
    {narrows::scene::Engine::kmc, narrows::kmc::check_lines, narrows::kmc::make_engine},
    {narrows::scene::Engine::continuum, narrows::continuum::check_lines,
     narrows::continuum::make_engine},
};

const EngineEntry &engine_of(narrows::scene::Engine engine) {
  for (const auto &e : engines)
    if (e.engine == engine)
      return e;
  throw std::logic_error("no entry in the table of engines for run.engine");
}

int main_inner(int argc, char **argv, std::optional<narrows::run::StopSignals> &signals) {
  CLI::App app{"narrows: hydrodynamics of colloids in narrow channels (MPCD, lattice gases)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string(NARROWS_VERSION));

  std::string scene_file;
  std::vector<std::string> sets;
  narrows::run::Options run_opt;
  auto *run = app.add_subcommand("run", "run a scene");
  run->add_option("scene", scene_file,
                  "scene file (TOML); with --restart it may be left out: the checkpoint's own "
                  "scene continues");
  run->add_option("--set", sets, "override a scene key: key.path=value (repeatable)");
  auto *restart_opt = run->add_option("--restart", run_opt.restart,
                                      "continue from a checkpoint file or directory (the scene "
                                      "must be the checkpoint's, but for run.steps and output.*)");
  auto *out_opt = run->add_option("--out", run_opt.out_dir,
                                  "output directory (default: output.dir of the scene)");
  run->add_flag("--overwrite", run_opt.overwrite,
                "a fresh run may replace the checkpoints of a run in the output directory");

  auto *check = app.add_subcommand("check", "validate a scene and print its pipeline");
  check->add_option("scene", scene_file, "scene file (TOML)")->required();
  check->add_option("--set", sets, "override a scene key: key.path=value (repeatable)");

  auto *info = app.add_subcommand("info", "pipeline, particle count, memory, Ma/Re/Sc");
  info->add_option("scene", scene_file, "scene file (TOML)")->required();
  info->add_option("--set", sets, "override a scene key: key.path=value (repeatable)");

  narrows::mpcd::BenchOptions bench_opt;
  auto *bench = app.add_subcommand("bench", "throughput of the hot kernels on this machine");
  bench->add_flag("--json", bench_opt.json, "print JSON");
  double kmc_sites = 0.0;
  bench->add_option("--kmc", kmc_sites, "only the kmc engine, on this many sites (e.g. 1e6)")
      ->check(CLI::PositiveNumber);
  double continuum_cells = 0.0;
  bench
      ->add_option("--continuum", continuum_cells,
                   "only the continuum engine's scheme, on this many cells (e.g. 1e5)")
      ->check(CLI::PositiveNumber);
  int lgca_sites = 0;
  bench
      ->add_option("--lgca", lgca_sites,
                   "only the lgca engine: FHP-III on an N x N lattice (e.g. 4096), 1 and all ranks")
      ->check(CLI::PositiveNumber);
  narrows::colloids::DemBenchOptions dem_opt;
  double dem_disks = 0.0;
  auto *dem =
      bench
          ->add_option(
              "--dem", dem_disks,
              "only the spring contacts (DEM) without fluid, on this many disks (e.g. 1.8e5)")
          ->check(CLI::PositiveNumber);
  bench
      ->add_option("--dem-data", dem_opt.lammps_data,
                   "with --dem: also write the packing as a LAMMPS data file here")
      ->needs(dem);
  bench
      ->add_option("--particles", bench_opt.particles,
                   "particles per case (default: beyond the cache, a working set of at least 4 "
                   "times the last-level cache; pulses-2d: the scene's 187150)")
      ->check(CLI::PositiveNumber);
  bench
      ->add_option("--angle", bench_opt.angle_deg,
                   "rotation angle of the SRD cases in degrees (default 130)")
      ->check(CLI::Range(0.0, 360.0));
  bench->add_option("--steps", bench_opt.steps, "timed steps per case (default 100)")
      ->check(CLI::PositiveNumber);
  bench->add_option("--case", bench_opt.cases,
                    "only this MPCD case (repeatable): srd-2d, srd-3d, at-2d, at+a-2d, at+a-3d, "
                    "pulses-2d (the Table 6.1 channel with its no-slip disks)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp &e) {
    if (rank_of_world() == 0)
      app.exit(e);
    return 0;
  } catch (const CLI::CallForVersion &e) {
    if (rank_of_world() == 0)
      app.exit(e);
    return 0;
  } catch (const CLI::ParseError &e) {
    throw narrows::input_error("command line: " + one_line(e.what()) + " (see narrows --help)");
  }
  for (auto *given : {restart_opt, out_opt})
    if (given->count() > 0 && given->as<std::string>().empty())
      throw narrows::input_error("command line: " + given->get_name() +
                                 " ''; allowed: a non-empty path (see narrows --help)");

  if (!*run) {
    // Only a run stops cleanly on a signal; check, info and bench end by the default action,
    // also for a signal that came while the command line was read.
    signals.reset();
    if (const int sig = narrows::run::stop_signal_received())
      std::raise(sig);
  }
  const bool root = rank_of_world() == 0;
  if (*bench && kmc_sites > 0.0) {
    if (root)
      narrows::kmc::run_bench(std::cout, kmc_sites, bench_opt.json);
    return 0;
  }
  if (*bench && continuum_cells > 0.0) {
    if (root)
      narrows::continuum::run_bench(std::cout, continuum_cells, bench_opt.json);
    return 0;
  }
  if (*bench && dem_disks > 0.0) {
    if (root) {
      dem_opt.disks = dem_disks;
      dem_opt.json = bench_opt.json;
      if (bench->get_option("--steps")->count() > 0)
        dem_opt.steps = bench_opt.steps;
      narrows::colloids::run_dem_bench(dem_opt, std::cout);
    }
    return 0;
  }
  if (*bench && lgca_sites > 0) {
    narrows::lgca::run_bench(std::cout, lgca_sites, static_cast<int>(bench_opt.steps),
                             bench_opt.json, MPI_COMM_WORLD);
    return 0;
  }
  if (*bench) {
    if (root)
      narrows::mpcd::run_bench(bench_opt, std::cout);
    return 0;
  }
  const auto scene = (*run && scene_file.empty())
                         ? narrows::run::scene_of_checkpoint(run_opt, sets, MPI_COMM_WORLD)
                         : narrows::scene::load_scene(scene_file, sets);
  const EngineEntry &engine = engine_of(scene.run.engine);
  if (*check || *info) {
    // Every rank computes the lines (a check may be collective), rank 0 prints them.
    const auto lines = engine.check(scene, MPI_COMM_WORLD);
    if (root) {
      if (*check)
        std::cout << scene.file << ": scene is valid\n";
      for (const auto &line : lines)
        std::cout << line << '\n';
    }
    return 0;
  }
  const auto run_engine = engine.make(scene, run_opt, MPI_COMM_WORLD);
  narrows::run::Shell shell(scene, run_opt, MPI_COMM_WORLD, run_engine->span());
  narrows::run::drive(*run_engine, shell);
  return 0;
}

} // namespace

int main(int argc, char **argv) {
  // The stop-signal handlers come before any work (MPI_Init alone takes a few tenths of a
  // second): a SIGTERM early in a run is kept and stops it after its first step, with a
  // checkpoint, instead of killing it by the default action.
  std::optional<narrows::run::StopSignals> signals(std::in_place);
  // A rank that alone finds a broken invariant inside a step prints its one line and ends the
  // run with MPI_Abort (the other ranks wait in the step's next message: mpcd/simulation.cpp);
  // when several find one in the same step, only the first to claim the line prints it
  // (run::abort_with_line).
  // Open MPI 4.1 then adds its own MPI_ABORT notice, which mpirun without --quiet fails to unpack
  // ("Data unpack would read past end of buffer", issue 35 item 4); quiet processes send none.
  // Not overwritten if the user set it.
  setenv("OMPI_MCA_orte_execute_quiet", "1", 0);
  MPI_Init(&argc, &argv);
  narrows::run::open_abort_line(); // one line when several ranks fail inside a step at once
  int code = 0;
  try {
    code = main_inner(argc, argv, signals);
  } catch (const narrows::Error &e) {
    if (rank_of_world() == 0)
      std::cerr << "narrows: " << e.what() << std::endl;
    code = static_cast<int>(e.code());
  } catch (const std::exception &e) {
    if (rank_of_world() == 0)
      std::cerr << "narrows: internal error: " << one_line(e.what()) << std::endl;
    code = 1;
  }
  narrows::run::close_abort_line();
  MPI_Finalize();
  return code;
}
