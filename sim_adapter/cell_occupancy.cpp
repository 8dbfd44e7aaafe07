// The inner test is a 3x3x3 erosion of two masks (all-full, all-empty), done separably: a
// cell is all-full-around when its row neighbours in x are, then in y, then in z. Three
// passes over the cells instead of 27 reads per cell. Outside the grid counts as empty air,
// as CellStatesView documents.
#include "cell_occupancy.h"

#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "voxspan/error.h"

namespace voxspan {
namespace detail {
namespace {

constexpr std::uint8_t kAllFull = 1;
constexpr std::uint8_t kAllEmpty = 2;
constexpr std::uint8_t kOutside = kAllEmpty;  // outside the grid is empty air

// dst[c] = src[c - step] & src[c] & src[c + step] along one axis of extent n; the grid is
// walked as (outer, n, inner) with step = inner.
void erode_axis(const std::uint8_t* src, std::uint8_t* dst, std::size_t outer, std::size_t n,
                std::size_t inner) {
  tbb::parallel_for(tbb::blocked_range2d<std::size_t>(0, outer, 16, 0, inner, 4096),
                    [&](const tbb::blocked_range2d<std::size_t>& r) {
                      for (std::size_t o = r.rows().begin(); o != r.rows().end(); ++o) {
                        const std::size_t base = o * n * inner;
                        for (std::size_t a = 0; a < n; ++a) {
                          const std::uint8_t* s = src + base + a * inner;
                          std::uint8_t* d = dst + base + a * inner;
                          const std::uint8_t* lo = a > 0 ? s - inner : nullptr;
                          const std::uint8_t* hi = a + 1 < n ? s + inner : nullptr;
                          for (std::size_t i = r.cols().begin(); i != r.cols().end(); ++i)
                            d[i] = s[i] & (lo ? lo[i] : kOutside) & (hi ? hi[i] : kOutside);
                        }
                      }
                    });
}

}  // namespace

void classify_cells(const GridGeometry& g, std::span<const std::uint32_t> counts, int full_count,
                    std::span<std::uint8_t> states, std::vector<std::uint8_t>& scratch) {
  const std::size_t cells = g.cell_count();
  if (counts.size() != cells || states.size() != cells)
    throw make_error("classify_cells: ", counts.size(), " counts and ", states.size(),
                     " states for a grid of ", cells, " cells");
  if (full_count < 1) throw make_error("classify_cells: full count ", full_count, " is not >= 1");
  if (cells == 0) return;
  const auto full = static_cast<std::uint32_t>(full_count);

  // Masks into states, eroded x -> scratch, y -> states, z -> scratch.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 1 << 14),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t c = r.begin(); c != r.end(); ++c)
                        states[c] = counts[c] == 0 ? kAllEmpty : counts[c] >= full ? kAllFull : 0;
                    });
  scratch.resize(cells);
  const std::size_t nx = std::size_t(g.dims[0]), ny = std::size_t(g.dims[1]),
                    nz = std::size_t(g.dims[2]);
  erode_axis(states.data(), scratch.data(), ny * nz, nx, 1);
  erode_axis(scratch.data(), states.data(), nz, ny, nx);
  erode_axis(states.data(), scratch.data(), 1, nz, nx * ny);

  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 1 << 14),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t c = r.begin(); c != r.end(); ++c) {
                        const std::uint8_t occupancy = counts[c] == 0      ? cell::kEmpty
                                                       : counts[c] >= full ? cell::kFull
                                                                           : cell::kPartial;
                        states[c] = occupancy | (scratch[c] != 0 ? cell::kInner : 0);
                      }
                    });
}

void tally_cells(std::span<const std::uint8_t> states, ClassifyCounts& counts) {
  struct Tally {
    std::size_t n[8] = {};
  };
  tbb::combinable<Tally> tallies;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, states.size(), 1 << 15),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      Tally& t = tallies.local();
                      for (std::size_t c = r.begin(); c != r.end(); ++c) ++t.n[states[c] & 7];
                    });
  Tally sum;
  tallies.combine_each([&](const Tally& t) {
    for (int s = 0; s < 8; ++s) sum.n[s] += t.n[s];
  });
  counts.cells += states.size();
  counts.cells_empty += sum.n[cell::kEmpty] + sum.n[cell::kInnerEmpty];
  counts.cells_partial += sum.n[cell::kPartial] + sum.n[cell::kPartial | cell::kInner];
  counts.cells_full += sum.n[cell::kFull] + sum.n[cell::kInnerFull];
  counts.cells_inner_empty += sum.n[cell::kInnerEmpty];
  counts.cells_inner_full += sum.n[cell::kInnerFull];
}

}  // namespace detail

void classify_cells(const GridGeometry& geometry, std::span<const std::uint32_t> counts,
                    int full_count, std::span<std::uint8_t> states) {
  std::vector<std::uint8_t> scratch;
  detail::classify_cells(geometry, counts, full_count, states, scratch);
}

int full_count_for(const ClassifyOptions& options, double cell_size) {
  if (options.full_count > 0) return options.full_count;
  if (!(options.particle_spacing > 0) || !(cell_size > 0))
    throw make_error(
        "the full count is unknown: set full_count or particle_spacing (got "
        "particle_spacing ",
        options.particle_spacing, ", cell size ", cell_size, ")");
  // A cell inside the fluid at rest holds at least floor(cell / spacing) lattice planes per
  // axis, whatever the lattice's offset: that many cubed is the count of a filled cell.
  const double planes = std::floor(cell_size / options.particle_spacing * (1 + 1e-9));
  const double count = options.full_fraction * planes * planes * planes;
  return static_cast<int>(std::max(1.0, std::min(std::round(count), 1e9)));
}

}  // namespace voxspan
