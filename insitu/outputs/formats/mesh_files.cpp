// The fluid's surface mesh (see mesh_files.h): the snapshot's level set (fluid_level_set.h),
// volumeToMesh, normals from the gradient, attributes from the nearest particle, PLY or OBJ. Like
// vdb_snapshot.cpp, one translation unit holds the mesher's OpenVDB templates (they compile
// slowly).
#include "insitu/outputs/formats/mesh_files.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "insitu/outputs/formats/fluid_level_set.h"
#include "insitu/outputs/writer/atomic_file.h"
#include "voxspan/error.h"
#include "voxspan/stopwatch.h"
#include "voxspan/version.h"

namespace voxspan {

namespace {

namespace vdb = openvdb;

// ---- the mesh

using Vec3 = std::array<float, 3>;

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
bool normalize(Vec3& v) {
  const float length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(length > 1e-20f) || !std::isfinite(length)) return false;
  for (float& c : v) c /= length;
  return true;
}

// Each point's normal: the gradient of the trilinear level set, central differences one voxel
// apart (index space; the voxels are cubes). Points where it vanishes (or falls outside the
// band) take the area-weighted normal of their faces.
void compute_normals(const vdb::FloatGrid& sdf, FluidMesh& mesh, FluidMeshReport& report) {
  mesh.normals.assign(mesh.points.size(), Vec3{0, 0, 0});
  std::vector<std::uint8_t> from_gradient(mesh.points.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.points.size(), 4096), [&](auto r) {
    auto acc = sdf.getConstAccessor();
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const vdb::Vec3d p = sdf.transform().worldToIndex(
          vdb::Vec3d(mesh.points[i][0], mesh.points[i][1], mesh.points[i][2]));
      auto at = [&](double dx, double dy, double dz) {
        return vdb::tools::BoxSampler::sample(acc, p + vdb::Vec3d(dx, dy, dz));
      };
      Vec3 g{at(1, 0, 0) - at(-1, 0, 0), at(0, 1, 0) - at(0, -1, 0), at(0, 0, 1) - at(0, 0, -1)};
      if (normalize(g)) mesh.normals[i] = g, from_gradient[i] = 1;
    }
  });
  report.normals_from_faces =
      mesh.points.size() - std::size_t(std::count(from_gradient.begin(), from_gradient.end(), 1));
  if (report.normals_from_faces == 0) return;
  // Twice the area times the unit normal of each triangle (a quad as two), summed per point.
  std::vector<Vec3> sum(mesh.points.size(), Vec3{0, 0, 0});
  auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const Vec3 n = cross(sub(mesh.points[b], mesh.points[a]), sub(mesh.points[c], mesh.points[a]));
    for (std::uint32_t v : {a, b, c})
      for (int k = 0; k < 3; ++k) sum[v][std::size_t(k)] += n[std::size_t(k)];
  };
  for (const auto& t : mesh.triangles) add(t[0], t[1], t[2]);
  for (const auto& q : mesh.quads) add(q[0], q[1], q[2]), add(q[0], q[2], q[3]);
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    if (!from_gradient[i] && normalize(sum[i])) mesh.normals[i] = sum[i];
}

// Each point's attributes from its nearest particle among the closest particles of the eight
// voxels around it (the voxels the snapshot's attribute grids would interpolate between).
void sample_attributes(const ClosestParticleGrid* closest,
                       std::span<const ParticleSphere> particles,
                       std::span<const AttributeSpan> attributes, FluidMesh& mesh,
                       FluidMeshReport& report) {
  mesh.attributes.resize(attributes.size());
  for (std::size_t a = 0; a < attributes.size(); ++a) {
    mesh.attributes[a].name = std::string(attributes[a].name);
    mesh.attributes[a].components = attributes[a].components;
    mesh.attributes[a].values.assign(mesh.points.size() * std::size_t(attributes[a].components),
                                     0.f);
  }
  if (attributes.empty()) return;
  constexpr vdb::Index32 kNone = std::numeric_limits<vdb::Index32>::max();
  std::vector<vdb::Index32> nearest(mesh.points.size(), kNone);
  if (closest != nullptr)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.points.size(), 4096), [&](auto r) {
      auto acc = closest->getConstAccessor();
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        const Vec3& p = mesh.points[i];
        const vdb::Vec3d x = closest->transform().worldToIndex(vdb::Vec3d(p[0], p[1], p[2]));
        const vdb::Coord base = vdb::Coord::floor(x);
        float best = std::numeric_limits<float>::max();
        for (int c = 0; c < 8; ++c) {
          vdb::Index32 index;
          if (!acc.probeValue(base.offsetBy(c & 1, (c >> 1) & 1, c >> 2), index)) continue;
          const ParticleSphere& s = particles[index];
          const float d2 = (s.x - p[0]) * (s.x - p[0]) + (s.y - p[1]) * (s.y - p[1]) +
                           (s.z - p[2]) * (s.z - p[2]);
          if (d2 < best) best = d2, nearest[i] = index;
        }
      }
    });
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    if (nearest[i] == kNone) {
      ++report.points_without_particle;
      continue;
    }
    for (std::size_t a = 0; a < attributes.size(); ++a) {
      const std::size_t n = std::size_t(attributes[a].components);
      std::copy_n(attributes[a].values.begin() + std::ptrdiff_t(n * nearest[i]), n,
                  mesh.attributes[a].values.begin() + std::ptrdiff_t(n * i));
    }
  }
}

// ---- the files

// Bytes gathered in memory and handed to the file a megabyte at a time.
class Buffered {
 public:
  explicit Buffered(AtomicFile& file) : file_(file) { bytes_.reserve(kChunk + 256); }
  void put(const void* data, std::size_t n) {
    const char* c = static_cast<const char*>(data);
    bytes_.insert(bytes_.end(), c, c + n);
    if (bytes_.size() >= kChunk) flush();
  }
  void put(std::string_view text) { put(text.data(), text.size()); }
  template <class T> void put_value(T v) { put(&v, sizeof v); }
  void put_number(float v) {
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, v).ptr;
    put(text, std::size_t(end - text));
  }
  void put_number(double v) {
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, v).ptr;
    put(text, std::size_t(end - text));
  }
  void put_number(std::uint64_t v) {
    char text[24];
    const auto end = std::to_chars(text, text + sizeof text, v).ptr;
    put(text, std::size_t(end - text));
  }
  void flush() {
    file_.write(bytes_.data(), bytes_.size());
    bytes_.clear();
  }

 private:
  static constexpr std::size_t kChunk = 1 << 20;
  AtomicFile& file_;
  std::vector<char> bytes_;
};

// A comment on one line: a line break would end it and break the header.
std::string one_line(std::string_view text) {
  std::string s(text);
  std::replace(s.begin(), s.end(), '\n', ' ');
  std::replace(s.begin(), s.end(), '\r', ' ');
  return s;
}

// A property name is one word of the header (the config refuses other names; a caller of
// write_mesh_file may not have checked).
std::string one_word(std::string_view name) {
  std::string s(name);
  for (char& c : s)
    if (std::isspace(static_cast<unsigned char>(c))) c = '_';
  return s;
}

void write_ply(Buffered& out, const FluidMesh& mesh, std::string_view comment) {
  // The machine's own byte order, said in the header: every reader swaps when it must.
  const char* format =
      std::endian::native == std::endian::little ? "binary_little_endian" : "binary_big_endian";
  std::string header = "ply\nformat " + std::string(format) + " 1.0\ncomment " + one_line(comment) +
                       "\nelement vertex " + std::to_string(mesh.points.size()) + "\n";
  const bool shifted = mesh.shifted();
  for (const char* axis : {"x", "y", "z"})
    header += std::string(shifted ? "property double " : "property float ") + axis + "\n";
  header += "property float nx\nproperty float ny\nproperty float nz\n";
  for (const Attribute& a : mesh.attributes) {
    if (a.components == 1) {
      header += "property float " + one_word(a.name) + "\n";
      continue;
    }
    for (const char* axis : {"_x", "_y", "_z"})
      header += "property float " + one_word(a.name) + axis + "\n";
  }
  header += "element face " + std::to_string(mesh.triangles.size() + mesh.quads.size()) +
            "\nproperty list uchar int vertex_indices\nend_header\n";
  out.put(header);
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    if (shifted) {
      const std::array<double, 3> p = mesh.world_point(i);
      out.put(p.data(), sizeof p);
    } else {
      out.put(mesh.points[i].data(), sizeof(Vec3));
    }
    out.put(mesh.normals[i].data(), sizeof(Vec3));
    for (const Attribute& a : mesh.attributes)
      out.put(a.values.data() + std::size_t(a.components) * i,
              std::size_t(a.components) * sizeof(float));
  }
  for (const auto& t : mesh.triangles) {
    out.put_value(std::uint8_t(3));
    for (std::uint32_t v : t) out.put_value(std::int32_t(v));
  }
  for (const auto& q : mesh.quads) {
    out.put_value(std::uint8_t(4));
    for (std::uint32_t v : q) out.put_value(std::int32_t(v));
  }
}

void write_obj(Buffered& out, const FluidMesh& mesh, std::string_view comment) {
  out.put("# ");
  out.put(one_line(comment));
  out.put("\n");
  auto put_vector = [&](const char* tag, const Vec3& v) {
    out.put(tag);
    for (float c : v) {
      out.put(" ");
      out.put_number(c);
    }
    out.put("\n");
  };
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    if (!mesh.shifted()) {
      put_vector("v", mesh.points[i]);
      continue;
    }
    out.put("v");
    for (const double c : mesh.world_point(i)) {
      out.put(" ");
      out.put_number(c);
    }
    out.put("\n");
  }
  for (const Vec3& n : mesh.normals) put_vector("vn", n);
  auto put_face = [&](std::span<const std::uint32_t> face) {
    out.put("f");
    for (std::uint32_t v : face) {
      const std::uint64_t one_based = std::uint64_t(v) + 1;
      out.put(" ");
      out.put_number(one_based);
      out.put("//");
      out.put_number(one_based);
    }
    out.put("\n");
  };
  for (const auto& t : mesh.triangles) put_face(t);
  for (const auto& q : mesh.quads) put_face(q);
}

}  // namespace

FluidMesh mesh_fluid(const FluidMeshInput& input, const FluidMeshSettings& settings,
                     FluidMeshReport* report_out) {
  ensure_openvdb_initialized();
  check_attributes(input.attributes, input.particles.size());
  if (!(settings.adaptivity >= 0 && settings.adaptivity <= 1))
    throw make_error("fluid mesh: adaptivity ", settings.adaptivity, " is not in [0, 1]");
  FluidMeshReport local;
  FluidMeshReport& report = report_out != nullptr ? *report_out : local;
  Stages stage(report.timings, "mesh_");
  const FluidLevelSet ls = build_fluid_level_set(input.particles, input.origin, input.cells,
                                                 settings, "fluid mesh", report, stage);

  stage.next("extract");
  FluidMesh mesh;
  mesh.origin = input.origin;
  std::vector<vdb::Vec3s> points;
  std::vector<vdb::Vec3I> triangles;
  std::vector<vdb::Vec4I> quads;
  vdb::tools::volumeToMesh(*ls.sdf, points, triangles, quads, /*isovalue=*/0.0,
                           settings.adaptivity);
  if (points.size() > std::size_t(std::numeric_limits<std::int32_t>::max()))
    throw make_error("fluid mesh: ", points.size(), " points exceed the PLY's int indices");
  mesh.points.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    mesh.points[i] = {points[i].x(), points[i].y(), points[i].z()};
  // volumeToMesh winds its faces clockwise seen from outside a level set (negative inside);
  // reversed here, so that right-hand face normals point out of the fluid.
  mesh.triangles.resize(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i)
    mesh.triangles[i] = {triangles[i][2], triangles[i][1], triangles[i][0]};
  mesh.quads.resize(quads.size());
  for (std::size_t i = 0; i < quads.size(); ++i)
    mesh.quads[i] = {quads[i][3], quads[i][2], quads[i][1], quads[i][0]};

  stage.next("normals");
  compute_normals(*ls.sdf, mesh, report);
  stage.next("attributes");
  sample_attributes(ls.closest.get(), input.particles, input.attributes, mesh, report);
  return mesh;
}

std::uint64_t write_mesh_file(const std::filesystem::path& path, const FluidMesh& mesh,
                              MeshFormat format, std::string_view comment, bool sync) {
  AtomicFile file(path);
  Buffered out(file);
  if (format == MeshFormat::ply) write_ply(out, mesh, comment);
  else write_obj(out, mesh, comment);
  out.flush();
  file.commit(sync);
  return file.bytes_written();
}

FluidMeshReport write_fluid_mesh(const std::filesystem::path& path, const FluidMeshInput& input,
                                 const FluidMeshSettings& settings, MeshFormat format, bool sync) {
  FluidMeshReport report;
  const FluidMesh mesh = mesh_fluid(input, settings, &report);
  const Stopwatch watch;
  char time[32];
  *std::to_chars(time, time + sizeof time - 1, input.time).ptr = '\0';
  const std::string comment = std::string("voxspan ") + version() + ", step " +
                              std::to_string(input.step) + ", time " + time;
  report.bytes = write_mesh_file(path, mesh, format, comment, sync);
  report.timings.add_time("mesh_write", watch.ms());
  return report;
}

}  // namespace voxspan
