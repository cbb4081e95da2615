// The schema of each engine (schema_<engine>.cpp), which scene/schema.cpp puts together.
#pragma once

#include "narrows/scene/schema.hpp"

namespace narrows::scene::detail {

const EngineSchema &mpcd_schema();
const EngineSchema &lgca_schema();
const EngineSchema &kmc_schema();
const EngineSchema &continuum_schema();

} // namespace narrows::scene::detail
