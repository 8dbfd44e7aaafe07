// insitu/views/volume_compositor.h - a volume view's frame rendered by several MPI ranks, each
// over the particles it owns, merged exactly (render/volume_parts.h says how and what is not
// one process's to rounding). The image's rows are cut into one band per rank
// (insitu/parallel/span_merge.h's band_of), and four all-to-all exchanges run:
//   1. hulls: each rank sends each band's owner its hull of samples per pixel it reaches;
//   2. shared: the owner sends each rank, per pixel, the samples of its hull another rank's
//      hull holds too;
//   3. parts: each rank sends each owner its sums at those samples and its segments;
//   4. (iso and mixed modes) hits: the owner merges its band and sends every rank the iso hits
//      found at the joins; each rank sends back its field sums there (those not zero);
// then the owners light their bands' hits and the root gathers the bands. Adaptive sampling
// (VolumeOptions::adaptive) gives each rank 1 / ranks of the tolerance: the composited picture
// stays within it of the full-rate composite.
// A rank that fails in any of its steps fails the step on every rank (Communicator::agree),
// before the next exchange: no rank waits for one that threw.
// Times: pass::volume (this rank's rendering), pass::composite (the exchanges and the merge);
// counts: composite.bytes_sent and this rank's volume.* (the stats line sums them over the ranks).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "insitu/parallel/communicator.h"
#include "render/recorder.h"
#include "render/volume_renderer.h"

namespace voxspan {

class VolumeCompositor {
 public:
  explicit VolumeCompositor(Communicator& comm) : comm_(comm) {}

  // Collective: every rank calls it with its own particles and the same camera and options.
  // True on the root, whose `out` then holds the frame (with `deep`, its deep image too).
  // Throws voxspan::Error on every rank, naming the rank, when any failed.
  bool render(VolumeRenderer& renderer, const Camera& camera,
              std::span<const VolumeParticle> particles, const VolumeOptions& options, bool deep,
              Recorder& recorder, VolumeFrame& out);

 private:
  // Every rank's failure or none: throws naming the first rank that failed.
  void agree(bool ok, const std::string& failure);

  Communicator& comm_;
  std::vector<SampleRange> hulls_;
  PixelRanges shared_;
  VolumePart part_;
};

}  // namespace voxspan
