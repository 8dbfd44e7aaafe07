#include "insitu/outputs/kinds/level_set_outputs.h"

#include <exception>
#include <string>
#include <utility>

#include "voxspan/error.h"

namespace voxspan {

std::vector<schema::Key<FluidLevelSetSettings>> fluid_level_set_keys() {
  using L = FluidLevelSetSettings;
  return {schema::number_or_auto("voxel_size", &L::voxel_size, schema::above(0),
                                 "world units; `auto` = the radius"),
          schema::number_or_auto("closing", &L::closing, schema::at_least(0),
                                 "gap closing distance (dilate, then erode by it); `auto` = the "
                                 "radius; 0: none"),
          schema::flag("fill_inner", &L::fill_inner,
                       "inner-full cells filled: the file holds the whole fluid")};
}

LevelSetOutput::LevelSetOutput(const OutputContext& context, std::optional<double> radius,
                               AttributeNames attributes, const char* label, WriteFile write_file)
    : label_(label),
      attributes_(std::move(attributes)),
      radius_(radius.value_or(context.particle_spacing > 0 ? 0.5 * context.particle_spacing : 0.0)),
      comm_(context.comm),
      jobs_(context.writer, context.slots, [write_file = std::move(write_file)](SnapshotCopy& s) {
        const std::vector<AttributeSpan> spans = s.attribute_spans();
        write_file({s.spheres, s.cells.view(), spans, s.step, s.time, s.origin});
      }) {
  ensure_openvdb_initialized();
}

void LevelSetOutput::write(const OutputStep& step) {
  const StepData& data = step.data;
  if (comm_ == nullptr || comm_->size() == 1) {
    jobs_.submit(label_, [&](SnapshotCopy& copy) { copy.fill(data, attributes_, radius_); });
    return;
  }
  // Every rank's part, gathered on the root before any slot is taken: a rank without a free
  // slot still takes part, and so does one whose part failed (all then fail, naming it), so
  // that no rank waits in a collective the others never reach.
  std::string failure;
  try {
    gathered_.fill(data, attributes_, radius_);
  } catch (const std::exception& e) {
    failure = e.what();
  }
  comm_->agree_or_throw(failure.empty(), failure);
  if (!gathered_.gather(*comm_)) return;
  jobs_.submit(label_, [&](SnapshotCopy& copy) { std::swap(copy, gathered_); });
}

}  // namespace voxspan
