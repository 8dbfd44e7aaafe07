// python/voxspan_module.cpp - the compiled part of the Python module `voxspan` (pybind11): the
// adapter as the C++ API has it (voxspan/adapter.h, voxspan/insitu.h), the particle-file
// readers and the spacing estimate. python/voxspan/__init__.py adds the offline render call.
//
// Arrays are viewed, never copied: a numpy array of float32 or float64 with any positive
// strides numpy allows becomes a StridedScalars pointing at its memory, valid for the one call
// that holds the array (the runtime copies what it keeps before execute() returns). Anything
// that cannot be viewed is a TypeError (not an array, wrong dtype) or a ValueError (wrong shape
// or length, negative or misaligned strides) naming the argument; the library's own errors are
// voxspan.Error with its message. execute() releases the GIL while the step runs.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <functional>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "insitu/io/particle_data.h"
#include "insitu/io/spacing_estimate.h"
#include "insitu/outputs/formats/png_image.h"
#include "insitu/runtime/adapter_config.h"
#include "insitu/runtime/config_file.h"
#include "insitu/runtime/pipeline.h"
#include "voxspan/adapter.h"
#include "voxspan/error.h"
#include "voxspan/version.h"

namespace py = pybind11;

namespace voxspan::python {
namespace {

std::string text(py::handle object) { return py::str(object); }
std::string type_name(py::handle object) { return py::str(py::type::of(object).attr("__name__")); }

// `object` as a numpy array (never converted: a list would need a copy).
py::array as_array(py::handle object, const std::string& argument) {
  if (!py::isinstance<py::array>(object))
    throw py::type_error(argument + " must be a numpy array, got " + type_name(object));
  return py::reinterpret_borrow<py::array>(object);
}

bool native_order(const py::dtype& d) {
  const char order = d.byteorder();
  constexpr char native = std::endian::native == std::endian::little ? '<' : '>';
  return order == '=' || order == '|' || order == native;
}

// The element type of a float array, or a TypeError naming the argument.
ScalarType float_type(const py::array& a, const std::string& argument) {
  const py::dtype d = a.dtype();
  if (d.kind() == 'f' && native_order(d) && (d.itemsize() == 4 || d.itemsize() == 8))
    return d.itemsize() == 4 ? ScalarType::float32 : ScalarType::float64;
  throw py::type_error(argument + " must be float32 or float64, got " + text(d));
}

// Stride `stride` (bytes) along one axis of `a`, checked to be viewable without a copy.
std::size_t viewable_stride(const py::array& a, py::ssize_t stride, py::ssize_t length,
                            const std::string& argument) {
  const auto item = std::size_t(a.itemsize());
  // An empty array is never read through its strides, and numpy gives it zero strides on every
  // axis (zeros((0, 3)) has strides (0, 0)): a rank with no particles is zero rows, not an error.
  if (a.size() == 0) return item;
  if (length > 1 && stride <= 0)
    throw py::value_error(argument +
                          " has a negative or zero stride, which cannot be viewed; pass "
                          "numpy.ascontiguousarray(" +
                          argument + ")");
  if (reinterpret_cast<std::uintptr_t>(a.data()) % item != 0 ||
      std::size_t(stride < 0 ? -stride : stride) % item != 0)
    throw py::value_error(argument +
                          " is not aligned to its element size, which cannot be "
                          "viewed; pass a copy (numpy.ascontiguousarray)");
  return length > 1 ? std::size_t(stride) : item;
}

// A 1-D float array of `count` values as the library's strided view.
StridedScalars column(py::handle object, const std::string& argument,
                      std::optional<std::size_t> count) {
  const py::array a = as_array(object, argument);
  const ScalarType type = float_type(a, argument);
  if (a.ndim() != 1)
    throw py::value_error(argument + " must be one-dimensional, got shape " +
                          text(py::cast(a.request().shape)));
  if (count && std::size_t(a.shape(0)) != *count)
    throw py::value_error(argument + " has " + std::to_string(a.shape(0)) + " values; expected " +
                          std::to_string(*count));
  return {a.data(), type, viewable_stride(a, a.strides(0), a.shape(0), argument)};
}

// An (n, 3) float array as three strided views (x, y, z of a particle anywhere numpy puts them).
std::array<StridedScalars, 3> columns3(py::handle object, const std::string& argument,
                                       std::optional<std::size_t> count) {
  const py::array a = as_array(object, argument);
  const ScalarType type = float_type(a, argument);
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw py::value_error(argument + " must have shape (n, 3), got " +
                          text(py::cast(a.request().shape)));
  if (count && std::size_t(a.shape(0)) != *count)
    throw py::value_error(argument + " has " + std::to_string(a.shape(0)) + " rows; expected " +
                          std::to_string(*count));
  const std::size_t row = viewable_stride(a, a.strides(0), a.shape(0), argument);
  const std::size_t step = viewable_stride(a, a.strides(1), 3, argument);
  const char* base = static_cast<const char*>(a.data());
  return {StridedScalars{base, type, row}, StridedScalars{base + step, type, row},
          StridedScalars{base + 2 * step, type, row}};
}

// A 1-D C-contiguous integer array as the grid's index view.
IndexArray index_array(py::handle object, const std::string& argument, std::size_t count) {
  const py::array a = as_array(object, argument);
  const py::dtype d = a.dtype();
  if ((d.kind() != 'i' && d.kind() != 'u') || !native_order(d) ||
      (d.itemsize() != 4 && d.itemsize() != 8))
    throw py::type_error(argument + " must be a 32- or 64-bit integer array, got " + text(d));
  if (a.ndim() != 1 || std::size_t(a.shape(0)) != count)
    throw py::value_error(argument + " must be one-dimensional with " + std::to_string(count) +
                          " entries, got shape " + text(py::cast(a.request().shape)));
  if (count > 1 && a.strides(0) != d.itemsize())
    throw py::value_error(argument +
                          " must be contiguous (the grid's index arrays have no "
                          "stride); pass numpy.ascontiguousarray(" +
                          argument + ")");
  const bool is_signed = d.kind() == 'i';
  const IndexType type = d.itemsize() == 4 ? (is_signed ? IndexType::int32 : IndexType::uint32)
                                           : (is_signed ? IndexType::int64 : IndexType::uint64);
  return {a.data(), type};
}

// The solver's neighbour-search grid (voxspan/grid.h) as Python holds it: the geometry and the
// index arrays it names, kept alive by this object.
struct Grid {
  GridGeometry geometry;
  py::object offsets, begin, end, cell_of, order;
  int index_base = 0;

  // The view for `count` particles; throws ValueError/TypeError naming the array.
  GridView view(std::size_t count) const {
    if (!geometry.valid())
      throw py::value_error("grid: cell_size must be positive and dims at least 1 each");
    const std::size_t cells = geometry.cell_count();
    GridView v = GridView::geometry_only(geometry);
    const int given = !offsets.is_none() + !begin.is_none() + !cell_of.is_none();
    if (given > 1 || begin.is_none() != end.is_none())
      throw py::value_error("grid: give one of offsets, begin and end, or cell_of");
    if (!offsets.is_none())
      v = GridView::offsets(geometry, index_array(offsets, "grid.offsets", cells + 1));
    if (!begin.is_none())
      v = GridView::begin_end(geometry, index_array(begin, "grid.begin", cells),
                              index_array(end, "grid.end", cells));
    if (!cell_of.is_none())
      v = GridView::cell_index(geometry, index_array(cell_of, "grid.cell_of", count));
    if (!order.is_none()) {
      if (offsets.is_none() && begin.is_none())
        throw py::value_error("grid: order needs offsets or begin and end");
      v.with_order(index_array(order, "grid.order", count));
    }
    return v.with_index_base(index_base);
  }
};

// The caller's arrays of one step as a ParticleView. Attribute names live here (the view only
// points at them), so the step must run while this lives.
struct StepArrays {
  std::deque<std::string> names;  // a deque: adding a name never moves the others
  ParticleView view;
  GridView grid;
};

void build_step(StepArrays& s, const py::object& x, const py::object& y, const py::object& z,
                const py::object& radius, const std::optional<std::size_t>& owned,
                const py::dict& scalars, const py::dict& vectors, const std::optional<Grid>& grid) {
  std::array<StridedScalars, 3> axes;
  std::size_t n = 0;
  if (y.is_none() && z.is_none()) {
    axes = columns3(x, "x", std::nullopt);
    n = std::size_t(as_array(x, "x").shape(0));
  } else {
    if (y.is_none() || z.is_none())
      throw py::value_error("give positions as one (n, 3) array x, or as three arrays x, y, z");
    n = std::size_t(as_array(x, "x").size());
    axes = {column(x, "x", std::nullopt), column(y, "y", n), column(z, "z", n)};
    if (axes[1].type != axes[0].type || axes[2].type != axes[0].type)
      throw py::type_error("x, y and z must have the same dtype");
  }
  s.view = ParticleView::from_axes(axes[0], axes[1], axes[2], n);
  if (owned) {
    if (*owned > n)
      throw py::value_error("owned = " + std::to_string(*owned) + " is more than the " +
                            std::to_string(n) + " particles");
    s.view.with_owned(*owned);
  }
  if (!radius.is_none()) {
    if (py::isinstance<py::array>(radius)) {
      s.view.with_radii(column(radius, "radius", n));
    } else {
      const double r = radius.cast<double>();
      if (!(r > 0 && std::isfinite(r)))
        throw py::value_error("radius = " + py::repr(radius).cast<std::string>() +
                              " is not a positive finite number (None: the adapter's)");
      s.view.with_radius(r);
    }
  }
  if (scalars.size() + vectors.size() > std::size_t(ParticleView::kMaxAttributes))
    throw py::value_error("at most " + std::to_string(ParticleView::kMaxAttributes) +
                          " attributes per step");
  // A name given twice (a scalar and a vector) would hide one of them; "" names nothing. The
  // names so far are s.names (at most kMaxAttributes): no set to allocate every step.
  const auto named = [&](const py::handle& key, const char* dict) -> const std::string& {
    if (!py::isinstance<py::str>(key))
      throw py::type_error(std::string(dict) + ": attribute names must be str, got " +
                           py::repr(key).cast<std::string>());
    std::string name = py::str(key);
    if (name.empty()) throw py::value_error(std::string(dict) + ": an attribute name is empty");
    if (std::find(s.names.begin(), s.names.end(), name) != s.names.end())
      throw py::value_error("the attribute '" + name + "' is given twice (in scalars and vectors)");
    return s.names.emplace_back(std::move(name));
  };
  for (auto [key, value] : scalars) {
    const std::string& name = named(key, "scalars");
    s.view.with_attribute({name, 1, {column(value, "scalars['" + name + "']", n), {}, {}}});
  }
  for (auto [key, value] : vectors) {
    const std::string& name = named(key, "vectors");
    const std::string argument = "vectors['" + name + "']";
    std::array<StridedScalars, 3> c;
    if (py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) {
      const py::sequence parts = py::reinterpret_borrow<py::sequence>(value);
      if (parts.size() != 3)
        throw py::value_error(argument + " must be an (n, 3) array or three arrays");
      for (int k = 0; k < 3; ++k)
        c[std::size_t(k)] =
            column(parts[std::size_t(k)], argument + "[" + std::to_string(k) + "]", n);
    } else {
      c = columns3(value, argument, n);
    }
    s.view.with_attribute({name, 3, c});
  }
  if (grid) s.grid = grid->view(n);
}

py::dict counts_dict(const ClassifyCounts& c) {
  py::dict d;
  d["particles"] = c.particles;
  d["owned"] = c.owned;
  d["boundary"] = c.boundary;
  d["dropped_nonfinite"] = c.dropped_nonfinite;
  d["not_in_grid"] = c.not_in_grid;
  d["cells"] = c.cells;
  d["cells_empty"] = c.cells_empty;
  d["cells_partial"] = c.cells_partial;
  d["cells_full"] = c.cells_full;
  d["cells_inner_empty"] = c.cells_inner_empty;
  d["cells_inner_full"] = c.cells_inner_full;
  d["full_count"] = c.full_count;
  d["cell_size"] = c.cell_size;
  d["grid_built"] = c.grid_built;
  return d;
}

py::dict stats_dict(const StepStats& s) {
  py::dict d;
  d["step"] = s.step;
  d["time"] = s.time;
  d["rendered"] = s.rendered;
  d["ok"] = s.status.ok();
  d["message"] = s.status.message;
  d["counts"] = counts_dict(s.counts);
  d["seconds_classify"] = s.seconds_classify;
  d["seconds_compact"] = s.seconds_compact;
  d["seconds_pipeline"] = s.seconds_pipeline;
  d["seconds_total"] = s.seconds_total;
  return d;
}

// A numpy array that owns `values` (moved to the heap, freed with the array): no copy.
template <class T> py::array owning_array(std::vector<T> values, std::vector<py::ssize_t> shape) {
  auto* held = new std::vector<T>(std::move(values));
  py::capsule free_it(held, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, held->data(), free_it);
}

// The adapter with the in-situ runtime behind it, as Python holds it.
class PyAdapter {
 public:
  struct Settings {
    std::optional<double> spacing, radius, cell_size;
    std::optional<int> full_count;
    bool validate = false;
    std::vector<std::string> attributes;
    py::object comm;
    bool offline = false;
    std::string output;
  };

  PyAdapter(const std::function<Config()>& load, const Settings& s) : adapter_(make(load, s)) {}

  Status execute(bool last, std::int64_t step, double time, const py::object& x,
                 const py::object& y, const py::object& z, const py::object& radius,
                 const std::optional<std::size_t>& owned, const py::dict& scalars,
                 const py::dict& vectors, const std::optional<Grid>& grid) {
    StepArrays arrays;
    build_step(arrays, x, y, z, radius, owned, scalars, vectors, grid);
    py::gil_scoped_release unlocked;
    return last ? adapter_.execute_last(step, time, arrays.view, arrays.grid)
                : adapter_.execute(step, time, arrays.view, arrays.grid);
  }

  std::size_t set_scenery(const py::object& x, const py::object& y, const py::object& z,
                          const py::object& radius) {
    StepArrays arrays;
    build_step(arrays, x, y, z, radius, std::nullopt, py::dict(), py::dict(), std::nullopt);
    return adapter_.set_scenery(arrays.view);
  }

  void finish() {
    py::gil_scoped_release unlocked;
    adapter_.finish();
  }

  // The latest render step's pictures by view name: 8-bit sRGB RGBA as the PNG files have
  // them, or the linear float RGBA the shading made; (height, width, 4), row 0 at the top.
  py::dict pictures(bool linear) const {
    py::dict out;
    for (const ViewResult& v : pipeline().latest_views()) {
      if (v.picture == nullptr) continue;
      const FloatImage& p = *v.picture;
      const std::vector<py::ssize_t> shape{p.height, p.width, 4};
      if (linear) out[py::str(std::string(v.name))] = owning_array(p.rgba, shape);
      else
        out[py::str(std::string(v.name))] = owning_array(v.shared_picture->srgb8()->pixels, shape);
    }
    return out;
  }

  void keep_linear_pictures() {
    dynamic_cast<InsituPipeline&>(*adapter_.pipeline()).keep_linear_pictures();
  }

  const Adapter& adapter() const { return adapter_; }
  const InsituPipeline& pipeline() const {
    return dynamic_cast<const InsituPipeline&>(*adapter_.pipeline());
  }

 private:
  // `load` reads the config: with ranks, a rank that cannot is every rank's failure.
  static Adapter make(const std::function<Config()>& load, const Settings& s) {
    AdapterOptions options;
    ClassifyOptions& c = options.classify;
    if (s.spacing) c.particle_spacing = *s.spacing;
    if (s.radius) c.radius = *s.radius;
    if (s.cell_size) c.cell_size = *s.cell_size;
    if (s.full_count) c.full_count = *s.full_count;
    c.validate = s.validate;
    c.attributes = s.attributes;
    if (!s.comm.is_none()) {
      if (!py::hasattr(s.comm, "py2f"))
        throw py::type_error("comm must be an mpi4py communicator, got " + type_name(s.comm));
      options.mpi_comm = s.comm.attr("py2f")().cast<int>();
    }
    return make_insitu_adapter(
        [&] {
          Config config = load();
          if (s.offline) config = offline_config(std::move(config), s.output);
          else if (!s.output.empty()) config.output_folder = s.output;
          return config;
        },
        options);
  }

  Adapter adapter_;
};

// A path argument as text: a str, or anything os.fspath takes (pathlib.Path); None: none.
std::optional<std::string> path_text(const py::object& path) {
  if (path.is_none()) return std::nullopt;
  return py::str(py::module_::import("os").attr("fspath")(path)).cast<std::string>();
}

Config config_of(const std::optional<std::string>& path) {
  return path ? load_config_file(*path) : default_config();
}

py::dict particle_file(const py::object& path_object, const std::vector<std::string>& arrays) {
  const std::string path = path_text(path_object).value_or("");
  ParticleReadOptions options;
  options.arrays = arrays;
  ParticleData d;
  {
    py::gil_scoped_release unlocked;
    d = read_particles(path, options);
  }
  const auto n = py::ssize_t(d.size());
  std::vector<double> xyz(3 * d.size());
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k) xyz[3 * i + k] = d.positions[i][k];
  py::dict out;
  out["positions"] = owning_array(std::move(xyz), {n, 3});
  out["radii"] = d.radii.empty() ? py::object(py::none()) : owning_array(std::move(d.radii), {n});
  py::dict attributes;
  for (Attribute& a : d.attributes) {
    std::vector<py::ssize_t> shape{n};
    if (a.components == 3) shape.push_back(3);
    attributes[py::str(a.name)] = owning_array(std::move(a.values), shape);
  }
  out["attributes"] = attributes;
  out["time"] = d.time;
  out["step"] = d.step;
  out["spacing"] = d.spacing;
  out["chosen"] = d.chosen;
  return out;
}

// The median nearest-neighbour distance (insitu/io/spacing_estimate.h) of an (n, 3) array.
double spacing_estimate(const py::object& positions) {
  const std::array<StridedScalars, 3> axes = columns3(positions, "positions", std::nullopt);
  const auto n = std::size_t(as_array(positions, "positions").shape(0));
  std::vector<std::array<double, 3>> p(n);
  for (std::size_t i = 0; i < n; ++i) p[i] = {axes[0][i], axes[1][i], axes[2][i]};
  py::gil_scoped_release unlocked;
  return estimate_particle_spacing(p);
}

// Where the library will read the particles of these arrays: the address and byte stride of
// each axis as execute() views them (the tests compare them with numpy's own).
py::list viewed_axes(const py::object& x, const py::object& y, const py::object& z) {
  StepArrays arrays;
  build_step(arrays, x, y, z, py::none(), std::nullopt, py::dict(), py::dict(), std::nullopt);
  py::list out;
  for (int a = 0; a < 3; ++a) {
    const StridedScalars& s = arrays.view.axis(a);
    out.append(py::make_tuple(reinterpret_cast<std::uintptr_t>(s.data), s.stride));
  }
  return out;
}

py::array png_file(const py::object& path) {
  ImageRGBA8 image = read_png(path_text(path).value_or(""));
  return owning_array(std::move(image.pixels), {image.height, image.width, 4});
}

}  // namespace
}  // namespace voxspan::python

PYBIND11_MODULE(_voxspan, m) {
  using namespace voxspan;
  using namespace voxspan::python;
  namespace py = pybind11;
  m.doc() = "Voxspan: in-situ rendering of SPH fluids (the compiled part; see voxspan.__doc__)";
  m.attr("__version__") = VOXSPAN_VERSION_STRING;
  py::register_exception<Error>(m, "Error", PyExc_RuntimeError);

  py::enum_<StatusCode>(m, "StatusCode")
      .value("ok", StatusCode::ok)
      .value("invalid_input", StatusCode::invalid_input)
      .value("pipeline_failed", StatusCode::pipeline_failed)
      .value("internal_error", StatusCode::internal_error);

  py::class_<Status>(m, "Status", "What one execute() did: ok, or why the step was skipped.")
      .def_readonly("code", &Status::code)
      .def_readonly("message", &Status::message)
      .def_property_readonly("ok", &Status::ok)
      .def("__bool__", &Status::ok)
      .def("__repr__", [](const Status& s) {
        return s.ok() ? std::string("Status(ok)")
                      : "Status(" + std::string(py::str(py::cast(s.code))) + ": " + s.message + ")";
      });

  py::class_<Grid>(m, "Grid",
                   "The solver's neighbour-search grid (voxspan/grid.h): geometry and one of "
                   "offsets (cells + 1), begin and end (cells each), or cell_of (per particle); "
                   "order (per particle) with cell ranges; index_base 1 for Fortran indices.")
      .def(
          py::init([](std::array<double, 3> origin, double cell_size, std::array<int, 3> dims,
                      py::object offsets, py::object begin, py::object end, py::object cell_of,
                      py::object order, int index_base) {
            return Grid{{origin, cell_size, dims}, offsets, begin, end, cell_of, order, index_base};
          }),
          py::arg("origin"), py::arg("cell_size"), py::arg("dims"), py::kw_only(),
          py::arg("offsets") = py::none(), py::arg("begin") = py::none(),
          py::arg("end") = py::none(), py::arg("cell_of") = py::none(),
          py::arg("order") = py::none(), py::arg("index_base") = 0);

  auto factory = [](bool text) {
    return [text](const py::object& source, std::optional<double> spacing,
                  std::optional<double> radius, std::optional<int> full_count,
                  std::optional<double> cell_size, bool validate,
                  std::vector<std::string> attributes, py::object comm, bool offline,
                  const py::object& output) {
      PyAdapter::Settings s{spacing,         radius,   cell_size,
                            full_count,      validate, std::move(attributes),
                            std::move(comm), offline,  path_text(output).value_or("")};
      const std::optional<std::string> given =
          text ? std::optional(source.is_none() ? std::string() : source.cast<std::string>())
               : path_text(source);
      return std::make_unique<PyAdapter>(
          [&] { return text ? load_config_string(*given, "<config text>") : config_of(given); }, s);
    };
  };
  auto settings_args = [](auto&& def, const char* first) {
    return def(py::arg(first), py::kw_only(), py::arg("spacing") = py::none(),
               py::arg("radius") = py::none(), py::arg("full_count") = py::none(),
               py::arg("cell_size") = py::none(), py::arg("validate") = false,
               py::arg("attributes") = std::vector<std::string>{}, py::arg("comm") = py::none(),
               py::arg("offline") = false, py::arg("output") = "");
  };

  py::class_<PyAdapter> adapter(m, "Adapter", "The adapter with the in-situ runtime behind it.");
  settings_args(
      [&](auto... args) {
        adapter.def_static("from_config_file", factory(false), args...,
                           "An adapter configured by a YAML file (None: every key at its default). "
                           "spacing: the particles' rest spacing; radius: their sphere radius "
                           "(default: the spacing); comm: an mpi4py communicator; offline: every "
                           "call a render step; output: the output folder. Raises voxspan.Error.");
      },
      "path");
  settings_args(
      [&](auto... args) {
        adapter.def_static("from_config_text", factory(true), args...,
                           "from_config_file with the YAML text itself.");
      },
      "yaml");

  auto execute = [](bool last) {
    return [last](PyAdapter& a, std::int64_t step, double time, py::object x, py::object y,
                  py::object z, py::object radius, std::optional<std::size_t> owned,
                  py::dict scalars, py::dict vectors, std::optional<Grid> grid) {
      return a.execute(last, step, time, x, y, z, radius, owned, scalars, vectors, grid);
    };
  };
  auto step_args = [](auto&& def) {
    return def(py::arg("step"), py::arg("time"), py::arg("x"), py::arg("y") = py::none(),
               py::arg("z") = py::none(), py::kw_only(), py::arg("radius") = py::none(),
               py::arg("owned") = py::none(), py::arg("scalars") = py::dict(),
               py::arg("vectors") = py::dict(), py::arg("grid") = py::none());
  };
  step_args([&](auto... args) {
    adapter.def("execute", execute(false), args...,
                "One solver step: positions as an (n, 3) array x or as x, y, z (float32 or "
                "float64, viewed, not copied); radius a number or an array; owned: the count "
                "of owned particles (ghosts after them); scalars / vectors: named attributes; "
                "grid: a voxspan.Grid. Returns a Status; never raises for the step's data "
                "(NaN positions are counted and left out), only for arrays it cannot view.");
  });
  step_args([&](auto... args) {
    adapter.def("execute_last", execute(true), args...,
                "execute() for the solver's last step: triggers with `last` fire on it.");
  });
  adapter.def("set_scenery", &PyAdapter::set_scenery, py::arg("x"), py::arg("y") = py::none(),
              py::arg("z") = py::none(), py::kw_only(), py::arg("radius") = py::none(),
              "The solver's walls and obstacles, drawn by the surface views as opaque solids: "
              "positions as in execute() (copied: give them again only when they move); radius "
              "a number or an array (default: the particles'). Returns the count kept (NaN "
              "positions are left out).");
  adapter.def("finish", &PyAdapter::finish, "Waits for the files still being written.")
      .def("summary", [](const PyAdapter& a) { return a.adapter().summary(); })
      .def("description", [](const PyAdapter& a) { return a.pipeline().description(); })
      .def("pictures", &PyAdapter::pictures, py::arg("linear") = false,
           "The latest render step's pictures: {view name: (height, width, 4) array}, uint8 "
           "sRGB as the PNG files (linear=True: float32 linear RGBA).")
      .def("keep_linear_pictures", &PyAdapter::keep_linear_pictures,
           "From the next render step on, pictures(linear=True) are the shading's floats; "
           "otherwise a step whose pictures only PNG files and the live page take has them made "
           "8-bit sRGB on the GPU, and its floats are those bytes decoded.")
      .def("is_render_step", [](const PyAdapter& a, std::int64_t step,
                                double time) { return a.adapter().is_render_step(step, time); })
      .def_property_readonly(
          "last_stats", [](const PyAdapter& a) { return stats_dict(a.adapter().last_stats()); })
      .def_property_readonly("seconds_in_situ",
                             [](const PyAdapter& a) { return a.adapter().seconds_in_situ(); })
      .def_property_readonly("steps_seen",
                             [](const PyAdapter& a) { return a.adapter().steps_seen(); })
      .def_property_readonly("render_steps",
                             [](const PyAdapter& a) { return a.adapter().render_steps(); })
      .def_property_readonly("failed_steps",
                             [](const PyAdapter& a) { return a.adapter().failed_steps(); })
      .def_property_readonly("output_folder",
                             [](const PyAdapter& a) { return a.pipeline().config().output_folder; })
      .def("__enter__", [](PyAdapter& a) -> PyAdapter& { return a; })
      .def("__exit__", [](PyAdapter& a, py::args) { a.finish(); });

  m.def("read_particles", &particle_file, py::arg("path"),
        py::arg("arrays") = std::vector<std::string>{},
        "Reads a particle file (.vtp .vtu .vtk .csv .xyz, .hdf5/.h5 of PySPH or GADGET/SWIFT): a "
        "dict of positions ((n, 3) float64), radii (or None), attributes ({name: array}), time, "
        "step, spacing (HDF5: from mass and density) and chosen (the arrays read). arrays: PySPH "
        "arrays or GADGET particle types (PartType4) to read, ['all'], or [] for the fluid's "
        "(the gas). Raises voxspan.Error naming the file.");
  m.def("read_png", &png_file, py::arg("path"),
        "A PNG file as a (height, width, 4) uint8 array (sRGB RGBA, row 0 at the top).");
  m.def("_viewed_axes", &viewed_axes, py::arg("x"), py::arg("y") = py::none(),
        py::arg("z") = py::none(),
        "[(address, byte stride)] of the x, y, z the library reads for these positions.");
  m.def("estimate_spacing", &spacing_estimate, py::arg("positions"),
        "The particle spacing of an (n, 3) array: the median nearest-neighbour distance.");
}
