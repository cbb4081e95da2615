// The segregation model's coefficient curves (see continuum/segregation_curves.hpp).
#include "narrows/engines/continuum/segregation_curves.hpp"

namespace narrows::continuum {

SegregationCurves segregation_curves(const SegregationModel &model, std::size_t points) {
  const scene::Segregation &s = model.parameters();
  const std::size_t n = model.kinds();
  SegregationCurves out;
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    total += s.kinds[i].fraction;
  for (std::size_t i = 0; i < n; ++i) {
    out.composition.push_back(s.kinds[i].fraction / total);
    out.scale.push_back(s.k_d * s.kinds[i].diffusivity);
  }
  for (std::size_t k = 0; k < points; ++k) {
    const double phi = static_cast<double>(k) * s.max_packing / static_cast<double>(points);
    double x[max_segregation_kinds], dc[max_segregation_kinds * max_segregation_kinds];
    for (std::size_t i = 0; i < n; ++i)
      x[i] = phi * out.composition[i];
    model.collective_diffusivity(x, dc);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j)
        out.value.push_back(dc[i * n + j] / out.scale[i]);
    out.phi.push_back(phi);
    out.structure.push_back(model.structure_factor(x));
    out.viscosity.push_back(model.viscosity(phi));
  }
  return out;
}

} // namespace narrows::continuum
