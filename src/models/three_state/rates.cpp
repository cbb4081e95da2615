// Names of the kmc transitions (see kmc/rates.hpp).
#include "narrows/models/three_state/rates.hpp"

#include <array>

namespace narrows::three_state {

namespace {

bool is_state(char c) { return c >= '0' && c <= '2'; }

// Boundary pairs of eq 2.2-2.3 in order 1, 2, 3: {forward from, forward to}.
constexpr std::array<std::pair<int, int>, 3> boundary_pairs{{{0, 1}, {0, 2}, {1, 2}}};

} // namespace

std::string pair_name(int from, int to) {
  return std::string{char('0' + from / 3), char('0' + from % 3), '-', '>',
                     char('0' + to / 3),   char('0' + to % 3)};
}

std::string seed_label(int from, int to) {
  return std::string{'w', char('1' + to), char('1' + from)};
}

std::string site_name(int from, int to) {
  return std::string{char('0' + from), '-', '>', char('0' + to)};
}

std::string boundary_label(bool left, int from, int to) {
  for (int m = 0; m < 3; ++m) {
    const auto [a, b] = boundary_pairs[m];
    if (from == a && to == b)
      return (left ? "alpha" : "delta") + std::to_string(m + 1);
    if (from == b && to == a)
      return (left ? "gamma" : "beta") + std::to_string(m + 1);
  }
  return "?";
}

std::optional<std::pair<int, int>> parse_pair_key(std::string_view key) {
  if (key.size() == 6 && key.substr(2, 2) == "->" && is_state(key[0]) && is_state(key[1]) &&
      is_state(key[4]) && is_state(key[5])) {
    const int from = pair_code(key[0] - '0', key[1] - '0');
    const int to = pair_code(key[4] - '0', key[5] - '0');
    if (from == to)
      return std::nullopt;
    return std::pair{from, to};
  }
  std::string_view digits;
  if (key.size() == 3 && key[0] == 'w')
    digits = key.substr(1);
  else if (key.size() == 4 && key.substr(0, 2) == "w_")
    digits = key.substr(2);
  else
    return std::nullopt;
  if (digits[0] < '1' || digits[0] > '9' || digits[1] < '1' || digits[1] > '9' ||
      digits[0] == digits[1])
    return std::nullopt;
  return std::pair{digits[1] - '1', digits[0] - '1'}; // w_ij: i target, j initial
}

std::optional<std::pair<int, int>> parse_site_key(std::string_view key, bool left) {
  if (key.size() == 4 && key.substr(1, 2) == "->" && is_state(key[0]) && is_state(key[3]) &&
      key[0] != key[3])
    return std::pair{key[0] - '0', key[3] - '0'};
  for (int from = 0; from < 3; ++from)
    for (int to = 0; to < 3; ++to)
      if (from != to && key == boundary_label(left, from, to))
        return std::pair{from, to};
  return std::nullopt;
}

} // namespace narrows::three_state
