// `narrows bench --continuum N`: cell updates per second of the conservation-law scheme.
#pragma once

#include <ostream>

namespace narrows::continuum {

// Times the scheme (MUSCL-MC, Rusanov, SSP-RK2) on `cells` periodic cells for Burgers and for
// the family 1 lattice-gas flux (the costliest flux: eq 2.59 solved per evaluation); prints
// cell-steps per second on one core (JSON with `json`); then the jamming model's pseudo-spectral
// step on as many points (point-steps per second), and the segregation model's RK4 step with
// two kinds on as many cells (cell-steps per second).
void run_bench(std::ostream &out, double cells, bool json);

} // namespace narrows::continuum
