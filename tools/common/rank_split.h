// tools/common/rank_split.h - one MPI rank's part of a set of particles (a file the offline
// renderer reads on every rank, a benchmark's scene): the particles it owns, then, as ghosts, every
// other particle within `margin` of its slab, so that its cells classify as they would in one
// process (voxspan/classify.h: ghosts count towards occupancy, and are not voxelized).
//   slabs        equal particle counts in slabs along the axis the particles spread most
//   uneven       slabs of unequal counts, the last rank empty (a test of compositing)
//   interleaved  particle i to rank i mod N: every rank's part covers the whole fluid, and
//                every rank has every other particle as a ghost
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "render/enum_names.h"

namespace voxspan::tools {

enum class Split { slabs, uneven, interleaved };
inline constexpr EnumName<Split> kSplitNames[] = {
    {"slabs", Split::slabs}, {"uneven", Split::uneven}, {"interleaved", Split::interleaved}};

// The indices of rank `rank`'s particles: its own first (`owned` of them), then its ghosts.
struct RankPart {
  std::vector<std::size_t> indices;
  std::size_t owned = 0;
};

RankPart split_particles(std::span<const std::array<double, 3>> positions, Split split, int rank,
                         int ranks, double margin);

// The ghosts' margin for particles of rest spacing `spacing`: two cells of the grid the adapter
// builds (two spacings each) deep, since the classification of a rank's border cells reads its
// neighbours' occupancy.
inline double ghost_margin(double spacing) { return 4 * spacing; }

}  // namespace voxspan::tools
