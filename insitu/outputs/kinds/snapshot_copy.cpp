#include "insitu/outputs/kinds/snapshot_copy.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "insitu/parallel/byte_packing.h"
#include "sim_adapter/near_name.h"
#include "voxspan/error.h"

namespace voxspan {

void SnapshotCopy::fill(const StepData& data, const AttributeNames& names, double radius) {
  step = data.step;
  time = data.time;
  spheres.assign(data.boundary.begin(), data.boundary.end());
  origin = data.origin;
  if (radius > 0)
    for (ParticleSphere& s : spheres) s.radius = float(radius);
  attributes.resize(names.names.size());
  for (std::size_t k = 0; k < names.names.size(); ++k) {
    const std::string& name = names.names[k];
    const auto found = std::find_if(data.attributes.begin(), data.attributes.end(),
                                    [&](const Attribute& a) { return a.name == name; });
    if (found == data.attributes.end()) {
      if (data.particles == nullptr || data.particles->find_attribute(name) != nullptr)
        throw make_error("attribute \"", name, "\" was not compacted by the adapter");
      throw make_error(names.key, " \"", name, "\": the solver passes no attribute of that name (",
                       attributes_instead(*data.particles, name), ")");
    }
    attributes[k].assign(found->view());
  }
  cells.assign(data.cells);
}

std::vector<AttributeSpan> SnapshotCopy::attribute_spans() const {
  std::vector<AttributeSpan> spans;
  spans.reserve(attributes.size());
  for (const Attribute& a : attributes) spans.push_back(a.view());
  return spans;
}

namespace {

void pack_cells(const CellStatesView& c, Packer& p) {
  p.put(c.origin), p.put(c.cell_size), p.put(c.dims);
  p.put_all<std::uint8_t>(std::span(c.states, c.empty() ? 0 : c.cell_count()));
}

CellStates unpack_cells(Unpacker& u) {
  CellStates c;
  c.origin = u.get<std::array<double, 3>>();
  c.cell_size = u.get<double>();
  c.dims = u.get<std::array<int, 3>>();
  u.get_all(c.states);
  return c;
}

std::vector<std::byte> pack(const SnapshotCopy& c) {
  Packer p;
  p.put_all<ParticleSphere>(c.spheres);
  p.put(std::uint64_t(c.attributes.size()));
  for (const Attribute& a : c.attributes) {
    p.put_all<char>(a.name);
    p.put(a.components);
    p.put_all<float>(a.values);
  }
  pack_cells(c.cells.view(), p);
  return std::move(p.bytes);
}

// A cell two ranks classified (one holds it, the other has it among its ghosts' cells). A rank
// can only miss particles, never see extra ones, so what says more fluid is right: the higher
// occupancy, inner-full when either found it so, inner-empty only when both did.
std::uint8_t combined_state(std::uint8_t a, std::uint8_t b) {
  const std::uint8_t occupancy = std::max(cell::occupancy(a), cell::occupancy(b));
  const bool inner = occupancy == cell::kFull    ? a == cell::kInnerFull || b == cell::kInnerFull
                     : occupancy == cell::kEmpty ? cell::is_inner(a) && cell::is_inner(b)
                                                 : false;
  return std::uint8_t(occupancy | (inner ? cell::kInner : 0));
}

// Every rank's cells in one grid over all of them, on the lattice of the first non-empty one.
CellStates merge_cells(const std::vector<CellStates>& parts) {
  const CellStates* first = nullptr;
  for (const CellStates& c : parts)
    if (!c.states.empty() && first == nullptr) first = &c;
  if (first == nullptr) return {};
  const double h = first->cell_size;
  std::array<long long, 3> lo{}, hi{};
  bool any = false;
  auto offset = [&](const CellStates& c, int a) {
    const double cells = (c.origin[std::size_t(a)] - first->origin[std::size_t(a)]) / h;
    if (std::abs(c.cell_size - h) > 1e-9 * h || std::abs(cells - std::round(cells)) > 1e-6)
      throw make_error("the ranks' grids do not lie on one lattice (cell size ", c.cell_size,
                       " against ", h, ", origins ", cells,
                       " cells apart): their cell states "
                       "cannot go in one grid");
    return std::llround(cells);
  };
  for (const CellStates& c : parts) {
    if (c.states.empty()) continue;
    for (int a = 0; a < 3; ++a) {
      const long long o = offset(c, a), e = o + c.dims[std::size_t(a)];
      lo[std::size_t(a)] = any ? std::min(lo[std::size_t(a)], o) : o;
      hi[std::size_t(a)] = any ? std::max(hi[std::size_t(a)], e) : e;
    }
    any = true;
  }
  CellStates merged;
  merged.cell_size = h;
  for (int a = 0; a < 3; ++a) {
    merged.origin[std::size_t(a)] = first->origin[std::size_t(a)] + double(lo[std::size_t(a)]) * h;
    merged.dims[std::size_t(a)] = int(hi[std::size_t(a)] - lo[std::size_t(a)]);
  }
  // Cells no rank covers are inner-empty air, as outside any grid.
  merged.states.assign(merged.view().cell_count(), cell::kInnerEmpty);
  for (const CellStates& c : parts) {
    if (c.states.empty()) continue;
    const long long ox = offset(c, 0) - lo[0], oy = offset(c, 1) - lo[1], oz = offset(c, 2) - lo[2];
    for (int k = 0; k < c.dims[2]; ++k)
      for (int j = 0; j < c.dims[1]; ++j)
        for (int i = 0; i < c.dims[0]; ++i) {
          const std::uint8_t state =
              c.states[std::size_t(i) +
                       std::size_t(c.dims[0]) * (std::size_t(j) + std::size_t(c.dims[1]) * k)];
          std::uint8_t& into =
              merged.states[std::size_t(i + ox) +
                            std::size_t(merged.dims[0]) *
                                (std::size_t(j + oy) + std::size_t(merged.dims[1]) * (k + oz))];
          into = combined_state(into, state);
        }
  }
  return merged;
}

}  // namespace

bool SnapshotCopy::gather(Communicator& comm) {
  const std::vector<std::vector<std::byte>> all = comm.gather(pack(*this));
  if (!comm.root()) return false;
  std::vector<ParticleSphere> spheres_all;
  std::vector<Attribute> attributes_all = attributes;
  for (Attribute& a : attributes_all) a.values.clear();
  std::vector<CellStates> cells_all(all.size());
  for (std::size_t r = 0; r < all.size(); ++r) {
    Unpacker u(all[r], "a rank's snapshot copy");
    std::vector<ParticleSphere> s;
    u.get_all(s);
    spheres_all.insert(spheres_all.end(), s.begin(), s.end());
    const auto n = u.get<std::uint64_t>();
    if (n != attributes_all.size()) throw make_error("rank ", r, " sent ", n, " attributes");
    for (Attribute& a : attributes_all) {
      std::vector<char> name;
      u.get_all(name);
      const int components = u.get<int>();
      std::vector<float> values;
      u.get_all(values);
      if (std::string(name.begin(), name.end()) != a.name || components != a.components)
        throw make_error("rank ", r, " sent attribute ", std::string(name.begin(), name.end()),
                         " where ", a.name, " was expected");
      a.values.insert(a.values.end(), values.begin(), values.end());
    }
    cells_all[r] = unpack_cells(u);
  }
  spheres = std::move(spheres_all);
  attributes = std::move(attributes_all);
  cells = merge_cells(cells_all);
  return true;
}

CellStates gather_cells(Communicator& comm, const CellStatesView& mine) {
  Packer p;
  pack_cells(mine, p);
  const std::vector<std::vector<std::byte>> all = comm.gather(p.bytes);
  if (!comm.root()) return {};
  std::vector<CellStates> parts;
  for (const std::vector<std::byte>& bytes : all) {
    Unpacker u(bytes, "a rank's cell states");
    parts.push_back(unpack_cells(u));
  }
  return merge_cells(parts);
}

}  // namespace voxspan
