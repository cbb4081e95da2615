// The hot kernel of the FHP engine: propagation (pull from the six neighbours on the
// triangular lattice) and collision (table look-up, bounce-back at solid sites) of one row.
// Two implementations with identical results: AVX-512 VBMI byte permutes (vpermi2b, 64 sites
// per instruction) when the compiler targets it (__AVX512VBMI__), and a portable loop.
#pragma once

#include <cstdint>

namespace narrows::lgca {

// One row y of n sites. Pointers address site x = 0 of a row; index -1 and n must be
// readable (the halo columns). Neighbours of site x of row y, with o = y mod 2 (odd rows sit
// half a spacing to the right): link 0 from (x-1, y), link 3 from (x+1, y), links 1, 2 from
// (x-1+o, y-1), (x+o, y-1), links 4, 5 from (x+o, y+1), (x-1+o, y+1), rest from (x, y).
struct RowUpdate {
  const std::uint8_t *below = nullptr; // row y - 1 (periodic)
  const std::uint8_t *here = nullptr;  // row y
  const std::uint8_t *above = nullptr; // row y + 1 (periodic)
  std::uint8_t *out = nullptr;         // row y after propagation and collision
  const std::uint8_t *solid = nullptr; // 0xFF at solid (bounce-back) sites, 0 else; may be null
  const std::uint64_t *chirality = nullptr; // bit x of the row: which table entry
  const std::uint8_t *table = nullptr;      // 256 entries [chirality][state] (CollisionTable::out)
  const std::uint8_t *bounce = nullptr;     // 128 entries: bounce-back
  int n = 0;
  int odd = 0; // y mod 2
};

void update_row_portable(const RowUpdate &r);
#ifdef __AVX512VBMI__
void update_row_vbmi(const RowUpdate &r);
#endif

// The fastest implementation this build has.
inline void update_row(const RowUpdate &r) {
#ifdef __AVX512VBMI__
  update_row_vbmi(r);
#else
  update_row_portable(r);
#endif
}

// Whether update_row uses the VBMI kernel.
bool vbmi_kernel();

} // namespace narrows::lgca
