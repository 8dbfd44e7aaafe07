// render/volume_merge.h - the merge of a volume frame's parts (render/volume_parts.h) for some of
// its pixels: per pixel, the ranks' sums at each shared sample added (in rank order) and
// composited, the segments composited in depth order between them (a segment's light scaled by
// the transmittance in front of it), the iso crossings at the joins found; then, once the
// ranks' field sums at those crossings are in, each hit lit and the pixel's colour and depth
// made as one process makes them (render/cpu/volume_caster.h).
#pragma once

#include <array>
#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <tbb/parallel_for.h>

#include "render/camera.h"
#include "render/model/volume_host.h"
#include "render/volume.h"
#include "render/volume_parts.h"
#include "render/volume_renderer.h"

namespace voxspan {

class VolumeMerge {
 public:
  // With `deep`, finish() gives the merged pixels' deep samples too.
  VolumeMerge(const Camera& camera, const VolumeOptions& options, bool deep = false);

  // Pixel `pixel` (x + y * width) from every rank's items on it, in rank order: raws[r] and
  // segments[r] (each in sample order). Its iso hits' queries are appended to `queries`.
  void merge(std::uint32_t pixel, std::span<const std::span<const RawSample>> raws,
             std::span<const std::span<const PartSegment>> segments,
             std::vector<HitQuery>& queries);

  // The merged pixels' colours and depths (VolumeFrame's), in the order merge() took them, from
  // the field's sums at every query (summed over the ranks), in the order they were appended;
  // with `deep`, their deep samples (per pixel a count in `deep_counts`, the samples appended).
  void finish(std::span<const FieldSums> sums, std::vector<glm::vec4>& colors,
              std::vector<float>& depths, std::vector<std::uint32_t>* deep_counts = nullptr,
              std::vector<DeepSample>* deep = nullptr);

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
    // Its deep runs: runs_[run_begin, run_end), the run of each lit hit.
    std::uint32_t run_begin = 0, run_end = 0;
    std::array<std::uint32_t, model::kMaxIsoHits> hit_run{};
  };
  // A run of samples with no gap, for the deep image: the ray's light and transmittance where
  // it starts, then its own.
  struct Run {
    std::int32_t first = 0, last = 0;
    glm::vec3 color_before{0.0f};
    float transmittance_before = 1;
    glm::vec3 color{0.0f};
    float transmittance = 1;
  };
  void composite(Ray& m, std::int32_t index, double s, double w);
  void join(Ray& m, const PartSegment& segment);
  void note_hits(Ray& m, int before);
  // The deep run for samples first..last of the ray: a new one after a gap.
  void extend_run(Ray& m, std::int32_t first, std::int32_t last, std::int64_t previous);
  void end_run(Ray& m);

  VolumeOptions options_;
  ViewFrame frame_;
  VolumeLattice lattice_;
  model::VolumeHost host_;
  std::vector<Ray> rays_;
  bool deep_ = false;
  std::vector<Run> runs_;
  VolumeCounts counts_;
  std::vector<std::size_t> next_raw_, next_segment_;  // merge()'s cursors, per rank
};

// VolumeMerge over pixels [first, first + count) in parallel: the pixels in chunks, a merge each;
// the queries, colours, depths and deep samples come in pixel order whatever the threads.
class ParallelVolumeMerge {
 public:
  ParallelVolumeMerge(const Camera& camera, const VolumeOptions& options, bool deep = false)
      : camera_(camera), options_(options), deep_(deep) {}

  // items(pixel, raws, segments) fills raws[r] and segments[r] (each `ranks` long) with every
  // rank's items on the pixel.
  template <class Items>
  void merge(std::size_t first, std::size_t count, std::size_t ranks, Items&& items) {
    const std::size_t chunks = (count + kChunk - 1) / kChunk;
    chunks_.clear();
    for (std::size_t c = 0; c < chunks; ++c)
      chunks_.push_back(std::make_unique<VolumeMerge>(camera_, options_, deep_));
    std::vector<std::vector<HitQuery>> queries(chunks);
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
      std::vector<std::span<const RawSample>> raws(ranks);
      std::vector<std::span<const PartSegment>> segments(ranks);
      for (std::size_t p = first + c * kChunk;
           p < std::min(first + count, first + (c + 1) * kChunk); ++p) {
        items(p, raws, segments);
        chunks_[c]->merge(std::uint32_t(p), raws, segments, queries[c]);
      }
    });
    queries_.clear();
    query_start_.assign(1, 0);
    for (const std::vector<HitQuery>& q : queries) {
      queries_.insert(queries_.end(), q.begin(), q.end());
      query_start_.push_back(queries_.size());
    }
  }

  // Where the merge wants every rank's field sums (the queries of all pixels, in order).
  const std::vector<HitQuery>& queries() const { return queries_; }

  // VolumeMerge::finish over all the pixels, `sums` one per query.
  void finish(std::span<const FieldSums> sums, std::vector<glm::vec4>& colors,
              std::vector<float>& depths, std::vector<std::uint32_t>* deep_counts = nullptr,
              std::vector<DeepSample>* deep = nullptr);

  VolumeCounts counts() const;

 private:
  static constexpr std::size_t kChunk = 4096;  // pixels
  Camera camera_;
  VolumeOptions options_;
  bool deep_;
  std::vector<std::unique_ptr<VolumeMerge>> chunks_;
  std::vector<HitQuery> queries_;
  std::vector<std::size_t> query_start_;  // per chunk, its first query; then the total
};

// One process's frame through the merge (the renderer's part with nothing shared, merged): the
// picture and depths render() gives, to rounding, and the deep image in out.deep.
VolumeCounts render_with_deep(VolumeRenderer& renderer, const Camera& camera,
                              std::span<const VolumeParticle> particles,
                              const VolumeOptions& options, Recorder& recorder, VolumeFrame& out);

}  // namespace voxspan
