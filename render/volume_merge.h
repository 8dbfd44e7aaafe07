// render/volume_merge.h - the merge of a volume frame's parts (render/volume_parts.h) for some of
// its pixels: per pixel, the ranks' sums at each shared sample added (in rank order) and
// composited, the segments composited in depth order between them (a segment's light scaled by
// the transmittance in front of it), the iso crossings at the joins found; then, once the
// ranks' field sums at those crossings are in, each hit lit and the pixel's colour and depth
// made as one process makes them (render/cpu/volume_caster.h).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "render/camera.h"
#include "render/model/volume_host.h"
#include "render/volume.h"
#include "render/volume_parts.h"

namespace voxspan {

class VolumeMerge {
 public:
  VolumeMerge(const Camera& camera, const VolumeOptions& options);

  // Pixel `pixel` (x + y * width) from every rank's items on it, in rank order: raws[r] and
  // segments[r] (each in sample order). Its iso hits' queries are appended to `queries`.
  void merge(std::uint32_t pixel, std::span<const std::span<const RawSample>> raws,
             std::span<const std::span<const PartSegment>> segments,
             std::vector<HitQuery>& queries);

  // The merged pixels' colours and depths (VolumeFrame's), in the order merge() took them, from
  // the field's sums at every query (summed over the ranks), in the order they were appended.
  void finish(std::span<const FieldSums> sums, std::vector<glm::vec4>& colors,
              std::vector<float>& depths);

  // The merge's own counts (samples composited here, iso hits found here, rays stopped).
  const VolumeCounts& counts() const { return counts_; }

 private:
  struct Ray {
    std::uint32_t pixel = 0;
    model::VolumeHost::VolumeRay ray;
    model::RayHits hits;
    float scale = 1;
    float first_depth = 0;
    bool first_is_hit = false;
    std::uint32_t first_query = 0;
  };
  void composite(Ray& m, std::int32_t index, double s, double w);
  void join(Ray& m, const PartSegment& segment);
  void note_hits(Ray& m, int before);

  VolumeOptions options_;
  ViewFrame frame_;
  VolumeLattice lattice_;
  model::VolumeHost host_;
  std::vector<Ray> rays_;
  VolumeCounts counts_;
};

}  // namespace voxspan
