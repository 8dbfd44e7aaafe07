#include "insitu/views/view_attributes.h"

#include "sim_adapter/near_name.h"
#include "voxspan/error.h"

namespace voxspan {

const AttributeView& require_attribute(const ParticleView& particles, std::string_view name,
                                       std::string_view key) {
  if (const AttributeView* a = particles.find_attribute(name)) return *a;
  throw make_error(key, " \"", name, "\": the solver passes no attribute of that name (",
                   attributes_instead(particles, name), ")");
}

}  // namespace voxspan
