#include "render/volume_renderer.h"

namespace voxspan {

void record(const VolumeCounts& c, Recorder& recorder) {
  for (const VolumeCountName& n : kVolumeCountNames) recorder.count(StatName(n.name), c.*n.member);
}

}  // namespace voxspan
