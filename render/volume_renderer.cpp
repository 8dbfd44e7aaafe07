#include "render/volume_renderer.h"

#include "render/stat_names.h"

namespace voxspan {

void record(const VolumeCounts& c, Recorder& recorder) {
  for (const VolumeCountName& n : kVolumeCountNames) recorder.count(StatName(n.name), c.*n.member);
  recorder.figure(figure::volume_error_bound, c.error_bound);
}

}  // namespace voxspan
