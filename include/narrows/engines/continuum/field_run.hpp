// The engine every continuum model shares in the run loop (run/drive.hpp): restart of its fields
// from a checkpoint (with the time step checked), the log's description, observables at each
// sample, checkpoints of the fields, the summary and Loop time lines. A model gives its fields,
// its step, its check of the fields and what it writes at a sample and at the end.
#pragma once

#include "narrows/core/error.hpp"
#include "narrows/io/observables_writer.hpp"
#include "narrows/run/engine.hpp"
#include "narrows/run/log.hpp"
#include "narrows/scene/scene.hpp"

#include <mpi.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace narrows::continuum {

// One continuum model: its numerics, its state and what it writes (one virtual call per step).
class FieldModel {
public:
  virtual ~FieldModel() = default;

  double dt = 0.0;                // time step
  std::int64_t steps = 0;         // steps of the whole run
  std::int64_t per_sample = 1;    // steps between samples
  std::size_t points = 0;         // grid points (cells) of every field
  const char *point = "cell";     // what a grid point is called in the log ("cell", "point")
  std::vector<std::string> lines; // the description the log opens with
  // The state, checkpointed as /continuum/<name> and restored on a restart (names in order).
  std::vector<std::pair<std::string, std::vector<double> *>> fields;
  // Resolved model parameters, written as attributes of /parameters/continuum of the
  // observables file (numbers and strings; empty: no group).
  std::vector<std::pair<std::string, double>> parameters;
  std::vector<std::pair<std::string, std::string>> parameter_texts;

  virtual void step(double dt) = 0;
  // Throws invariant_error if the fields are no longer sound at this step.
  virtual void check(std::int64_t step) const = 0;
  // On a restart, after the fields were read (finite): the first value outside the model's range
  // as "<field>[i] = value; allowed: ...", naming what the model keeps (empty: all in range).
  virtual std::string restored_out_of_range() const { return {}; }
  // At a sample, on every rank; `writer` is rank 0's (nullptr elsewhere).
  virtual void sample(io::ObservablesWriter *writer, std::int64_t step, double t) = 0;
  // The lines the log ends with after the last step (not after a stop signal).
  virtual void summary(run::Log &log, std::int64_t step) const = 0;
};

// The engine of `narrows run` over a continuum model. Every rank advances the same points (1D,
// no decomposition) and rank 0 writes.
std::unique_ptr<run::Engine> field_engine(const scene::Scene &scene, MPI_Comm comm,
                                          std::unique_ptr<FieldModel> model);

// Bytes one rank holds for the model's grid (every rank advances the whole grid): the figure
// `check` prints. check_memory refuses (collective, one line naming continuum.cells) a grid
// that exceeds this rank's share of the machine's memory, before anything is allocated.
double memory_bytes(const scene::Continuum &m);
void check_memory(const scene::Scene &scene, MPI_Comm comm);

// Small helpers of the model drivers: printf-style text of up to four numbers; whether
// output.observables lists `name`; the model's plan, its refusal naming the scene file.
std::string format(const char *format, double a, double b = 0.0, double c = 0.0, double d = 0.0);
bool wants(const scene::Scene &scene, const char *name);
template <class MakePlan> auto plan_of(const scene::Scene &scene, MakePlan make) {
  try {
    return make(*scene.continuum);
  } catch (const Error &e) {
    throw input_error(scene.file + ": " + e.what());
  }
}

} // namespace narrows::continuum
