// Refusal is collective: a check that fails on some ranks only ends every rank with the same
// one-line error and exit code, instead of one rank leaving while the others wait for it.
#pragma once

#include <mpi.h>

#include <functional>
#include <string>

namespace narrows::run {

// Runs `work` on every rank of comm, then agrees: if it threw on any rank, every rank throws
// the error of the lowest such rank (an Error with ExitCode::ok too: a run that ends early)
// (narrows::Error with its code; other exceptions become exit code 1, "internal error: ...").
// `work` must not itself end in a collective call that a failing rank would skip: throw after the
// last collective call, or wrap smaller steps.
void collectively(MPI_Comm comm, const std::function<void()> &work);

// A failure that only some ranks see, inside a step where the others wait in a message for
// them: one line on stderr and MPI_Abort, however many ranks fail at once. The failing ranks
// claim the line by an atomic increment of a counter on rank 0 (one-sided MPI, passive target:
// no rank that did not fail takes part, so none can block it); the first prints the line and
// aborts, the later ones print nothing and wait for that abort (aborting themselves after
// `grace_seconds`, should it not come). Without open_abort_line (or on 1 rank) every caller
// prints. open_ and close_abort_line are collective over MPI_COMM_WORLD: after MPI_Init and
// before MPI_Finalize.
void open_abort_line();
void close_abort_line();
[[noreturn]] void abort_with_line(MPI_Comm comm, const std::string &line, int code,
                                  double grace_seconds = 10.0);

// Bytes of memory one rank may use: the machine's physical memory shared by the ranks of comm
// on this node (collective), for the refusals of scenes that would not fit.
double memory_per_rank(MPI_Comm comm);

} // namespace narrows::run
