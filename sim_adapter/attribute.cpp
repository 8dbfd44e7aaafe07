#include "voxspan/attribute.h"

#include "voxspan/error.h"

namespace voxspan {

void check_attributes(std::span<const AttributeSpan> attributes, std::size_t count) {
  for (const AttributeSpan& a : attributes) {
    if (a.components != 1 && a.components != 3)
      throw make_error("attribute \"", a.name, "\" has ", a.components,
                       " components (1 or 3 are supported)");
    if (a.values.size() != count * std::size_t(a.components))
      throw make_error("attribute \"", a.name, "\" has ", a.values.size(), " values for ", count,
                       " particles with ", a.components, " components each");
  }
}

}  // namespace voxspan
