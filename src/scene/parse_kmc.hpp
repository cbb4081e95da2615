// Validation of the [kmc] section (engine "kmc"), called by parse_scene.
#pragma once

#include "narrows/scene/scene.hpp"

#include "checker.hpp"

#include <toml.hpp>

#include <string>

namespace narrows::scene::detail {

// The [kmc] section of the scene's table `root` into s.kmc.
void parse_kmc_scene(const Checker &c, const toml::value &root, Scene &s);

// `section` may be null (missing [kmc]).
Kmc parse_kmc(const toml::value *section, const Checker &c);

// Pieces shared with [continuum] (its lattice-gas fluxes take the kmc presets' rates); `name`
// is the key in messages ("kmc.rates", "continuum.parameters").
void parse_bulk_rates(const Checker &c, const toml::value &v, Kmc &out, const std::string &name);
void parse_family2(const Checker &c, const toml::value &v, Kmc &out, const std::string &name);
// Refuses a rate that is not one of family 1's ten transitions (`with`: the setting that asks
// for family 1, for the message).
void check_family1_rates(const Checker &c, const Kmc &out, const std::string &name,
                         const std::string &with);

} // namespace narrows::scene::detail
