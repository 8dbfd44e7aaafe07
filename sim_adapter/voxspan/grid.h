// voxspan/grid.h - a zero-copy view of a solver's neighbour-search grid, in the layouts
// solvers really use:
//   * cell ranges ("compact grid"): per cell a half-open range [begin, end) into a cell-sorted
//     particle order, given as offsets (one array of cells + 1 entries, CSR style) or as two
//     arrays begin[] and end[]; the order is the particles' own storage order, or an index
//     array order[k] = particle index when the solver sorts an index list instead;
//   * a per-particle cell index (cell_of[i]), particles in any order;
//   * only the geometry (the solver has no grid it can share): the adapter sorts the particles
//     into this geometry itself with a counting sort;
//   * none: the adapter also chooses the geometry (the particles' bounds, AdapterOptions).
// Cells are numbered x fastest: cell (i, j, k) is i + dims[0] * (j + dims[1] * k), and covers
// [origin + (i, j, k) * cell_size, origin + (i+1, j+1, k+1) * cell_size).
// Every index may be 32- or 64-bit, signed or unsigned, and 0- or 1-based (Fortran).
// Standard library only.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace voxspan {

struct GridGeometry {
  std::array<double, 3> origin{0, 0, 0};
  double cell_size = 0;
  std::array<int, 3> dims{0, 0, 0};

  std::size_t cell_count() const {
    return std::size_t(dims[0]) * std::size_t(dims[1]) * std::size_t(dims[2]);
  }
  std::size_t linear(int i, int j, int k) const {
    return std::size_t(i) +
           std::size_t(dims[0]) * (std::size_t(j) + std::size_t(dims[1]) * std::size_t(k));
  }
  bool valid() const { return cell_size > 0 && dims[0] > 0 && dims[1] > 0 && dims[2] > 0; }
};

enum class IndexType : std::uint8_t { int32, uint32, int64, uint64 };

// A read-only array of integer indices of any of the four index types.
struct IndexArray {
  const void* data = nullptr;
  IndexType type = IndexType::uint32;

  bool present() const { return data != nullptr; }
  // The raw value (before the index base is applied).
  std::int64_t operator[](std::size_t i) const {
    switch (type) {
      case IndexType::int32: return static_cast<const std::int32_t*>(data)[i];
      case IndexType::uint32: return static_cast<const std::uint32_t*>(data)[i];
      case IndexType::int64: return static_cast<const std::int64_t*>(data)[i];
      case IndexType::uint64:
        return static_cast<std::int64_t>(static_cast<const std::uint64_t*>(data)[i]);
    }
    return 0;
  }
  std::size_t element_size() const {
    return type == IndexType::int32 || type == IndexType::uint32 ? 4 : 8;
  }

  template <class I> static IndexArray of(const I* d) {
    static_assert(std::is_integral_v<I> && (sizeof(I) == 4 || sizeof(I) == 8),
                  "grid indices must be 32- or 64-bit integers");
    IndexType t = sizeof(I) == 4 ? (std::is_signed_v<I> ? IndexType::int32 : IndexType::uint32)
                                 : (std::is_signed_v<I> ? IndexType::int64 : IndexType::uint64);
    return {d, t};
  }
};

class GridView {
 public:
  enum class Layout : std::uint8_t { none, geometry_only, cell_ranges, cell_index };

  // No grid: the adapter chooses a geometry and sorts the particles itself.
  GridView() = default;
  static GridView none() { return GridView(); }

  // The geometry only: the adapter sorts the particles into it.
  static GridView geometry_only(const GridGeometry& g) {
    GridView v;
    v.layout_ = Layout::geometry_only;
    v.geometry_ = g;
    return v;
  }
  // Compact grid, CSR offsets: cell c holds sorted positions [offsets[c], offsets[c+1]).
  template <class I> static GridView offsets(const GridGeometry& g, const I* offsets) {
    return begin_end(g, offsets, offsets + 1);
  }
  static GridView offsets(const GridGeometry& g, IndexArray offsets) {
    IndexArray end{static_cast<const char*>(offsets.data) + offsets.element_size(), offsets.type};
    return begin_end(g, offsets, end);
  }
  // Compact grid, two arrays: cell c holds sorted positions [begin[c], end[c]). Empty cells
  // need begin == end (any value).
  template <class I>
  static GridView begin_end(const GridGeometry& g, const I* begin, const I* end) {
    return begin_end(g, IndexArray::of(begin), IndexArray::of(end));
  }
  static GridView begin_end(const GridGeometry& g, IndexArray begin, IndexArray end) {
    GridView v = geometry_only(g);
    v.layout_ = Layout::cell_ranges;
    v.begin_ = begin;
    v.end_ = end;
    return v;
  }
  // Per-particle cell index: particle i lies in cell cell_of[i]; particles in any order.
  template <class I> static GridView cell_index(const GridGeometry& g, const I* cell_of) {
    return cell_index(g, IndexArray::of(cell_of));
  }
  static GridView cell_index(const GridGeometry& g, IndexArray cell_of) {
    GridView v = geometry_only(g);
    v.layout_ = Layout::cell_index;
    v.cell_of_ = cell_of;
    return v;
  }

  // For cell ranges: the k-th particle in cell order is particle order[k] (default: the
  // particles are stored in cell order, k itself).
  template <class I> GridView& with_order(const I* order) {
    return with_order(IndexArray::of(order));
  }
  GridView& with_order(IndexArray order) {
    order_ = order;
    return *this;
  }
  // 1 when every index (begin, end, order, cell index) counts from 1, as in Fortran.
  GridView& with_index_base(int base) {
    index_base_ = base;
    return *this;
  }

  Layout layout() const { return layout_; }
  const GridGeometry& geometry() const { return geometry_; }
  const IndexArray& begin() const { return begin_; }
  const IndexArray& end() const { return end_; }
  const IndexArray& order() const { return order_; }
  const IndexArray& cell_of() const { return cell_of_; }
  int index_base() const { return index_base_; }

 private:
  Layout layout_ = Layout::none;
  GridGeometry geometry_{};
  IndexArray begin_{}, end_{}, order_{}, cell_of_{};
  int index_base_ = 0;
};

}  // namespace voxspan
