// The C API of voxspan/voxspan.h: thin wrappers over voxspan/adapter.h that never let an
// exception reach the caller. The particle and grid handles keep the solver's pointers and
// build the (allocation-free) C++ views on each execute.
#include "voxspan/voxspan.h"

#include <algorithm>
#include <array>
#include <exception>
#include <string>
#include <vector>

#include "voxspan/adapter.h"
#include "voxspan/error.h"
#include "voxspan/insitu.h"
#include "voxspan/log.h"
#include "voxspan/version.h"

struct voxspan_adapter {
  voxspan::AdapterOptions options;
  std::unique_ptr<voxspan::Adapter> adapter;
};

struct voxspan_particles {
  struct Attribute {
    std::string name;
    int components;
    voxspan::StridedScalars component[3];
  };
  voxspan::ParticleView view;  // positions, owned count, radii; attributes added on use
  std::vector<Attribute> attributes;

  voxspan::ParticleView build() const {
    voxspan::ParticleView v = view;
    for (const Attribute& a : attributes)
      v.with_attribute({a.name, a.components, {a.component[0], a.component[1], a.component[2]}});
    return v;
  }
};

struct voxspan_grid {
  voxspan::GridView view;
};

namespace {

thread_local std::string last_error;

int fail(int code, const std::string& message) {
  try {
    last_error = message;
  } catch (...) {}
  return code;
}

// Runs f, turning any exception into a status and the thread's last error.
template <class F> int guarded(const char* function, F&& f) noexcept {
  try {
    last_error.clear();
    return f();
  } catch (const voxspan::Error& e) {
    return fail(VOXSPAN_INVALID_INPUT, std::string(function) + ": " + e.what());
  } catch (const std::exception& e) {
    return fail(VOXSPAN_INTERNAL_ERROR, std::string(function) + ": " + e.what());
  } catch (...) {
    return fail(VOXSPAN_INTERNAL_ERROR, std::string(function) + ": unknown exception");
  }
}

void require(const void* p, const char* what) {
  if (!p) throw voxspan::make_error(what, " is NULL");
}

voxspan::AdapterOptions adapter_options(const voxspan_adapter_options* o) {
  require(o, "options");
  voxspan::AdapterOptions options;
  options.render_every = o->render_every;
  voxspan::ClassifyOptions& c = options.classify;
  c.particle_spacing = o->particle_spacing;
  c.full_count = o->full_count;
  c.full_fraction = o->full_fraction;
  c.radius = o->particle_radius;
  c.cell_size = o->cell_size;
  c.validate = o->validate != 0;
  c.include_ghosts = o->include_ghosts != 0;
  if (o->has_mpi_comm) options.mpi_comm = o->mpi_comm;
  return options;
}

voxspan::ScalarType scalar_type(int type) {
  if (type == VOXSPAN_FLOAT32) return voxspan::ScalarType::float32;
  if (type == VOXSPAN_FLOAT64) return voxspan::ScalarType::float64;
  throw voxspan::make_error("scalar type ", type,
                            " is neither VOXSPAN_FLOAT32 (0) nor "
                            "VOXSPAN_FLOAT64 (1)");
}

std::size_t scalar_size(voxspan::ScalarType t) { return t == voxspan::ScalarType::float32 ? 4 : 8; }

// `count` values of `type` from data, `stride` bytes apart (0: packed).
voxspan::StridedScalars strided(int type, const void* data, std::size_t stride,
                                std::size_t offset_values = 0) {
  const voxspan::ScalarType t = scalar_type(type);
  return {static_cast<const char*>(data) + offset_values * scalar_size(t), t,
          stride ? stride : scalar_size(t)};
}

// A stride given (not 0) must step past one particle's `values` scalars: a smaller one reads the
// particles overlapping, as garbage.
void require_stride(int type, std::size_t stride, int values, const std::string& what) {
  const std::size_t least = std::size_t(values) * scalar_size(scalar_type(type));
  if (stride != 0 && stride < least)
    throw voxspan::make_error(what, ": a stride of ", stride, " bytes is less than one particle's ",
                              values == 3 ? "x, y, z" : "value", " (", least, " bytes)");
}

voxspan::IndexArray index_array(int type, const void* data) {
  if (type < VOXSPAN_INT32 || type > VOXSPAN_UINT64)
    throw voxspan::make_error("index type ", type,
                              " is not one of VOXSPAN_INT32, _UINT32, "
                              "_INT64, _UINT64 (0-3)");
  return {data, static_cast<voxspan::IndexType>(type)};
}

voxspan::GridGeometry geometry(const double origin[3], double cell_size, const int dims[3]) {
  require(origin, "grid origin");
  require(dims, "grid dims");
  voxspan::GridGeometry g{
      {origin[0], origin[1], origin[2]}, cell_size, {dims[0], dims[1], dims[2]}};
  if (!g.valid())
    throw voxspan::make_error("grid geometry: cell size ", cell_size, " and dims ", dims[0], " x ",
                              dims[1], " x ", dims[2], " must all be > 0");
  return g;
}

// Keeps the order and index base across a change of ranges.
void set_ranges(voxspan_grid* grid, voxspan::GridView view) {
  view.with_order(grid->view.order()).with_index_base(grid->view.index_base());
  grid->view = view;
}

voxspan_particles::Attribute& attribute_slot(voxspan_particles* p, const char* name) {
  require(name, "attribute name");
  if (!*name) throw voxspan::make_error("attribute name is empty");
  for (auto& a : p->attributes)
    if (a.name == name) return a;
  if (int(p->attributes.size()) >= voxspan::ParticleView::kMaxAttributes)
    throw voxspan::make_error("attribute '", name, "': at most ",
                              voxspan::ParticleView::kMaxAttributes, " attributes");
  p->attributes.push_back({name, 0, {}});
  return p->attributes.back();
}

// The walls `from` was given, given to `to` (an adapter made again with other options).
void carry_scenery(const voxspan::Adapter& from, voxspan::Adapter& to) {
  const std::span<const voxspan::ParticleSphere> walls = from.scenery();
  if (walls.empty()) return;
  constexpr std::size_t stride = sizeof(voxspan::ParticleSphere);
  to.set_scenery(voxspan::ParticleView::aos(&walls[0].x, walls.size(), stride)
                     .with_radii(&walls[0].radius, stride));
}

int execute_step(const char* function, voxspan_adapter* a, int64_t step, double time,
                 const voxspan_particles* particles, const voxspan_grid* grid, bool last) {
  return guarded(function, [&] {
    require(a, "adapter");
    require(particles, "particles");
    const voxspan::ParticleView view = particles->build();
    const voxspan::GridView g = grid ? grid->view : voxspan::GridView();
    const voxspan::Status s = last ? a->adapter->execute_last(step, time, view, g)
                                   : a->adapter->execute(step, time, view, g);
    return s.ok() ? VOXSPAN_OK : fail(static_cast<int>(s.code), s.message);
  });
}

}  // namespace

extern "C" {

const char* voxspan_version(void) { return voxspan::version(); }

void voxspan_set_log_level(int level) {
  if (level < 0) level = 0;
  if (level > 3) level = 3;
  voxspan::set_log_level(static_cast<voxspan::LogLevel>(level));
}

const char* voxspan_last_error(void) { return last_error.c_str(); }

void voxspan_adapter_options_init(voxspan_adapter_options* o) {
  if (!o) return;
  const voxspan::AdapterOptions d;
  const voxspan::ClassifyOptions& c = d.classify;
  *o = {d.render_every,
        c.particle_spacing,
        c.full_count,
        c.full_fraction,
        c.radius,
        c.cell_size,
        c.validate ? 1 : 0,
        c.include_ghosts ? 1 : 0,
        0,
        0};
}

voxspan_adapter* voxspan_adapter_create(const voxspan_adapter_options* o) {
  voxspan_adapter* result = nullptr;
  guarded("voxspan_adapter_create", [&] {
    auto a = std::make_unique<voxspan_adapter>();
    a->options = adapter_options(o);
    a->adapter = std::make_unique<voxspan::Adapter>(a->options);
    result = a.release();
    return VOXSPAN_OK;
  });
  return result;
}

voxspan_adapter* voxspan_adapter_create_from_config(const voxspan_adapter_options* o,
                                                    const char* config_path) {
  voxspan_adapter* result = nullptr;
  guarded("voxspan_adapter_create_from_config", [&] {
    require(config_path, "config path");
    auto a = std::make_unique<voxspan_adapter>();
    a->adapter = std::make_unique<voxspan::Adapter>(
        voxspan::adapter_from_config_file(config_path, adapter_options(o)));
    a->options = a->adapter->options();
    result = a.release();
    return VOXSPAN_OK;
  });
  return result;
}

int voxspan_adapter_finish(voxspan_adapter* a) {
  return guarded("voxspan_adapter_finish", [&] {
    require(a, "adapter");
    a->adapter->finish();
    return VOXSPAN_OK;
  });
}

size_t voxspan_adapter_summary(const voxspan_adapter* a, char* buffer, size_t size) {
  std::string summary;
  try {
    if (a) summary = a->adapter->summary();
  } catch (...) {
    summary.clear();
  }
  if (buffer && size > 0) {
    const size_t n = summary.size() < size - 1 ? summary.size() : size - 1;
    summary.copy(buffer, n);
    buffer[n] = '\0';
  }
  return summary.size();
}

void voxspan_adapter_destroy(voxspan_adapter* adapter) { delete adapter; }

int voxspan_adapter_add_attribute(voxspan_adapter* a, const char* name) {
  return guarded("voxspan_adapter_add_attribute", [&] {
    require(a, "adapter");
    require(name, "attribute name");
    voxspan::AdapterOptions options = a->options;
    options.classify.attributes.push_back(name);
    auto replacement = std::make_unique<voxspan::Adapter>(options);  // checks the name
    replacement->set_pipeline(a->adapter->pipeline());               // the runtime stays
    carry_scenery(*a->adapter, *replacement);
    a->options = std::move(options);
    a->adapter = std::move(replacement);
    return VOXSPAN_OK;
  });
}

int voxspan_adapter_set_scenery(voxspan_adapter* a, const voxspan_particles* scenery,
                                size_t* kept) {
  return guarded("voxspan_adapter_set_scenery", [&] {
    require(a, "adapter");
    require(scenery, "scenery");
    const std::size_t n = a->adapter->set_scenery(scenery->build());
    if (kept) *kept = n;
    return VOXSPAN_OK;
  });
}

int voxspan_adapter_execute(voxspan_adapter* a, int64_t step, double time,
                            const voxspan_particles* particles, const voxspan_grid* grid) {
  return execute_step("voxspan_adapter_execute", a, step, time, particles, grid, false);
}

int voxspan_adapter_execute_last(voxspan_adapter* a, int64_t step, double time,
                                 const voxspan_particles* particles, const voxspan_grid* grid) {
  return execute_step("voxspan_adapter_execute_last", a, step, time, particles, grid, true);
}

int voxspan_adapter_is_render_step(const voxspan_adapter* a, int64_t step, double time) {
  return a && a->adapter->is_render_step(step, time) ? 1 : 0;
}

int voxspan_adapter_stats(const voxspan_adapter* a, voxspan_step_stats* out) {
  return guarded("voxspan_adapter_stats", [&] {
    require(a, "adapter");
    require(out, "stats");
    const voxspan::StepStats& s = a->adapter->last_stats();
    const voxspan::ClassifyCounts& c = s.counts;
    *out = {s.step,
            s.time,
            s.rendered ? 1 : 0,
            static_cast<int>(s.status.code),
            c.particles,
            c.owned,
            c.boundary,
            c.dropped_nonfinite,
            c.not_in_grid,
            c.cells,
            c.cells_empty,
            c.cells_partial,
            c.cells_full,
            c.cells_inner_empty,
            c.cells_inner_full,
            c.full_count,
            c.grid_built ? 1 : 0,
            c.cell_size,
            s.seconds_classify,
            s.seconds_compact,
            s.seconds_pipeline,
            s.seconds_total};
    return VOXSPAN_OK;
  });
}

size_t voxspan_adapter_boundary(const voxspan_adapter* a, const float** xyzr) {
  if (!a || !xyzr) return 0;
  const auto& b = a->adapter->last_classification().boundary;
  *xyzr = b.empty() ? nullptr : &b[0].x;
  return b.size();
}

void voxspan_adapter_boundary_origin(const voxspan_adapter* a, double origin[3]) {
  if (!a || !origin) return;
  const std::array<double, 3>& o = a->adapter->last_classification().origin;
  std::copy(o.begin(), o.end(), origin);
}

size_t voxspan_adapter_scenery(const voxspan_adapter* a, const float** xyzr) {
  if (!a || !xyzr) return 0;
  const std::span<const voxspan::ParticleSphere> walls = a->adapter->scenery();
  *xyzr = walls.empty() ? nullptr : &walls[0].x;
  return walls.size();
}

size_t voxspan_adapter_cell_states(const voxspan_adapter* a, double origin[3], double* cell_size,
                                   int dims[3], const uint8_t** states) {
  if (!a) return 0;
  const voxspan::CellStatesView v = a->adapter->last_classification().cell_states();
  for (int k = 0; k < 3; ++k) {
    if (origin) origin[k] = v.origin[std::size_t(k)];
    if (dims) dims[k] = v.dims[std::size_t(k)];
  }
  if (cell_size) *cell_size = v.cell_size;
  if (states) *states = v.states;
  return v.empty() ? 0 : v.cell_count();
}

size_t voxspan_adapter_attribute(const voxspan_adapter* a, const char* name, const float** values,
                                 int* components) {
  if (!a || !name) return 0;
  for (const auto& attr : a->adapter->last_classification().attributes) {
    if (attr.name != name) continue;
    if (values) *values = attr.values.data();
    if (components) *components = attr.components;
    return attr.values.size();
  }
  return 0;
}

voxspan_particles* voxspan_particles_create(void) {
  voxspan_particles* p = nullptr;
  guarded("voxspan_particles_create", [&] {
    p = new voxspan_particles();
    return VOXSPAN_OK;
  });
  return p;
}

void voxspan_particles_destroy(voxspan_particles* p) { delete p; }

int voxspan_particles_set_aos(voxspan_particles* p, int type, const void* xyz, size_t count,
                              size_t stride_bytes) {
  return guarded("voxspan_particles_set_aos", [&] {
    require(p, "particles");
    if (count > 0) require(xyz, "positions");
    require_stride(type, stride_bytes, 3, "positions");
    const voxspan::StridedScalars x =
        strided(type, xyz, stride_bytes ? stride_bytes : 3 * scalar_size(scalar_type(type)));
    const auto axis = [&](std::size_t k) {
      return voxspan::StridedScalars{static_cast<const char*>(x.data) + k * scalar_size(x.type),
                                     x.type, x.stride};
    };
    const voxspan::ParticleView old = p->view;
    p->view = voxspan::ParticleView::from_axes(x, axis(1), axis(2), count);
    p->view.with_radius(old.uniform_radius()).with_radii(old.radii());
    return VOXSPAN_OK;
  });
}

int voxspan_particles_set_soa(voxspan_particles* p, int type, const void* x, const void* y,
                              const void* z, size_t count) {
  return guarded("voxspan_particles_set_soa", [&] {
    require(p, "particles");
    if (count > 0) {
      require(x, "x positions");
      require(y, "y positions");
      require(z, "z positions");
    }
    const voxspan::ParticleView old = p->view;
    p->view = voxspan::ParticleView::from_axes(strided(type, x, 0), strided(type, y, 0),
                                               strided(type, z, 0), count);
    p->view.with_radius(old.uniform_radius()).with_radii(old.radii());
    return VOXSPAN_OK;
  });
}

int voxspan_particles_set_owned(voxspan_particles* p, size_t owned) {
  return guarded("voxspan_particles_set_owned", [&] {
    require(p, "particles");
    p->view.with_owned(owned);
    return VOXSPAN_OK;
  });
}

int voxspan_particles_set_radius(voxspan_particles* p, double radius) {
  return guarded("voxspan_particles_set_radius", [&] {
    require(p, "particles");
    p->view.with_radius(radius);
    return VOXSPAN_OK;
  });
}

int voxspan_particles_set_radii(voxspan_particles* p, int type, const void* radii,
                                size_t stride_bytes) {
  return guarded("voxspan_particles_set_radii", [&] {
    require(p, "particles");
    if (radii) require_stride(type, stride_bytes, 1, "radii");
    p->view.with_radii(radii ? strided(type, radii, stride_bytes) : voxspan::StridedScalars{});
    return VOXSPAN_OK;
  });
}

int voxspan_particles_set_scalar(voxspan_particles* p, const char* name, int type,
                                 const void* values, size_t stride_bytes) {
  return guarded("voxspan_particles_set_scalar", [&] {
    require(p, "particles");
    require(values, "attribute values");
    require_stride(type, stride_bytes, 1, "attribute '" + std::string(name ? name : "") + "'");
    const voxspan::StridedScalars v = strided(type, values, stride_bytes);
    attribute_slot(p, name) = {name, 1, {v, {}, {}}};
    return VOXSPAN_OK;
  });
}

int voxspan_particles_set_vector(voxspan_particles* p, const char* name, int type, const void* xyz,
                                 size_t stride_bytes) {
  return guarded("voxspan_particles_set_vector", [&] {
    require(p, "particles");
    require(xyz, "attribute values");
    require_stride(type, stride_bytes, 3, "attribute '" + std::string(name ? name : "") + "'");
    const std::size_t stride = stride_bytes ? stride_bytes : 3 * scalar_size(scalar_type(type));
    attribute_slot(p, name) = {name,
                               3,
                               {strided(type, xyz, stride, 0), strided(type, xyz, stride, 1),
                                strided(type, xyz, stride, 2)}};
    return VOXSPAN_OK;
  });
}

void voxspan_particles_clear_attributes(voxspan_particles* p) {
  if (p) p->attributes.clear();
}

voxspan_grid* voxspan_grid_create(void) {
  voxspan_grid* g = nullptr;
  guarded("voxspan_grid_create", [&] {
    g = new voxspan_grid();
    return VOXSPAN_OK;
  });
  return g;
}

void voxspan_grid_destroy(voxspan_grid* g) { delete g; }

int voxspan_grid_set_offsets(voxspan_grid* g, const double origin[3], double cell_size,
                             const int dims[3], int index_type, const void* offsets) {
  return guarded("voxspan_grid_set_offsets", [&] {
    require(g, "grid");
    require(offsets, "offsets");
    set_ranges(g, voxspan::GridView::offsets(geometry(origin, cell_size, dims),
                                             index_array(index_type, offsets)));
    return VOXSPAN_OK;
  });
}

int voxspan_grid_set_begin_end(voxspan_grid* g, const double origin[3], double cell_size,
                               const int dims[3], int index_type, const void* begin,
                               const void* end) {
  return guarded("voxspan_grid_set_begin_end", [&] {
    require(g, "grid");
    require(begin, "begin");
    require(end, "end");
    set_ranges(g, voxspan::GridView::begin_end(geometry(origin, cell_size, dims),
                                               index_array(index_type, begin),
                                               index_array(index_type, end)));
    return VOXSPAN_OK;
  });
}

int voxspan_grid_set_cell_index(voxspan_grid* g, const double origin[3], double cell_size,
                                const int dims[3], int index_type, const void* cell_of) {
  return guarded("voxspan_grid_set_cell_index", [&] {
    require(g, "grid");
    require(cell_of, "cell index array");
    set_ranges(g, voxspan::GridView::cell_index(geometry(origin, cell_size, dims),
                                                index_array(index_type, cell_of)));
    return VOXSPAN_OK;
  });
}

int voxspan_grid_set_geometry(voxspan_grid* g, const double origin[3], double cell_size,
                              const int dims[3]) {
  return guarded("voxspan_grid_set_geometry", [&] {
    require(g, "grid");
    set_ranges(g, voxspan::GridView::geometry_only(geometry(origin, cell_size, dims)));
    return VOXSPAN_OK;
  });
}

int voxspan_grid_set_order(voxspan_grid* g, int index_type, const void* order) {
  return guarded("voxspan_grid_set_order", [&] {
    require(g, "grid");
    g->view.with_order(order ? index_array(index_type, order) : voxspan::IndexArray{});
    return VOXSPAN_OK;
  });
}

int voxspan_grid_set_index_base(voxspan_grid* g, int base) {
  return guarded("voxspan_grid_set_index_base", [&] {
    require(g, "grid");
    if (base != 0 && base != 1) throw voxspan::make_error("index base ", base, " is not 0 or 1");
    g->view.with_index_base(base);
    return VOXSPAN_OK;
  });
}

void voxspan_grid_clear(voxspan_grid* g) {
  if (g) g->view = voxspan::GridView();
}

}  // extern "C"
