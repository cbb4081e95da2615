// Names of the kmc transitions: bulk pair transitions "10->01" or Tabatabaei's w_ij (eq 2.1:
// i = 3 n'_k + n'_(k+1) + 1 labels the target pair, j the initial pair), and boundary site
// transitions "0->1" or Tabatabaei's alpha/gamma (left, eq 2.2) and delta/beta (right, eq 2.3).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace narrows::three_state {

// Pair code of two neighbouring states: c = 3 n_k + n_(k+1), 0..8 (Tabatabaei's label is c + 1).
constexpr int pair_code(int a, int b) { return 3 * a + b; }

std::string pair_name(int from, int to);  // pair codes -> "10->01"
std::string seed_label(int from, int to); // pair codes -> "w24"
std::string site_name(int from, int to);  // states -> "0->1"
// Tabatabaei's boundary rate name: left 0->1 "alpha1", 1->0 "gamma1", 0->2 "alpha2", 2->0
// "gamma2", 1->2 "alpha3", 2->1 "gamma3"; right likewise with delta (forward) and beta.
std::string boundary_label(bool left, int from, int to);

// {from, to} pair codes of "10->01", "w24" or "w_24"; nullopt if the key is neither or names
// no change.
std::optional<std::pair<int, int>> parse_pair_key(std::string_view key);
// {from, to} states of "0->1" or Tabatabaei's name (alpha1 ... gamma3 on the left, delta1 ...
// beta3 on the right); nullopt otherwise.
std::optional<std::pair<int, int>> parse_site_key(std::string_view key, bool left);

} // namespace narrows::three_state
