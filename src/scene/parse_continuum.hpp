// Validation of the [continuum] section (engine "continuum"), called by parse_scene.
#pragma once

#include "narrows/scene/scene.hpp"

#include "checker.hpp"

#include <toml.hpp>

namespace narrows::scene::detail {

// The [continuum] section of the scene's table `root` into s.continuum.
void parse_continuum_scene(const Checker &c, const toml::value &root, Scene &s);
// Refuses an observable of output.observables that the scene's model does not write.
void check_continuum_observables(const Checker &c, const Scene &s);

// `section` may be null (missing [continuum]).
Continuum parse_continuum(const toml::value *section, const Checker &c);

} // namespace narrows::scene::detail
