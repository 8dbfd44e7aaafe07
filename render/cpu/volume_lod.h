// render/cpu/volume_lod.h - particle level of detail for the volume views ([FAW10] sec. 4.1-4.2),
// built per frame: a particle whose smoothing length at its depth is under `level` sample
// spacings (h < level * p * z, p the spacing of the rays at depth 1, one pixel; z its depth) is
// merged with the others of its world grid cell into one coarser particle. Samples that far
// apart cannot resolve such particles one by one: each costs its projection, sorting and
// binning, and its supports' walk, while the picture aliases.
//
// Each such particle picks the cell size L = 2^e, the smallest power of two with
// L >= level * p * z, and its cell floor(x / L) of the world grid of that size (so that the
// cells stay put while the camera moves, and a particle changes level where its depth doubles;
// kept as it is where the scene spans over 2^18 cells of that size along an axis). The
// particles of one (e, cell) become one particle ([FAW10]'s merging rules, with the volume
// V = weight h^3 standing for the mass the input does not carry: exact for a fluid of one
// density):
//   V = sum V_j;  x = sum V_j x_j / V;  q = sum V_j q_j / V (so that sum V q W and sum V W, the
//   Shepard sums, take it as they took its particles);
//   h = max(L, max h_j): the merged particles stand about L apart, and a cubic spline of h = L
//   on such a lattice sums to about 1 (Shepard divides the rest out). A larger h (the
//   particles' own h in spacings, 1.3 for the views) smooths more and grows the silhouette by
//   more: 1.3 L gave three times the 99th-percentile error of h = L in the tests.
//   weight = V / h^3.
// Every other particle (near enough, behind the eye, or not finite: the caster counts and skips
// those as it does without level of detail) is kept as it is. The result does not depend on the
// threads: kept particles in input order, then the merged ones by cell, each summed in input
// order.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "render/camera.h"
#include "render/volume.h"

namespace voxspan {

struct LodCounts {
  std::int64_t merged = 0;  // input particles merged into coarser ones
  std::int64_t coarse = 0;  // the coarser particles they made
};

// Holds its scratch from frame to frame.
class VolumeLod {
 public:
  // The particles to draw of `particles` at level `level` (> 0) for the view `frame`: those
  // given where none is merged, else this object's (valid until the next run); `counts` gets
  // the merged and the coarser.
  std::span<const VolumeParticle> run(const ViewFrame& frame,
                                      std::span<const VolumeParticle> particles, double level,
                                      LodCounts& counts);

  struct Cell {
    std::uint64_t key;    // the cell: its size's exponent, its index from the scene's first
    std::uint32_t index;  // the particle's
  };

 private:
  std::vector<Cell> cells_;
  std::vector<VolumeParticle> drawn_;
};

}  // namespace voxspan
