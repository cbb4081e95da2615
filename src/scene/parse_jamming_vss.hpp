// The jamming model's v_ss parameters (Kanehl (thesis) eq 6.4): a column of Table 6.2
// (continuum.mu), given in the scene (continuum.vss) or read from the JSON file of a fit
// (continuum.vss_fit, written by tools/vss_fit.py). Exactly one of the three; mu = "1" if none.
#pragma once

#include "narrows/scene/scene.hpp"

#include "checker.hpp"

#include <toml.hpp>

namespace narrows::scene::detail {

// The names of the six parameters of eq 6.4, in the order of Continuum::vss.
inline constexpr const char *vss_names[6] = {"delta_v", "delta_phi", "phi_c", "e1", "e2", "phi_q"};

// continuum.mu, continuum.vss or continuum.vss_fit of section `sec` into out.fit / out.vss.
void parse_jamming_vss(const Checker &c, const toml::value *sec, Continuum &out);

} // namespace narrows::scene::detail
