// The one run loop of every engine (run/engine.hpp), over the run shell (run/shell.hpp).
#pragma once

#include "narrows/run/engine.hpp"
#include "narrows/run/shell.hpp"

namespace narrows::run {

// `narrows run` of one engine in the shell made for it (Shell(scene, options, comm,
// engine.span())): the state (engine.start), the folder and log (shell.open, engine.open),
// then every step in this order:
//   advance; observables (if due); trajectory frame (if due); stop signal (collective: on a
//   signal the loop ends here); checkpoint (if due); progress line
// and at the end: the engine's closing lines (finish), the last checkpoint, the line of a stop
// signal, the results of a complete run (summary) and the "Loop time" line.
void drive(Engine &engine, Shell &shell);

} // namespace narrows::run
