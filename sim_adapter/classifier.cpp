// Classifier::run - the step from the solver's particles and grid to the cell states and the
// compacted boundary particles ([ZD15] sec. 3.1: "a fast reduction and compaction step
// before voxelization"). Phases (voxspan/classify.h's ClassifyPhase, each timed), each parallel
// over cells or particles:
//   1. ranges: the solver's own cell ranges (compact grid), or a counting sort of a per-particle
//      cell index (the solver's, or computed from the positions);
//   2. count: per cell the valid particles (NaN/inf dropped and counted), checking ranges
//      always and claimed cells under `validate`;
//   3. classify: the cell states, occupancy and the inner bit (cell_occupancy.cpp);
//   4. compact: the particles of non-inner cells, in cell order, into packed float spheres and
//      the requested attributes.
#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <ostream>

#include "cell_occupancy.h"
#include "cell_sort.h"
#include "first_error.h"
#include "near_name.h"
#include "parallel_scan.h"
#include "positions.h"
#include "voxspan/classify.h"
#include "voxspan/error.h"
#include "voxspan/stopwatch.h"

namespace voxspan {
namespace {

using detail::kNoCell;
constexpr std::size_t kCellGrain = 1 << 10;
constexpr std::size_t kParticleGrain = 1 << 14;

// Prints a linear cell index as (i, j, k) in messages.
struct CellName {
  const GridGeometry& g;
  std::size_t c;
};
std::ostream& operator<<(std::ostream& os, const CellName& n) {
  const std::size_t nx = std::size_t(n.g.dims[0]), ny = std::size_t(n.g.dims[1]);
  return os << "(" << n.c % nx << ", " << (n.c / nx) % ny << ", " << n.c / (nx * ny) << ")";
}

// The cell of a point, or -1 per axis outside [0, dims).
template <class T> std::array<std::int64_t, 3> cell_of_point(const GridGeometry& g, T x, T y, T z) {
  const double p[3] = {double(x), double(y), double(z)};
  std::array<std::int64_t, 3> ijk{};
  for (int a = 0; a < 3; ++a) {
    // For the only t kept, [0, dims), floor(t) is the truncation: one instruction, where
    // baseline x86-64 (no SSE4.1) emulates floor in several.
    const double t = (p[a] - g.origin[std::size_t(a)]) / g.cell_size;
    ijk[std::size_t(a)] = t >= 0 && t < g.dims[std::size_t(a)] ? std::int64_t(t) : -1;
  }
  return ijk;
}

// Whether a point lies in cell c, up to rounding in the solver's own cell computation.
template <class T> bool point_in_cell(const GridGeometry& g, std::size_t c, T x, T y, T z) {
  const std::size_t nx = std::size_t(g.dims[0]), ny = std::size_t(g.dims[1]);
  const std::size_t idx[3] = {c % nx, (c / nx) % ny, c / (nx * ny)};
  const double p[3] = {double(x), double(y), double(z)};
  for (int a = 0; a < 3; ++a) {
    const double lo = g.origin[std::size_t(a)] + double(idx[a]) * g.cell_size;
    const double tol =
        1e-4 * g.cell_size + 8 * double(std::numeric_limits<T>::epsilon()) * std::abs(p[a]);
    if (!(p[a] >= lo - tol && p[a] <= lo + g.cell_size + tol)) return false;
  }
  return true;
}

// Per-cell ranges into a cell-sorted order, read the same way whoever built them.
struct CellRanges {
  IndexArray begin, end, order;
  std::int64_t base = 0;
  bool built = false;
};

struct Tallies {
  std::size_t nonfinite = 0, outside = 0, entries = 0;
};

Tallies total(tbb::combinable<Tallies>& tallies) {
  Tallies sum;
  tallies.combine_each([&](const Tallies& t) {
    sum.nonfinite += t.nonfinite;
    sum.outside += t.outside;
    sum.entries += t.entries;
  });
  return sum;
}

// The particle at sorted slot k of the cell ranges.
std::int64_t particle_at(const CellRanges& r, std::int64_t k) {
  return r.order.present() ? r.order[std::size_t(k)] - r.base : k;
}

// The particles' radii: per particle from the view, else the view's one radius, the option's,
// or the spacing.
detail::Radii radii_of(const ParticleView& view, const ClassifyOptions& options) {
  const double given = view.uniform_radius();  // 0: none given
  if (given != 0 && !(given > 0 && std::isfinite(given)))
    throw make_error("the particle view's radius ", given,
                     " is not a positive finite number (0 leaves the options' radius)");
  detail::Radii radii{view.radii(), 0.f};
  const double uniform = view.uniform_radius() > 0 ? view.uniform_radius()
                         : options.radius > 0      ? options.radius
                                                   : options.particle_spacing;
  radii.uniform = static_cast<float>(uniform);
  if (!radii.varies() && !(uniform > 0 && std::isfinite(uniform)))
    throw make_error(
        "no particle radius: give one in the particle view, or set radius or "
        "particle_spacing in the options");
  return radii;
}

// Which particles compact() emits: the owned ones, and the ghosts when asked.
struct Emits {
  std::size_t owned;
  bool ghosts;
  bool operator()(std::size_t i) const { return ghosts || i < owned; }
};

// One cell as count() finds it: its valid particles, and those of them compact() emits unless
// the cell is inner.
struct CellCount {
  std::uint32_t valid = 0, emitted = 0;
};

// count()'s common case: the cell's particles [b, e) stored in cell order, one radius, no
// validation: per particle only the finiteness test.
template <class T>
CellCount count_in_order(const detail::Positions<T>& pos, std::int64_t b, std::int64_t e,
                         const Emits& emits, Tallies& t) {
  CellCount found;
  T x, y, z;
  for (std::int64_t k = b; k < e; ++k) {
    if (!pos.load(std::size_t(k), x, y, z)) {
      ++t.nonfinite;
      continue;
    }
    ++found.valid;
    found.emitted += emits(std::size_t(k)) ? 1 : 0;
  }
  return found;
}

// count()'s case for a grid built here, one radius, no validation: its lists hold only finite
// particles (the others have no cell), each list in ascending index order, the owned first.
CellCount count_built(const std::uint32_t* first, const std::uint32_t* last, const Emits& emits) {
  const auto valid = static_cast<std::uint32_t>(last - first);
  if (emits.ghosts) return {valid, valid};
  const auto owned = std::partition_point(first, last, [&](std::uint32_t i) { return emits(i); });
  return {valid, static_cast<std::uint32_t>(owned - first)};
}

// What count() checks of the grid's lists beyond their ranges, and where it says what it found:
// always that each entry is a particle; under `cells` that the particle lies in the cell that
// lists it; with `seen` (a flag per particle) that no particle is listed twice.
struct CountChecks {
  const GridGeometry& grid;
  std::size_t particles;
  bool cells;
  std::uint8_t* seen;
  detail::FirstError& error;
};

// count()'s general case: cell c's slots [b, e) of the ranges, in any order, radii per particle,
// with the checks.
template <class T>
CellCount count_listed(const detail::Positions<T>& pos, const CellRanges& ranges,
                       const detail::Radii& radii, std::size_t c, std::int64_t b, std::int64_t e,
                       const Emits& emits, const CountChecks& checks, Tallies& t) {
  const GridGeometry& g = checks.grid;
  const std::size_t n = checks.particles;
  CellCount found;
  T x, y, z;
  for (std::int64_t k = b; k < e; ++k) {
    const std::int64_t idx = particle_at(ranges, k);
    if (idx < 0 || idx >= static_cast<std::int64_t>(n)) {
      checks.error.offer(c, "grid order entry ", k, " (in cell ", CellName{g, c}, ") is particle ",
                         idx, ", not one of the ", n, " particles");
      break;
    }
    const auto i = std::size_t(idx);
    if (checks.seen && std::atomic_ref<std::uint8_t>(checks.seen[i]).exchange(1) != 0)
      checks.error.offer(c, "particle ", i, " is listed twice by the grid (again in cell ",
                         CellName{g, c}, ")");
    if (!pos.load(i, x, y, z) || !detail::Radii::usable(radii.get(i))) {
      ++t.nonfinite;
      continue;
    }
    if (checks.cells && !point_in_cell(g, c, x, y, z)) {
      const auto ijk = cell_of_point(g, x, y, z);
      if (std::min({ijk[0], ijk[1], ijk[2]}) < 0)
        checks.error.offer(c, "particle ", i, " at (", x, ", ", y, ", ", z,
                           ") lies in no cell of the grid, which lists it in cell ",
                           CellName{g, c});
      else
        checks.error.offer(c, "particle ", i, " at (", x, ", ", y, ", ", z, ") lies in cell (",
                           ijk[0], ", ", ijk[1], ", ", ijk[2], ") but the grid lists it in cell ",
                           CellName{g, c});
    }
    ++found.valid;
    if (emits(i)) ++found.emitted;
  }
  return found;
}

}  // namespace

struct Classifier::Work {
  Classification result;
  std::vector<AttributeView> requested;  // the attributes asked for, kept from run to run
  std::vector<std::uint32_t> cell_of, offsets, order, sort_scratch;  // cell_ranges()' counting sort
  std::vector<std::uint32_t> counts, emit;                           // count()'s, per cell
  std::vector<std::uint32_t> emit_offsets;                           // compact()'s
  std::vector<std::uint8_t> scratch, seen;  // classify_states()' scratch; count()'s flags

  template <class T>
  void run(const detail::Positions<T>& pos, const ParticleView& view, const GridView& grid,
           const ClassifyOptions& options, const std::vector<AttributeView>& attributes);

 private:
  // The phases of run() (ClassifyPhase), in order.
  template <class T>
  CellRanges cell_ranges(const detail::Positions<T>& pos, std::size_t n, const GridView& grid,
                         const ClassifyOptions& options, Tallies& built);
  template <class T>
  Tallies count(const detail::Positions<T>& pos, const ParticleView& view, const CellRanges& ranges,
                const ClassifyOptions& options, const detail::Radii& radii);
  void classify_states(std::size_t cells);
  void size_attributes(const std::vector<AttributeView>& attributes, std::size_t particles);
  template <class T>
  void compact(const detail::Positions<T>& pos, const ParticleView& view, const CellRanges& ranges,
               const ClassifyOptions& options, const detail::Radii& radii,
               const std::vector<AttributeView>& attributes);

  // cell_ranges()' steps where the solver gives no ranges.
  template <class T>
  GridGeometry bounds_geometry(const detail::Positions<T>& pos, std::size_t n,
                               const ClassifyOptions& options);
  template <class T>
  Tallies cells_from_positions(const detail::Positions<T>& pos, std::size_t n,
                               const GridGeometry& g);
  template <class T>
  Tallies cells_from_index(const detail::Positions<T>& pos, std::size_t n, const GridView& grid);
};

namespace {

void check_geometry(const GridGeometry& g) {
  if (!g.valid() || !std::isfinite(g.cell_size) || !std::isfinite(g.origin[0]) ||
      !std::isfinite(g.origin[1]) || !std::isfinite(g.origin[2]))
    throw make_error("invalid grid geometry: cell size ", g.cell_size, ", dims ", g.dims[0], " x ",
                     g.dims[1], " x ", g.dims[2], ", origin (", g.origin[0], ", ", g.origin[1],
                     ", ", g.origin[2], ")");
  // Cells are counted in 32 bits, and each holds a few bytes of state: a grid this large is a
  // cell size far below the domain's, not a fluid.
  const double cells = double(g.dims[0]) * double(g.dims[1]) * double(g.dims[2]);
  if (cells > 4294967295.0)
    throw make_error("grid of ", g.dims[0], " x ", g.dims[1], " x ", g.dims[2], " cells (", cells,
                     ") has more than 2^32 cells: a cell size (", g.cell_size,
                     ") far below the domain's?");
}

}  // namespace

// Bounds of the finite positions, cells aligned to multiples of the cell size so that the
// classification does not shift when the bounds move a little between steps.
template <class T>
GridGeometry Classifier::Work::bounds_geometry(const detail::Positions<T>& pos, std::size_t n,
                                               const ClassifyOptions& options) {
  double cs = options.cell_size > 0 ? options.cell_size : 2 * options.particle_spacing;
  if (!(cs > 0) || !std::isfinite(cs))
    throw make_error(
        "no grid was given and the cell size is unknown: set cell_size or "
        "particle_spacing (got cell_size ",
        options.cell_size, ", particle_spacing ", options.particle_spacing, ")");
  struct Box {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  };
  Box box = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, kParticleGrain), Box{},
      [&](const tbb::blocked_range<std::size_t>& r, Box b) {
        T p[3];
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          if (!pos.load(i, p[0], p[1], p[2])) continue;
          for (int a = 0; a < 3; ++a) {
            b.lo[a] = std::min(b.lo[a], double(p[a]));
            b.hi[a] = std::max(b.hi[a], double(p[a]));
          }
        }
        return b;
      },
      [](Box a, const Box& b) {
        for (int k = 0; k < 3; ++k) {
          a.lo[k] = std::min(a.lo[k], b.lo[k]);
          a.hi[k] = std::max(a.hi[k], b.hi[k]);
        }
        return a;
      });
  GridGeometry g;
  g.cell_size = cs;
  if (!(box.lo[0] <= box.hi[0])) return g;  // no finite particle: an empty grid
  // Few particles spread far apart: coarser cells keep the grid bounded, by the option and by
  // the particles (64 cells each, 2^20 at least): one stray particle far from the fluid would
  // otherwise cost the option's cells (2^27 by default: about 3 GB and seconds) every step.
  const double most =
      std::min(double(options.max_built_cells), std::max(double(1 << 20), 64.0 * double(n)));
  for (;;) {
    double cells = 1;
    for (int a = 0; a < 3; ++a) {
      const double first = std::floor(box.lo[a] / g.cell_size);
      const double last = std::floor(box.hi[a] / g.cell_size);
      g.origin[std::size_t(a)] = first * g.cell_size;
      const double extent = last - first + 1;
      g.dims[std::size_t(a)] = extent < 1e9 ? int(extent) : 1000000000;
      cells *= extent;
    }
    if (cells <= most) break;
    g.cell_size *= std::cbrt(cells / most) * 1.01;
  }
  return g;
}

namespace {

// cell_of[i] = place(i, x, y, z, tallies) for the finite particles, kNoCell for the others.
template <class T, class Place>
Tallies assign_cells(const detail::Positions<T>& positions, std::size_t n,
                     std::vector<std::uint32_t>& cell_of, Place&& place) {
  cell_of.resize(n);
  tbb::combinable<Tallies> tallies;
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, n, kParticleGrain),
      [&](const tbb::blocked_range<std::size_t>& r) {
        Tallies& t = tallies.local();
        T x, y, z;
        const detail::Positions<T> pos = positions;  // a local copy stays in registers
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          if (!pos.load(i, x, y, z)) {  // a NaN particle has no cell, whatever the solver says
            ++t.nonfinite;
            cell_of[i] = kNoCell;
          } else {
            cell_of[i] = place(i, x, y, z, t);
          }
        }
      });
  return total(tallies);
}

}  // namespace

template <class T>
Tallies Classifier::Work::cells_from_positions(const detail::Positions<T>& pos, std::size_t n,
                                               const GridGeometry& g) {
  return assign_cells(pos, n, cell_of, [g](std::size_t, T x, T y, T z, Tallies& t) {
    const auto ijk = cell_of_point(g, x, y, z);
    if (ijk[0] < 0 || ijk[1] < 0 || ijk[2] < 0) {
      ++t.outside;
      return kNoCell;
    }
    return static_cast<std::uint32_t>(g.linear(int(ijk[0]), int(ijk[1]), int(ijk[2])));
  });
}

template <class T>
Tallies Classifier::Work::cells_from_index(const detail::Positions<T>& pos, std::size_t n,
                                           const GridView& grid) {
  const auto cells = static_cast<std::int64_t>(grid.geometry().cell_count());
  const IndexArray& claimed = grid.cell_of();
  const std::int64_t base = grid.index_base();
  detail::FirstError error;
  const Tallies t = assign_cells(pos, n, cell_of, [&](std::size_t i, T, T, T, Tallies&) {
    const std::int64_t c = claimed[i] - base;
    if (c >= 0 && c < cells) return static_cast<std::uint32_t>(c);
    error.offer(i, "grid cell index of particle ", i, " is ", claimed[i], ", outside the grid's ",
                cells, " cells (index base ", base, ")");
    return kNoCell;
  });
  error.throw_if_raised<GridMismatch>();
  return t;
}

// Count: per cell its valid particles (counts) and those compact() emits from it (emit),
// NaN/inf left out and tallied; the grid's ranges checked always, its lists under `validate`.
template <class T>
Tallies Classifier::Work::count(const detail::Positions<T>& positions, const ParticleView& view,
                                const CellRanges& ranges, const ClassifyOptions& options,
                                const detail::Radii& radii) {
  const GridGeometry& g = result.geometry;
  const std::size_t cells = g.cell_count(), n = view.size();
  const auto n64 = static_cast<std::int64_t>(n);
  const bool check_once = options.validate && !ranges.built;
  counts.resize(cells);
  emit.resize(cells);
  if (check_once) seen.assign(n, 0);

  detail::FirstError error;
  const CountChecks checks{g, n, options.validate, check_once ? seen.data() : nullptr, error};
  const Emits emits{view.owned_count(), options.include_ghosts};
  // The common case: particles stored in cell order, one radius, no validation.
  const bool in_order = !ranges.order.present() && !options.validate && !radii.varies();
  const bool built = ranges.built && !options.validate && !radii.varies();
  tbb::combinable<Tallies> tallies;
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, cells, kCellGrain),
      [&](const tbb::blocked_range<std::size_t>& r) {
        Tallies& t = tallies.local();
        const detail::Positions<T> pos = positions;  // a local copy stays in registers
        for (std::size_t c = r.begin(); c != r.end(); ++c) {
          counts[c] = emit[c] = 0;
          const std::int64_t b = ranges.begin[c] - ranges.base, e = ranges.end[c] - ranges.base;
          if (b == e) continue;
          if (e < b) {
            error.offer(c, "grid cell ", CellName{g, c}, " lists particles [", b, ", ", e,
                        "): its range ends before it begins (offsets must not decrease)");
            continue;
          }
          if (b < 0 || e > n64) {
            error.offer(c, "grid cell ", CellName{g, c}, " lists particles [", b, ", ", e,
                        "), outside the ", n, " particles");
            continue;
          }
          t.entries += std::size_t(e - b);
          const CellCount found = built ? count_built(order.data() + b, order.data() + e, emits)
                                  : in_order
                                      ? count_in_order(pos, b, e, emits, t)
                                      : count_listed(pos, ranges, radii, c, b, e, emits, checks, t);
          counts[c] = found.valid;
          emit[c] = found.emitted;
        }
      });
  error.throw_if_raised<GridMismatch>();
  if (check_once) {
    for (std::size_t i = 0; i < n; ++i)
      if (!seen[i])
        throw GridMismatch(make_error("particle ", i, " is in no cell of the grid").what());
  }
  return total(tallies);
}

// The result's attributes: those asked for, named, with room for `particles` particles each.
void Classifier::Work::size_attributes(const std::vector<AttributeView>& attributes,
                                       std::size_t particles) {
  result.attributes.resize(attributes.size());
  for (std::size_t a = 0; a < attributes.size(); ++a) {
    result.attributes[a].name = std::string(attributes[a].name);
    result.attributes[a].components = attributes[a].components;
    result.attributes[a].values.resize(particles * std::size_t(attributes[a].components));
  }
}

// Compact: the particles of the cells that are not inner, in cell order, into the boundary
// spheres and the attributes asked for; inner cells' emit counts zeroed on the way.
template <class T>
void Classifier::Work::compact(const detail::Positions<T>& positions, const ParticleView& view,
                               const CellRanges& ranges, const ClassifyOptions& options,
                               const detail::Radii& radii,
                               const std::vector<AttributeView>& attributes) {
  const std::size_t cells = result.geometry.cell_count();
  const Emits emits{view.owned_count(), options.include_ghosts};
  const std::array<double, 3> origin = result.origin = options.origin;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 1 << 14),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t c = r.begin(); c != r.end(); ++c)
                        if (cell::is_inner(result.states[c])) emit[c] = 0;
                    });
  emit_offsets.resize(cells + 1);
  const std::size_t total = detail::exclusive_scan(emit, emit_offsets);
  result.boundary.resize(total);
  size_attributes(attributes, total);
  result.counts.boundary = total;

  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, cells, kCellGrain),
      [&](const tbb::blocked_range<std::size_t>& r) {
        T x, y, z;
        const detail::Positions<T> pos = positions;  // a local copy stays in registers
        for (std::size_t c = r.begin(); c != r.end(); ++c) {
          if (emit[c] == 0) continue;
          std::size_t out = emit_offsets[c];
          const std::int64_t b = ranges.begin[c] - ranges.base, e = ranges.end[c] - ranges.base;
          for (std::int64_t k = b; k < e; ++k) {
            const auto i = std::size_t(particle_at(ranges, k));
            if (!emits(i)) continue;
            const float radius = radii.get(i);
            if (!pos.load(i, x, y, z) || !detail::Radii::usable(radius)) continue;
            result.boundary[out] = {float(double(x) - origin[0]), float(double(y) - origin[1]),
                                    float(double(z) - origin[2]), radius};
            for (std::size_t a = 0; a < attributes.size(); ++a) {
              const AttributeView& src = attributes[a];
              float* dst = result.attributes[a].values.data() + out * std::size_t(src.components);
              for (int j = 0; j < src.components; ++j)
                dst[j] = static_cast<float>(src.component[std::size_t(j)][i]);
            }
            ++out;
          }
        }
      });
}

// Ranges: the geometry of result (the grid's, or one fitted to the particles) and the cell
// ranges: the solver's own, or a counting sort of a per-particle cell index (the solver's, or
// computed from the positions), whose tallies go to `built`.
template <class T>
CellRanges Classifier::Work::cell_ranges(const detail::Positions<T>& pos, std::size_t n,
                                         const GridView& grid, const ClassifyOptions& options,
                                         Tallies& built) {
  switch (grid.layout()) {
    case GridView::Layout::none:
    case GridView::Layout::geometry_only:
      result.geometry = grid.layout() == GridView::Layout::none ? bounds_geometry(pos, n, options)
                                                                : grid.geometry();
      if (grid.layout() == GridView::Layout::geometry_only) check_geometry(result.geometry);
      built = cells_from_positions(pos, n, result.geometry);
      break;
    case GridView::Layout::cell_index:
      check_geometry(grid.geometry());
      if (n > 0 && !grid.cell_of().present())
        throw make_error("the grid's per-particle cell index array is missing");
      result.geometry = grid.geometry();
      built = cells_from_index(pos, n, grid);
      break;
    case GridView::Layout::cell_ranges:
      check_geometry(grid.geometry());
      if (!grid.begin().present() || !grid.end().present())
        throw make_error("the grid's cell range arrays (begin/end or offsets) are missing");
      result.geometry = grid.geometry();
      return {grid.begin(), grid.end(), grid.order(), grid.index_base(), false};
  }
  detail::counting_sort(cell_of, result.geometry.cell_count(), offsets, order, sort_scratch);
  return {IndexArray::of(offsets.data()), IndexArray::of(offsets.data() + 1),
          IndexArray::of(order.data()), 0, true};
}

// Classify: the cell states from the counts (occupancy and the inner bit), tallied.
void Classifier::Work::classify_states(std::size_t cells) {
  result.states.resize(cells);
  if (cells > 0)
    detail::classify_cells(result.geometry, counts, result.counts.full_count, result.states,
                           scratch);
  detail::tally_cells(result.states, result.counts);
}

template <class T>
void Classifier::Work::run(const detail::Positions<T>& pos, const ParticleView& view,
                           const GridView& grid, const ClassifyOptions& options,
                           const std::vector<AttributeView>& attributes) {
  // Each phase's wall time, read between the phases (nothing inside them).
  Stopwatch clock;
  const auto lap = [&](ClassifyPhase p) {
    result.phase_ms[std::size_t(p)] = clock.ms();
    clock.restart();
  };
  const std::size_t n = view.size();
  ClassifyCounts& counts_out = result.counts;
  counts_out = {};
  counts_out.particles = n;
  counts_out.owned = view.owned_count();
  const detail::Radii radii = radii_of(view, options);

  Tallies built;
  const CellRanges ranges = cell_ranges(pos, n, grid, options, built);
  const std::size_t cells = result.geometry.cell_count();
  counts_out.grid_built = ranges.built;
  counts_out.cell_size = result.geometry.cell_size;
  counts_out.full_count = full_count_for(options, result.geometry.cell_size);
  lap(ClassifyPhase::ranges);

  const Tallies counted = cells > 0 ? count(pos, view, ranges, options, radii) : Tallies{};
  counts_out.dropped_nonfinite = built.nonfinite + counted.nonfinite;
  counts_out.not_in_grid = ranges.built          ? built.outside
                           : counted.entries < n ? n - counted.entries
                                                 : 0;
  lap(ClassifyPhase::count);

  classify_states(cells);
  lap(ClassifyPhase::classify);

  if (cells > 0) {
    compact(pos, view, ranges, options, radii, attributes);
  } else {
    // No cells (no particles on this rank): the attributes asked for are there, with no
    // values, as the outputs that name them expect on every rank.
    result.boundary.clear();
    result.origin = options.origin;
    size_attributes(attributes, 0);
  }
  lap(ClassifyPhase::compact);

  const auto& ms = result.phase_ms;
  result.seconds_classify =
      1e-3 * (ms[std::size_t(ClassifyPhase::ranges)] + ms[std::size_t(ClassifyPhase::count)] +
              ms[std::size_t(ClassifyPhase::classify)]);
  result.seconds_compact = 1e-3 * ms[std::size_t(ClassifyPhase::compact)];
}

Classifier::Classifier() : work_(std::make_unique<Work>()) {}
Classifier::~Classifier() = default;
Classifier::Classifier(Classifier&&) noexcept = default;
Classifier& Classifier::operator=(Classifier&&) noexcept = default;

const Classification& Classifier::result() const { return work_->result; }

Classification Classifier::take_result() { return std::move(work_->result); }

const Classification& Classifier::run(const ParticleView& view, const GridView& grid,
                                      const ClassifyOptions& options) {
  if (!view.overflowed_attribute().empty())
    throw make_error("too many particle attributes: '", view.overflowed_attribute(),
                     "' is past the limit of ", ParticleView::kMaxAttributes);
  for (int k = 0; k < view.attribute_count(); ++k) {
    const std::string_view name = view.attribute(k).name;
    if (name.empty()) throw make_error("attribute ", k, " of the particle view has no name");
    for (int j = 0; j < k; ++j)
      if (view.attribute(j).name == name)
        throw make_error("the particle view has two attributes named '", name, "' (",
                         view.attribute(j).components, " and ", view.attribute(k).components,
                         " components): one would hide the other");
  }
  std::vector<AttributeView>& attributes = work_->requested;
  attributes.clear();  // keeps its storage: a solver's steady loop allocates nothing here
  for (const std::string& name : options.attributes) {
    const AttributeView* a = view.find_attribute(name);
    if (!a && options.skip_missing_attributes) continue;
    if (!a)
      throw make_error("attribute '", name,
                       "' was asked for but the solver passes no attribute of ", "that name (",
                       attributes_instead(view, name), ")");
    if (a->components != 1 && a->components != 3)
      throw make_error("attribute '", name, "' has ", a->components, " components (1 or 3)");
    for (int j = 0; j < a->components; ++j)
      if (view.size() > 0 && !a->component[std::size_t(j)].present())
        throw make_error("attribute '", name, "' has no data for component ", j);
    attributes.push_back(*a);
  }
  if (view.size() > std::numeric_limits<std::uint32_t>::max() - 1)
    throw make_error("a classification takes at most 2^32 - 2 particles, got ", view.size());

  const ScalarType type = view.axis(0).type;
  if (view.size() > 0) {
    for (int a = 0; a < 3; ++a) {
      if (!view.axis(a).present())
        throw make_error("particle positions are missing (axis ", a, ", ", view.size(),
                         " particles)");
      if (view.axis(a).type != type)
        throw make_error("particle positions mix float and double between axes");
    }
  }
  if (type == ScalarType::float32)
    work_->run(detail::Positions<float>(view), view, grid, options, attributes);
  else work_->run(detail::Positions<double>(view), view, grid, options, attributes);
  return work_->result;
}

namespace {

template <class T>
std::size_t pack_positions(const detail::Positions<T>& pos, const detail::Radii& radii,
                           std::size_t n, std::vector<ParticleSphere>& out) {
  out.resize(n);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n; ++i) {
    T x, y, z;
    const float radius = radii.get(i);
    if (!pos.load(i, x, y, z) || !detail::Radii::usable(radius) || !(radius > 0)) continue;
    out[kept++] = {float(x), float(y), float(z), radius};
  }
  out.resize(kept);
  return n - kept;
}

}  // namespace

std::size_t pack_spheres(const ParticleView& particles, const ClassifyOptions& options,
                         std::vector<ParticleSphere>& out) {
  out.clear();
  if (particles.empty()) return 0;
  for (int a = 0; a < 3; ++a)
    if (!particles.axis(a).present() || particles.axis(a).type != particles.axis(0).type)
      throw make_error("particle positions are missing or mix float and double (axis ", a, ")");
  const detail::Radii radii = radii_of(particles, options);
  if (particles.axis(0).type == ScalarType::float32)
    return pack_positions(detail::Positions<float>(particles), radii, particles.size(), out);
  return pack_positions(detail::Positions<double>(particles), radii, particles.size(), out);
}

std::array<double, 3> frame_origin_near(const std::array<double, 3>& point, double unit) {
  const double reach = std::ldexp(unit, 10);
  // A non-finite point or unit is left to the renderers' own checks.
  bool world = !std::isfinite(reach), near_world_origin = true;
  for (const double c : point) {
    world = world || !std::isfinite(c);
    near_world_origin = near_world_origin && std::abs(c) < reach;
  }
  if (world || near_world_origin) return {0, 0, 0};
  return point;
}

Classification classify(const ParticleView& particles, const GridView& grid,
                        const ClassifyOptions& options) {
  Classifier classifier;
  classifier.run(particles, grid, options);
  return classifier.take_result();
}

}  // namespace voxspan
