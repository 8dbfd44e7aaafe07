// voxspan/classify.h - cell classification and boundary-particle compaction ([ZD15],
// sec. 3.1 and 4.3): per cell of the simulation grid empty, partial or full; a cell is inner
// when it and its 26 neighbours are all empty or all full; the particles of non-inner cells
// (boundary particles) are compacted, in cell order, into packed float spheres (and the named
// attributes asked for, in the same order). Particles of inner cells add nothing to the
// picture and are left out.
//
// Reads: a ParticleView and a GridView (any layout). Writes: one state byte per cell
// (voxspan/cell_states.h) and the boundary spheres. Costs: one pass over all positions (to
// count valid particles per cell and drop NaN/inf), three passes over the cells, one pass over
// the boundary particles; a counting sort first when the solver shares no cell ranges.
// Parallel with oneTBB. Standard library only in this header.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "voxspan/attribute.h"
#include "voxspan/cell_states.h"
#include "voxspan/error.h"
#include "voxspan/grid.h"
#include "voxspan/particles.h"

namespace voxspan {

// What run() throws when the grid's cell lists do not match the positions: a range outside the
// particles, a cell index outside the grid, a particle outside its claimed cell or in none (a
// wrong origin, cell size or index base, or particles not stored in the grid's order).
class GridMismatch : public Error {
 public:
  using Error::Error;
};

struct ClassifyOptions {
  // The solver's particle spacing at rest density (world units). Gives the full count, the
  // cell size of a grid the adapter builds, and the radius when the view has none.
  double particle_spacing = 0;
  // Particles that make a cell full. 0: the count of a cell filled at rest density, the
  // fewest a cell inside a cubic rest lattice holds whatever its offset,
  // round(full_fraction * floor(cell_size / spacing)^3).
  int full_count = 0;
  double full_fraction = 1.0;
  // Cell size of the grid built when the solver gives none (GridView::none()); 0: 2 * spacing.
  double cell_size = 0;
  // Sphere radius when the view has no radius; 0: particle_spacing (a sphere of radius >=
  // sqrt(3)/2 spacing leaves no holes in the rest lattice).
  double radius = 0;
  // Checks that every particle lies in the cell the grid claims, and appears once. (The
  // Adapter checks a solver's grid this way until one render step passes, and on every one
  // with this on.)
  bool validate = false;
  // Ghost particles (past ParticleView::owned_count()) count towards the cells' occupancy
  // always; with this on they are also compacted when they are boundary particles (the
  // in-situ runtime turns it off in an MPI job, where each particle is its owner's).
  bool include_ghosts = true;
  // Names of the particle attributes to compact beside the spheres. One the view lacks is an
  // error, or with skip_missing_attributes left out (the in-situ runtime's outputs that name it
  // then fail alone, each naming its key, while the pictures and the other outputs go on).
  std::vector<std::string> attributes;
  bool skip_missing_attributes = false;
  // A grid the adapter builds never has more cells than this, nor more than 64 per particle
  // (2^20 at least): its cells grow instead.
  std::size_t max_built_cells = std::size_t(1) << 27;
  // The world point the boundary spheres are measured from (Classification::origin): each
  // position is shifted by it in double before it becomes a float, whose 24 bits hold a
  // coordinate of 4.2e6 (UTM-like) only to 0.5. The Adapter chooses it on its first render step
  // (frame_origin_near) unless the solver sets it: the same on every rank of an MPI job.
  std::array<double, 3> origin{0, 0, 0};
};

// The frame origin of a scene around `point` whose lengths that matter are of order `unit` (the
// particle spacing): the world's origin while a float holds coordinates there to 2^-13 of
// `unit` (every |coordinate| under 2^10 units: ordinary scenes stay bit for bit as they were),
// else `point` itself. A non-finite point or unit gives the world's origin.
std::array<double, 3> frame_origin_near(const std::array<double, 3>& point, double unit);

// What one classification saw. The occupancy counts (empty/partial/full) include the inner
// cells; inner_empty and inner_full say how many of them are inner.
struct ClassifyCounts {
  std::size_t particles = 0;          // in the view
  std::size_t owned = 0;              // of them owned by this rank
  std::size_t boundary = 0;           // compacted
  std::size_t dropped_nonfinite = 0;  // NaN/inf position or radius: left out
  std::size_t not_in_grid = 0;        // listed in no cell of the solver's grid
  std::size_t cells = 0;
  std::size_t cells_empty = 0, cells_partial = 0, cells_full = 0;
  std::size_t cells_inner_empty = 0, cells_inner_full = 0;
  int full_count = 0;
  double cell_size = 0;
  bool grid_built = false;  // the adapter sorted the particles itself
};

// The phases of a classification, in the order they run; kClassifyPhaseNames[p] names phase p.
//   ranges    the grid's geometry and per-cell ranges of the particles: the solver's own, or a
//             counting sort of a per-particle cell index (the solver's, or from the positions)
//   count     per cell its valid particles (NaN/inf left out), the grid's claims checked
//   classify  per cell its state: occupancy and the inner bit
//   compact   the particles of the cells that are not inner into the boundary spheres and the
//             attributes asked for
enum class ClassifyPhase { ranges, count, classify, compact };
inline constexpr std::array<const char*, 4> kClassifyPhaseNames{"ranges", "count", "classify",
                                                                "compact"};
static_assert(kClassifyPhaseNames.size() == std::size_t(ClassifyPhase::compact) + 1);

// A compacted attribute: `components` floats per boundary particle, in boundary order.

struct Classification {
  GridGeometry geometry;
  std::vector<std::uint8_t> states;      // one byte per cell, voxspan::cell
  std::vector<ParticleSphere> boundary;  // in cell order, then grid order within a cell
  // World coordinates of the spheres' (0, 0, 0) (ClassifyOptions::origin): a sphere at (x, y, z)
  // is at origin + (x, y, z) in the world. The cell states' geometry is in world coordinates.
  std::array<double, 3> origin{0, 0, 0};
  std::vector<Attribute> attributes;  // the requested ones, in boundary order
  ClassifyCounts counts;
  double seconds_classify = 0;  // counting (and sorting) and the cell states
  double seconds_compact = 0;   // the boundary spheres and attributes
  // Wall time of each phase, milliseconds, by ClassifyPhase: seconds_classify is the first
  // three, seconds_compact the last.
  std::array<double, kClassifyPhaseNames.size()> phase_ms{};

  CellStatesView cell_states() const {
    return {geometry.origin, geometry.cell_size, geometry.dims,
            states.empty() ? nullptr : states.data()};
  }
};

// The occupancy and inner bits from per-cell particle counts (cells outside the grid are
// empty). `states` must have geometry.cell_count() entries.
void classify_cells(const GridGeometry& geometry, std::span<const std::uint32_t> counts,
                    int full_count, std::span<std::uint8_t> states);

// The full count for cells of `cell_size` (see ClassifyOptions::full_count).
int full_count_for(const ClassifyOptions& options, double cell_size);

// Reuses its buffers from step to step: a solver's loop should keep one.
class Classifier {
 public:
  Classifier();
  ~Classifier();
  Classifier(Classifier&&) noexcept;
  Classifier& operator=(Classifier&&) noexcept;

  // Throws voxspan::Error naming the bad input: GridMismatch for the grid's lists (ranges out
  // of bounds, cell index out of range, a particle outside its claimed cell under validate),
  // Error for the rest (a missing attribute, a bad geometry...). NaN
  // and infinite positions are not errors: they are counted and left out.
  const Classification& run(const ParticleView& particles, const GridView& grid,
                            const ClassifyOptions& options);
  const Classification& result() const;
  // Moves the result out (the next run() starts with empty buffers).
  Classification take_result();

 private:
  struct Work;
  std::unique_ptr<Work> work_;
};

// Every particle of `particles` (ghosts too) as a sphere into `out` (resized), in world
// coordinates (options.origin is not applied: the scenery is packed before any step), radii as
// run() takes them; those with a NaN or infinite position or a NaN, infinite or negative radius are
// left out. Returns how many were left out; throws voxspan::Error when no radius can be found.
std::size_t pack_spheres(const ParticleView& particles, const ClassifyOptions& options,
                         std::vector<ParticleSphere>& out);

// The common case, with fresh buffers.
Classification classify(const ParticleView& particles, const GridView& grid,
                        const ClassifyOptions& options);

}  // namespace voxspan
