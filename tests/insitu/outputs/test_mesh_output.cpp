// The fluid's surface mesh (outputs.mesh): closed, on the exact union of the particles' spheres
// within the distances docs/benchmarks.md states ("Mesh output"), its PLY and OBJ files read
// back by readers written here from the formats' specifications, its keys, and the output
// through the registry and the background writer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <numeric>
#include <sstream>

#include "insitu/outputs/formats/mesh_files.h"
#include "insitu/outputs/kinds/mesh_output.h"
#include "insitu/runtime/config_file.h"
#include "insitu/runtime/registry.h"
#include "tests/support/error_message.h"
#include "tests/support/lattice_block_test.h"
#include "tests/support/temp_folder.h"
#include "tools/common/dambreak_state.h"
#include "tools/scenes/lattice.h"
#include "voxspan/stopwatch.h"

namespace voxspan {
namespace {

using Vec3 = std::array<float, 3>;

// ---- what the tests measure

// The exact signed distance to the union of the spheres: min over spheres of |p - c| - r.
double union_distance(const Vec3& p, std::span<const ParticleSphere> spheres) {
  double best = std::numeric_limits<double>::max();
  for (const ParticleSphere& s : spheres) {
    const double dx = p[0] - s.x, dy = p[1] - s.y, dz = p[2] - s.z;
    best = std::min(best, std::sqrt(dx * dx + dy * dy + dz * dz) - s.radius);
  }
  return best;
}

struct Distances {
  double max_abs = 0, mean_abs = 0, mean = 0;  // world units
};

// Over every `every`-th point (brute force: points x spheres).
Distances distances_to_union(const FluidMesh& mesh, std::span<const ParticleSphere> spheres,
                             std::size_t every = 1) {
  Distances d;
  std::size_t n = 0;
  for (std::size_t i = 0; i < mesh.points.size(); i += every, ++n) {
    const double s = union_distance(mesh.points[i], spheres);
    d.max_abs = std::max(d.max_abs, std::abs(s));
    d.mean_abs += std::abs(s);
    d.mean += s;
  }
  d.mean_abs /= double(n);
  d.mean /= double(n);
  return d;
}

// The faces' centres as points (the surface between the points).
FluidMesh face_centres(const FluidMesh& mesh);

std::vector<std::vector<std::uint32_t>> faces_of(const FluidMesh& mesh) {
  std::vector<std::vector<std::uint32_t>> faces;
  for (const auto& t : mesh.triangles) faces.push_back({t.begin(), t.end()});
  for (const auto& q : mesh.quads) faces.push_back({q.begin(), q.end()});
  return faces;
}

FluidMesh face_centres(const FluidMesh& mesh) {
  FluidMesh centres;
  for (const auto& f : faces_of(mesh)) {
    Vec3 c{0, 0, 0};
    for (std::uint32_t v : f)
      for (std::size_t k = 0; k < 3; ++k) c[k] += mesh.points[v][k] / float(f.size());
    centres.points.push_back(c);
  }
  return centres;
}

// A closed surface: every edge in exactly two faces, once each way round (consistent winding).
// Returns the Euler characteristic V - E + F (2 per sphere-like piece).
long closed_surface_euler(const FluidMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  const auto faces = faces_of(mesh);
  for (const auto& f : faces)
    for (std::size_t k = 0; k < f.size(); ++k) ++directed[{f[k], f[(k + 1) % f.size()]}];
  std::size_t edges = 0;
  for (const auto& [e, n] : directed) {
    EXPECT_EQ(n, 1) << "edge " << e.first << "-" << e.second << " twice the same way";
    const auto back = directed.find({e.second, e.first});
    EXPECT_TRUE(back != directed.end()) << "edge " << e.first << "-" << e.second << " open";
    edges += e.first < e.second;
  }
  return long(mesh.points.size()) - long(edges) + long(faces.size());
}

// The pieces of the surface (points joined by faces).
std::size_t components(const FluidMesh& mesh) {
  std::vector<std::uint32_t> parent(mesh.points.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto root = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& f : faces_of(mesh))
    for (std::uint32_t v : f) parent[root(v)] = root(f[0]);
  std::size_t n = 0;
  for (std::uint32_t v = 0; v < parent.size(); ++v) n += root(v) == v;
  return n;
}

// Faces whose right-hand normal points against their points' normals.
std::size_t faces_against_normals(const FluidMesh& mesh) {
  std::size_t against = 0;
  for (const auto& f : faces_of(mesh)) {
    const Vec3 &a = mesh.points[f[0]], &b = mesh.points[f[1]], &c = mesh.points[f[2]];
    const float u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const float w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const float n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                        u[0] * w[1] - u[1] * w[0]};
    float dot = 0;
    for (std::uint32_t v : f)
      for (int k = 0; k < 3; ++k) dot += n[k] * mesh.normals[v][std::size_t(k)];
    against += dot < 0;
  }
  return against;
}

// ---- the files read back, from the formats' specifications

struct PlyFile {
  std::string format;
  std::vector<std::string> vertex_properties;
  std::size_t vertices = 0, faces = 0;
  std::vector<float> vertex_data;  // vertices x properties
  std::vector<std::vector<std::int32_t>> face_list;
};

PlyFile read_ply(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  PlyFile ply;
  std::string line, element;
  std::getline(in, line);
  EXPECT_EQ(line, "ply");
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "format") {
      words >> ply.format;
    } else if (word == "element") {
      words >> element;
      (element == "vertex" ? ply.vertices : ply.faces) = [&] {
        std::size_t n = 0;
        words >> n;
        return n;
      }();
    } else if (word == "property" && element == "vertex") {
      std::string type, name;
      words >> type >> name;
      EXPECT_EQ(type, "float") << line;
      ply.vertex_properties.push_back(name);
    } else if (word == "property") {
      EXPECT_EQ(line, "property list uchar int vertex_indices");
    } else {
      EXPECT_EQ(word, "comment") << line;
    }
  }
  ply.vertex_data.resize(ply.vertices * ply.vertex_properties.size());
  in.read(reinterpret_cast<char*>(ply.vertex_data.data()),
          std::streamsize(ply.vertex_data.size() * sizeof(float)));
  for (std::size_t f = 0; f < ply.faces && in; ++f) {
    std::uint8_t count = 0;
    in.read(reinterpret_cast<char*>(&count), 1);
    std::vector<std::int32_t> face(count);
    in.read(reinterpret_cast<char*>(face.data()), std::streamsize(count * sizeof(std::int32_t)));
    ply.face_list.push_back(std::move(face));
  }
  EXPECT_TRUE(in) << "the file ends before its " << ply.faces << " faces";
  EXPECT_EQ(in.peek(), std::char_traits<char>::eof()) << "bytes after the last face";
  return ply;
}

class MeshOutputTest : public test::LatticeBlockTest {};

TEST_F(MeshOutputTest, BlockMeshesToOneClosedSurfaceOnTheSphereUnion) {
  FluidMeshReport report;
  const FluidMesh mesh = mesh_fluid({scene.boundary, scene.cells(), {}, 0, 0}, {}, &report);
  ASSERT_GT(mesh.points.size(), 1000u);
  EXPECT_EQ(report.particles, scene.boundary.size());
  EXPECT_EQ(report.normals_from_faces, 0u);
  EXPECT_EQ(closed_surface_euler(mesh), 2) << "a block: one piece, no handle";
  EXPECT_EQ(components(mesh), 1u) << "no inner shell between the spheres and the filled cells";
  EXPECT_EQ(faces_against_normals(mesh), 0u);
  for (const Vec3& n : mesh.normals)
    ASSERT_NEAR(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-5);

  // Against every particle's sphere (the interior ones too): the closing fills the dimples
  // between touching spheres (their union is porous at radius dx/2: a channel runs between
  // every four neighbours), so the surface lies up to their depth outside the union.
  // The points lie on the union's bumps but the block's corners and edges are cut; the faces
  // span the dimples between the bumps (0.37 dx deep at the middle of four spheres).
  const Distances d = distances_to_union(mesh, scene.all);
  const Distances c = distances_to_union(face_centres(mesh), scene.all);
  std::cout << "radius dx/2, closing and voxel dx/2: " << mesh.points.size() << " points, "
            << mesh.quads.size() << " quads, " << mesh.triangles.size()
            << " triangles; distance to the sphere union: points max " << d.max_abs / kDx
            << " dx, mean |d| " << d.mean_abs / kDx << " dx, mean " << d.mean / kDx
            << " dx; face centres max " << c.max_abs / kDx << " dx, mean |d| " << c.mean_abs / kDx
            << " dx, mean " << c.mean / kDx << " dx\n";
  EXPECT_LT(d.max_abs, 0.30 * kDx);
  EXPECT_LT(d.mean_abs, 0.03 * kDx);
  EXPECT_LT(c.max_abs, 0.40 * kDx);
}

TEST_F(MeshOutputTest, OverlappingSpheresWithoutClosingMeshToTheirUnion) {
  // Spheres of 0.9 dx overlap past the lattice's channels (0.71 dx) and voids (0.87 dx): their
  // union is closed by itself, so without closing the surface is the union's up to the voxels
  // (dx/4), which cut its creases where neighbours meet.
  const test::LatticeScene big = test::make_lattice_block(kSide, kDx, float(0.9 * kDx));
  FluidMeshSettings settings;
  settings.closing = 0.0;
  settings.voxel_size = kDx / 4;
  const FluidMesh mesh = mesh_fluid({big.boundary, big.cells(), {}, 0, 0}, settings);
  EXPECT_EQ(closed_surface_euler(mesh), 2);
  EXPECT_EQ(components(mesh), 1u);
  EXPECT_EQ(faces_against_normals(mesh), 0u);
  const Distances d = distances_to_union(mesh, big.all);
  std::cout << "radius 0.9 dx, no closing, voxel dx/4: " << mesh.points.size()
            << " points; distance to the sphere union: max " << d.max_abs / kDx << " dx, mean |d| "
            << d.mean_abs / kDx << " dx, mean " << d.mean / kDx << " dx\n";
  EXPECT_LT(d.max_abs, 0.05 * kDx);
  EXPECT_LT(d.mean_abs, 0.02 * kDx);
}

TEST_F(MeshOutputTest, AdaptivityMergesFlatFacesAndKeepsTheSurfaceClosed) {
  const FluidMeshInput input{scene.boundary, scene.cells(), {}, 0, 0};
  FluidMeshSettings settings;
  settings.adaptivity = 0.5;
  const FluidMesh fine = mesh_fluid(input, {});
  const FluidMesh merged = mesh_fluid(input, settings);
  EXPECT_LT(merged.points.size(), fine.points.size() / 4);
  EXPECT_GT(merged.triangles.size(), 0u);
  EXPECT_EQ(closed_surface_euler(merged), 2);
  EXPECT_EQ(faces_against_normals(merged), 0u);
  const Distances d = distances_to_union(merged, scene.all);
  std::cout << "adaptivity 0.5: " << merged.points.size() << " points (" << fine.points.size()
            << " at 0), " << merged.quads.size() << " quads, " << merged.triangles.size()
            << " triangles; distance to the sphere union: points max " << d.max_abs / kDx
            << " dx, mean |d| " << d.mean_abs / kDx << " dx\n";
  EXPECT_LT(d.max_abs, 0.40 * kDx);
}

TEST_F(MeshOutputTest, PlyReadsBackWithNormalsAndTheNearestParticlesAttributes) {
  // Attributes that name their particle: its index (exact in a float below 2^24).
  std::vector<float> index(scene.boundary.size()), velocity(3 * scene.boundary.size());
  for (std::size_t i = 0; i < index.size(); ++i) {
    index[i] = float(i);
    velocity[3 * i] = float(i), velocity[3 * i + 1] = 1, velocity[3 * i + 2] = -float(i);
  }
  const std::vector<AttributeSpan> attributes = {{"id", 1, index}, {"velocity", 3, velocity}};
  const FluidMeshInput input{scene.boundary, scene.cells(), attributes, 40, 0.125};
  const FluidMeshReport report =
      write_fluid_mesh(dir / "m.ply", input, {}, MeshFormat::ply, /*sync=*/false);
  const FluidMesh mesh = mesh_fluid(input, {});
  EXPECT_EQ(test::count_temp_files(dir.path()), 0u);
  EXPECT_EQ(report.points_without_particle, 0u);
  EXPECT_EQ(report.bytes, std::filesystem::file_size(dir / "m.ply"));

  const PlyFile ply = read_ply(dir / "m.ply");
  EXPECT_EQ(ply.format, "binary_little_endian");
  EXPECT_EQ(ply.vertex_properties,
            (std::vector<std::string>{"x", "y", "z", "nx", "ny", "nz", "id", "velocity_x",
                                      "velocity_y", "velocity_z"}));
  ASSERT_EQ(ply.vertices, mesh.points.size());
  ASSERT_EQ(ply.faces, mesh.quads.size() + mesh.triangles.size());
  const std::size_t stride = ply.vertex_properties.size();
  for (std::size_t v = 0; v < ply.vertices; ++v) {
    const float* p = &ply.vertex_data[v * stride];
    ASSERT_EQ(Vec3({p[0], p[1], p[2]}), mesh.points[v]);
    ASSERT_NEAR(std::sqrt(p[3] * p[3] + p[4] * p[4] + p[5] * p[5]), 1.0, 1e-5);
    // The particle it names is a nearest one (ties: the lattice has many).
    const auto id = std::size_t(p[6]);
    ASSERT_LT(id, scene.boundary.size());
    const ParticleSphere& s = scene.boundary[id];
    auto distance = [&](const ParticleSphere& o) {
      return std::hypot(double(p[0]) - o.x, double(p[1]) - o.y, double(p[2]) - o.z);
    };
    const double to_it = distance(s);
    double nearest = std::numeric_limits<double>::max();
    for (const ParticleSphere& o : scene.boundary) nearest = std::min(nearest, distance(o));
    ASSERT_LE(to_it, nearest + 1e-6) << "vertex " << v;
    ASSERT_EQ(p[7], float(id));
    ASSERT_EQ(p[8], 1.f);
    ASSERT_EQ(p[9], -float(id));
  }
  std::size_t quads = 0;
  for (const auto& f : ply.face_list) {
    ASSERT_TRUE(f.size() == 3 || f.size() == 4);
    quads += f.size() == 4;
    for (std::int32_t v : f) ASSERT_TRUE(v >= 0 && std::size_t(v) < ply.vertices);
  }
  EXPECT_EQ(quads, mesh.quads.size());
}

TEST_F(MeshOutputTest, ObjHasAPointANormalAndFacesThatNameBoth) {
  const FluidMeshInput input{scene.boundary, scene.cells(), {}, 3, 0};
  write_fluid_mesh(dir / "m.obj", input, {}, MeshFormat::obj, false);
  const FluidMesh mesh = mesh_fluid(input, {});
  std::ifstream in(dir / "m.obj");
  std::string line;
  std::size_t v = 0, vn = 0, f = 0;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "v" || tag == "vn") {
      float x, y, z;
      ASSERT_TRUE(words >> x >> y >> z) << line;
      if (tag == "vn") {
        ASSERT_NEAR(std::sqrt(x * x + y * y + z * z), 1.0, 1e-5);
      }
      ++(tag == "v" ? v : vn);
    } else if (tag == "f") {
      std::string corner;
      int corners = 0;
      while (words >> corner) {
        const std::size_t slashes = corner.find("//");
        ASSERT_NE(slashes, std::string::npos) << line;
        const long a = std::stol(corner.substr(0, slashes)),
                   b = std::stol(corner.substr(slashes + 2));
        ASSERT_EQ(a, b);
        ASSERT_TRUE(a >= 1 && std::size_t(a) <= mesh.points.size()) << line;
        ++corners;
      }
      ASSERT_TRUE(corners == 3 || corners == 4) << line;
      ++f;
    } else {
      ASSERT_EQ(tag, "#") << line;
    }
  }
  EXPECT_EQ(v, mesh.points.size());
  EXPECT_EQ(vn, mesh.points.size());
  EXPECT_EQ(f, mesh.quads.size() + mesh.triangles.size());
}

TEST_F(MeshOutputTest, EmptyInputWritesAnEmptyMesh) {
  write_fluid_mesh(dir / "e.ply", {}, {}, MeshFormat::ply, false);
  const PlyFile ply = read_ply(dir / "e.ply");
  EXPECT_EQ(ply.vertices, 0u);
  EXPECT_EQ(ply.faces, 0u);
  FluidMeshSettings bad;
  bad.adaptivity = 2;
  EXPECT_NE(test::error_message([&] { mesh_fluid({}, bad); }).find("adaptivity 2"),
            std::string::npos);
}

TEST(MeshOutputConfig, KeysAreReadAndABadFormatNamesTheKey) {
  const Config defaults = default_config();
  const MeshSettings& d = defaults.output<MeshSettings>();
  EXPECT_FALSE(d.enabled);
  EXPECT_EQ(d.folder, "mesh");
  EXPECT_EQ(d.format, MeshFormat::ply);
  EXPECT_EQ(d.surface.adaptivity, 0);

  const Config c = load_config_string(R"(
outputs:
  mesh: {enabled: true, folder: surface, format: obj, trigger: {every_steps: 50},
         adaptivity: 0.25, closing: 0, voxel_size: 0.002}
)");
  const MeshSettings& m = c.output<MeshSettings>();
  EXPECT_TRUE(m.enabled);
  EXPECT_EQ(m.folder, "surface");
  EXPECT_EQ(m.format, MeshFormat::obj);
  EXPECT_EQ(m.trigger, (TriggerSpec{50, 0, false, false}));
  EXPECT_EQ(m.surface.adaptivity, 0.25);
  EXPECT_EQ(m.surface.closing, 0.0);
  EXPECT_EQ(m.surface.voxel_size, 0.002);
  EXPECT_EQ(load_config_string(to_yaml(c)), c);

  auto error_of = [](const std::string& yaml) {
    return test::error_message([&] { load_config_string(yaml, "test.yaml"); });
  };
  EXPECT_NE(error_of("outputs:\n  mesh: {format: stl}\n")
                .find("test.yaml:2:18: outputs.mesh.format: expected one of ply, obj; got \"stl\""),
            std::string::npos)
      << error_of("outputs:\n  mesh: {format: stl}\n");
  EXPECT_NE(error_of("outputs:\n  mesh: {adaptivity: 1.5}\n").find("outputs.mesh.adaptivity"),
            std::string::npos);
  EXPECT_NE(error_of("outputs:\n  mesh: {format: obj, attributes: [density]}\n")
                .find("outputs.mesh.attributes: OBJ files hold no per-vertex attributes"),
            std::string::npos);
  EXPECT_NE(error_of("outputs:\n  mesh: {attributes: [nx, \"wave height\"]}\n")
                .find("\"nx\" cannot name a PLY vertex property (the vertex's own)"),
            std::string::npos);
  EXPECT_NE(error_of("outputs:\n  mesh: {attributes: [\"wave height\"]}\n")
                .find("\"wave height\" cannot name a PLY vertex property (not one word)"),
            std::string::npos);
}

TEST_F(MeshOutputTest, OutputWritesTheStepsMeshOnTheWriterThread) {
  const Config config = load_config_string(
      "outputs:\n  mesh: {enabled: true, attributes: [density]}\nwriter: {fsync: false}\n");
  BackgroundWriter writer(config.writer);
  const OutputContext context{config, dir.path(), {}, kDx, writer, 3, false, nullptr};
  std::unique_ptr<Output> output =
      registered_output_kind("mesh").make(config.output<MeshSettings>(), context);
  const std::vector<float> density(scene.boundary.size(), 1000.f);
  const std::vector<Attribute> attributes = {{"density", 1, density}};
  StepData data;
  data.step = 40;
  data.time = 0.5;
  data.boundary = scene.boundary;
  data.cells = scene.cells();
  data.attributes = attributes;
  output->write({data, {}, nullptr});
  writer.drain();
  EXPECT_EQ(output->tally().written, 1);
  const PlyFile ply = read_ply(dir / "fluid_00000040.ply");
  EXPECT_GT(ply.vertices, 1000u);
  EXPECT_EQ(ply.vertex_properties.back(), "density");
}

// The dam break at 10^5 particles (docs/benchmarks.md, "Mesh output"): run only when
// VOXSPAN_MESH_BENCH names the solver's state at T = 2 (build/dambreak_state_T2.bin, which
// bench_renderers --particles 1e5 --time 2 --state ... writes).
TEST(MeshOutputBench, DamBreakAt1e5Particles) {
  const char* state = std::getenv("VOXSPAN_MESH_BENCH");
  if (state == nullptr) GTEST_SKIP() << "set VOXSPAN_MESH_BENCH=build/dambreak_state_T2.bin";
  const tools::DamBreakState s = tools::solver_dam_break(1e5, 2, state);
  const Classification& c = s.classification;
  test::TempFolder dir;
  std::vector<ParticleSphere> spheres = c.boundary;
  for (ParticleSphere& p : spheres) p.radius = float(0.5 * s.spacing);  // outputs' `auto`
  std::vector<ParticleSphere> all;
  for (std::size_t i = 0; i < s.x.size(); ++i)
    all.push_back({s.x[i], s.y[i], s.z[i], float(0.5 * s.spacing)});
  // A velocity to sample (the state holds positions only): the particle's position.
  std::vector<float> velocity;
  for (const ParticleSphere& p : spheres) velocity.insert(velocity.end(), {p.x, p.y, p.z});
  const std::vector<AttributeSpan> attributes = {{"velocity", 3, velocity}};
  const FluidMeshInput input{spheres, c.cell_states(), attributes, 0, 2.0};
  for (MeshFormat format : {MeshFormat::ply, MeshFormat::obj}) {
    const Stopwatch watch;
    const FluidMeshReport r = write_fluid_mesh(
        dir / (format == MeshFormat::ply ? "d.ply" : "d.obj"),
        format == MeshFormat::ply ? input : FluidMeshInput{spheres, c.cell_states(), {}, 0, 2.0},
        {}, format, false);
    std::cout << s.description << ", " << spheres.size()
              << " boundary: " << (format == MeshFormat::ply ? "PLY " : "OBJ ") << watch.seconds()
              << " s, " << r.bytes / 1048576.0 << " MiB; " << r.timings.json() << "\n";
  }
  const FluidMesh mesh = mesh_fluid(input, {});
  const std::size_t every = std::max<std::size_t>(1, mesh.points.size() / 20000);
  const Distances d = distances_to_union(mesh, all, every);
  std::cout << mesh.points.size() << " points, " << mesh.quads.size() << " quads, "
            << mesh.triangles.size() << " triangles, " << components(mesh)
            << " pieces; distance to the union of all particles' spheres (every " << every
            << "th point): max " << d.max_abs / s.spacing << " dx, mean |d| "
            << d.mean_abs / s.spacing << " dx, mean " << d.mean / s.spacing << " dx\n";
}

}  // namespace
}  // namespace voxspan
