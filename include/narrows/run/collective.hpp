// Refusal is collective: a check that fails on some ranks only ends every rank with the same
// one-line error and exit code, instead of one rank leaving while the others wait for it.
#pragma once

#include <mpi.h>

#include <functional>

namespace narrows::run {

// Runs `work` on every rank of comm, then agrees: if it threw on any rank, every rank throws
// the error of the lowest such rank (an Error with ExitCode::ok too: a run that ends early)
// (narrows::Error with its code; other exceptions become exit code 1, "internal error: ...").
// `work` must not itself end in a collective call that a failing rank would skip: throw after the
// last collective call, or wrap smaller steps.
void collectively(MPI_Comm comm, const std::function<void()> &work);

// Bytes of memory one rank may use: the machine's physical memory shared by the ranks of comm
// on this node (collective), for the refusals of scenes that would not fit.
double memory_per_rank(MPI_Comm comm);

} // namespace narrows::run
