#include "insitu/outputs/snapshot_copy.h"

#include <algorithm>

#include "voxspan/error.h"

namespace voxspan {

void SnapshotCopy::fill(const StepData& data, std::span<const std::string> names, double radius) {
  step = data.step;
  time = data.time;
  spheres.assign(data.boundary.begin(), data.boundary.end());
  if (radius > 0)
    for (ParticleSphere& s : spheres) s.radius = float(radius);
  attributes.resize(names.size());
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto found = std::find_if(data.attributes.begin(), data.attributes.end(),
                                    [&](const Attribute& a) { return a.name == names[k]; });
    if (found == data.attributes.end())
      throw make_error("attribute \"", names[k], "\" was not compacted by the adapter");
    attributes[k].assign(found->view());
  }
  cells.assign(data.cells);
}

std::vector<AttributeSpan> SnapshotCopy::attribute_spans() const {
  std::vector<AttributeSpan> spans;
  spans.reserve(attributes.size());
  for (const Attribute& a : attributes) spans.push_back(a.view());
  return spans;
}

}  // namespace voxspan
