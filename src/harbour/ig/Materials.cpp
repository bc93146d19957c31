#include "harbour/ig/Materials.h"

namespace harbour::ig {

std::optional<Surface> surface_named(std::string_view name) {
  for (std::size_t k = 0; k < kSurfaceFinishes.size(); ++k)
    if (kSurfaceFinishes[k].name == name) return static_cast<Surface>(k);
  return std::nullopt;
}

std::string_view surface_names() {
  return "paint, steel, galvanised, rubber, concrete, glass, timber or bulk";
}

osg::Vec4 finished(const osg::Vec4& colour, Surface surface) {
  return {colour.r(), colour.g(), colour.b(), 1.0f - static_cast<float>(surface) / 16.0f};
}

}  // namespace harbour::ig
