#include "insitu/views/view_attributes.h"

#include <string>

#include "voxspan/error.h"

namespace voxspan {

const AttributeView& require_attribute(const ParticleView& particles, std::string_view name,
                                       std::string_view key) {
  if (const AttributeView* a = particles.find_attribute(name)) return *a;
  std::string passed;
  for (int k = 0; k < particles.attribute_count(); ++k)
    passed.append(k == 0 ? "" : ", ").append(particles.attribute(k).name);
  throw make_error(key, " \"", name, "\": the solver passes no attribute of that name (",
                   passed.empty() ? std::string("it passes none") : "it passes: " + passed, ")");
}

}  // namespace voxspan
