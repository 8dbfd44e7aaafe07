// The VTK peer (tools/peers/vtk_sph_surface.h): the pipeline a ParaView/VTK user builds from SPH
// particles to a surface, then the mesh ray cast to our camera so that the pictures compare
// pixel for pixel. Every object is made afresh per call: a frame of a moving fluid shares nothing
// with the last, and the benchmark times whole frames.
#include "tools/peers/vtk_sph_surface.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <mutex>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <vtkCellArray.h>
#include <vtkDataObject.h>
#include <vtkFlyingEdges3D.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSPHCubicKernel.h>
#include <vtkSPHInterpolator.h>
#include <vtkSPHQuinticKernel.h>
#include <vtkStaticPointLocator.h>
#include <vtkTypeInt32Array.h>
#include <vtkTypeInt64Array.h>
#include <vtkVersionMacros.h>

#include "tools/peers/vtk_smp_backend.h"
#include "voxspan/error.h"
#include "voxspan/stopwatch.h"

namespace voxspan::tools {
namespace {

// The cutoff of VTK's kernels in units of h (vtkSPHKernel::CutoffFactor, hard wired there).
constexpr double kCubicSupport = 2, kQuinticSupport = 3;
// Far beyond any frame the benchmark renders; it only keeps a typo from allocating the machine.
constexpr double kMaxSamples = 1 << 30;
// A ray meets a closed surface an even, small number of times; the cap only bounds degenerate
// meshes (a ray along a sheet of coplanar triangles).
constexpr int kMaxHitsPerRay = 256;
// A mesh of one frame is traced once. On the check's ball (60 k triangles, 800x600) LOW, MEDIUM
// and HIGH differed by less than the timing noise in build and in cast; MEDIUM is Embree's
// default for a static scene.
constexpr RTCBuildQuality kBuildQuality = RTC_BUILD_QUALITY_MEDIUM;
constexpr const char* kBuildQualityName = "medium";

// One Embree device for the process, as an application would hold it: its thread pool starts
// once, not per frame.
RTCDevice embree_device() {
  static std::once_flag once;
  static RTCDevice device = nullptr;
  std::call_once(once, [] { device = rtcNewDevice(nullptr); });
  if (device == nullptr)
    throw make_error("vtk_sph_surface: no Embree device (", rtcGetDeviceError(nullptr), ")");
  return device;
}

class EmbreeScene {
 public:
  explicit EmbreeScene(RTCDevice device) : device_(device), scene_(rtcNewScene(device)) {}
  ~EmbreeScene() { rtcReleaseScene(scene_); }
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;
  RTCScene get() const { return scene_; }
  RTCDevice device() const { return device_; }

 private:
  RTCDevice device_;
  RTCScene scene_;
};

void check_input(const std::vector<float>& x, const std::vector<float>& y,
                 const std::vector<float>& z, double spacing, const Camera& camera,
                 const VtkSphOptions& o) {
  if (x.size() != y.size() || x.size() != z.size())
    throw make_error("vtk_sph_surface: x, y, z hold ", x.size(), ", ", y.size(), ", ", z.size(),
                     " values; they must be as many");
  if (x.empty()) throw make_error("vtk_sph_surface: no particles");
  if (!(std::isfinite(spacing) && spacing > 0))
    throw make_error("vtk_sph_surface: spacing ", spacing, " must be finite and > 0");
  if (!(std::isfinite(o.voxel) && o.voxel > 0))
    throw make_error("vtk_sph_surface: voxel ", o.voxel, " must be finite and > 0");
  if (!(std::isfinite(o.smoothing_length) && o.smoothing_length > 0))
    throw make_error("vtk_sph_surface: smoothing_length ", o.smoothing_length,
                     " must be finite and > 0");
  // At or below 0 the whole padded box would be inside: no surface to speak of.
  if (!(std::isfinite(o.iso) && o.iso > 0))
    throw make_error("vtk_sph_surface: iso ", o.iso, " must be finite and > 0");
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!(std::isfinite(x[i]) && std::isfinite(y[i]) && std::isfinite(z[i])))
      throw make_error("vtk_sph_surface: particle ", i, " has a non-finite coordinate");
  validate(camera);
}

// The particles as VTK's SPH filters expect them: mass and density arrays give each particle
// the volume m / rho = spacing^3 (without them VTK takes h^3, the wrong volume whenever
// h != spacing), and a constant 1 to interpolate, whose SPH sum is then the volume fraction.
vtkNew<vtkPolyData> particle_cloud(const std::vector<float>& x, const std::vector<float>& y,
                                   const std::vector<float>& z, double spacing) {
  const auto n = static_cast<vtkIdType>(x.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(n);
  float* p = vtkFloatArray::SafeDownCast(points->GetData())->GetPointer(0);
  for (vtkIdType i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    p[3 * i] = x[k], p[3 * i + 1] = y[k], p[3 * i + 2] = z[k];
  }
  auto constant = [n](const char* name, double value) {
    vtkNew<vtkFloatArray> a;
    a->SetName(name);
    a->SetNumberOfTuples(n);
    a->FillValue(static_cast<float>(value));
    return a;
  };
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  // rho0 = 1: only the ratio m / rho enters the fraction.
  auto mass = constant("mass", spacing * spacing * spacing);
  auto density = constant("density", 1);
  auto fraction = constant("fraction", 1);
  cloud->GetPointData()->AddArray(mass);
  cloud->GetPointData()->AddArray(density);
  cloud->GetPointData()->AddArray(fraction);
  return cloud;
}

struct Grid {
  double origin[3];
  int dims[3];
};

// The particles' bounds padded by the kernel's support, so that the field is exactly 0 on the
// box's faces and every contour closes inside it.
Grid probe_grid(const std::vector<float>& x, const std::vector<float>& y,
                const std::vector<float>& z, double voxel, double support) {
  const std::vector<float>* axes[3] = {&x, &y, &z};
  Grid g{};
  double samples = 1;
  for (int a = 0; a < 3; ++a) {
    const auto [lo, hi] = std::minmax_element(axes[a]->begin(), axes[a]->end());
    g.origin[a] = double(*lo) - support;
    const double cells = std::ceil((double(*hi) + support - g.origin[a]) / voxel);
    samples *= cells + 1;
    if (!(samples <= kMaxSamples))
      throw make_error("vtk_sph_surface: voxel ", voxel, " makes a volume of over ", kMaxSamples,
                       " samples");
    g.dims[a] = static_cast<int>(cells) + 1;
  }
  return g;
}

// The mesh's triangles as indices, whatever width VTK stored them in.
std::vector<std::uint32_t> triangle_indices(vtkPolyData* mesh) {
  vtkCellArray* polys = mesh->GetPolys();
  const vtkIdType cells = polys->GetNumberOfCells();
  std::vector<std::uint32_t> out(static_cast<std::size_t>(3 * cells));
  auto copy = [&](auto* offsets, auto* connectivity) {
    for (vtkIdType c = 0; c < cells; ++c)
      if (offsets->GetValue(c + 1) - offsets->GetValue(c) != 3)
        throw make_error("vtk_sph_surface: vtkFlyingEdges3D gave a polygon that is not a triangle");
    const vtkIdType n = connectivity->GetNumberOfValues();
    for (vtkIdType i = 0; i < n; ++i)
      out[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(connectivity->GetValue(i));
  };
  if (polys->IsStorage64Bit()) copy(polys->GetOffsetsArray64(), polys->GetConnectivityArray64());
  else copy(polys->GetOffsetsArray32(), polys->GetConnectivityArray32());
  return out;
}

// +1 where the triangles' right-handed normals (Embree's geometric normal, (v1-v0) x (v2-v0))
// face out of the fluid, -1 where they face in: the sign of the enclosed volume. VTK's contour
// winding then need not be assumed.
double outward_sign(const float* v, const std::vector<std::uint32_t>& tri) {
  const std::size_t n = tri.size() / 3;
  const double volume6 = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n), 0.0,
      [&](const tbb::blocked_range<std::size_t>& r, double sum) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
          const float* a = v + 3 * tri[3 * t];
          const float* b = v + 3 * tri[3 * t + 1];
          const float* c = v + 3 * tri[3 * t + 2];
          const glm::dvec3 p(a[0], a[1], a[2]), q(b[0], b[1], b[2]), s(c[0], c[1], c[2]);
          sum += glm::dot(p, glm::cross(q, s));
        }
        return sum;
      },
      [](double a, double b) { return a + b; });
  return volume6 >= 0 ? 1.0 : -1.0;
}

}  // namespace

PeerSurface vtk_sph_surface(const std::vector<float>& x, const std::vector<float>& y,
                            const std::vector<float>& z, double spacing, const Camera& camera,
                            const VtkSphOptions& options) {
  Stopwatch total;
  check_input(x, y, z, spacing, camera, options);
  const double h = options.smoothing_length;
  const double support = (options.quintic ? kQuinticSupport : kCubicSupport) * h;
  const Grid grid = probe_grid(x, y, z, options.voxel, support);
  PeerSurface out;

  // --- interpolate: the fraction on the volume's points
  Stopwatch watch;
  vtkNew<vtkPolyData> cloud = particle_cloud(x, y, z, spacing);
  vtkNew<vtkImageData> volume;
  volume->SetDimensions(grid.dims[0], grid.dims[1], grid.dims[2]);
  volume->SetOrigin(grid.origin[0], grid.origin[1], grid.origin[2]);
  volume->SetSpacing(options.voxel, options.voxel, options.voxel);
  vtkNew<vtkSPHCubicKernel> cubic;
  vtkNew<vtkSPHQuinticKernel> quintic;
  vtkSPHKernel* kernel = options.quintic ? static_cast<vtkSPHKernel*>(quintic.Get()) : cubic.Get();
  kernel->SetSpatialStep(h);
  kernel->SetDimension(3);
  vtkNew<vtkStaticPointLocator> locator;
  vtkNew<vtkSPHInterpolator> interpolator;
  interpolator->SetInputData(volume);
  interpolator->SetSourceData(cloud);
  interpolator->SetKernel(kernel);
  interpolator->SetLocator(locator);
  interpolator->SetMassArrayName("mass");
  interpolator->SetDensityArrayName("density");
  interpolator->AddExcludedArray("mass");
  interpolator->AddExcludedArray("density");
  // The raw sum: Shepard normalization would divide the fraction by itself (1 wherever any
  // particle is in reach), and the sum array itself is not needed.
  interpolator->ShepardNormalizationOff();
  interpolator->ComputeShepardSumOff();
  interpolator->SetNullPointsStrategyToNullValue();
  interpolator->SetNullValue(0);
  interpolator->PassPointArraysOff();
  interpolator->PassCellArraysOff();
  interpolator->PassFieldArraysOff();
  interpolator->Update();
  out.ms["interpolate"] = watch.ms();

  // --- contour
  watch.restart();
  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputConnection(interpolator->GetOutputPort());
  contour->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "fraction");
  contour->SetValue(0, options.iso);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  contour->InterpolateAttributesOff();
  contour->Update();
  vtkPolyData* mesh = contour->GetOutput();
  out.ms["contour"] = watch.ms();

  // --- bvh: the mesh into Embree (copied: Embree wants padded buffers) and its build
  watch.restart();
  const vtkIdType vertex_count = mesh->GetNumberOfPoints();
  if (vertex_count > std::numeric_limits<std::int32_t>::max())
    throw make_error("vtk_sph_surface: ", vertex_count,
                     " mesh vertices; Embree indices are 32 bit");
  const std::vector<std::uint32_t> tri = triangle_indices(mesh);
  out.elements = tri.size() / 3;
  const RTCDevice device = embree_device();
  EmbreeScene scene(device);
  double outward = 1;
  if (out.elements > 0) {
    vtkFloatArray* points = vtkFloatArray::SafeDownCast(mesh->GetPoints()->GetData());
    if (points == nullptr) throw make_error("vtk_sph_surface: the mesh's points are not float");
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                          static_cast<std::size_t>(vertex_count)));
    auto* i = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), out.elements));
    if (v == nullptr || i == nullptr) {
      rtcReleaseGeometry(g);
      throw make_error("vtk_sph_surface: Embree could not allocate the mesh's buffers");
    }
    std::copy_n(points->GetPointer(0), 3 * vertex_count, v);
    std::copy(tri.begin(), tri.end(), i);
    outward = outward_sign(v, tri);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene.get(), g);
    rtcReleaseGeometry(g);
  }
  rtcSetSceneBuildQuality(scene.get(), kBuildQuality);
  // Watertight: a ray through a shared edge of the back surface must hit one of the two
  // triangles, or its exit is lost and the thickness with it (tens of spacings on a few pixels
  // of the ball without the flag).
  rtcSetSceneFlags(scene.get(), RTC_SCENE_FLAG_ROBUST);
  rtcCommitScene(scene.get());
  if (rtcGetDeviceError(device) != RTC_ERROR_NONE)
    throw make_error("vtk_sph_surface: Embree's build failed");
  out.ms["bvh"] = watch.ms();

  // --- cast: every hit along each pixel's centre ray
  watch.restart();
  const ViewFrame view(camera);
  const int w = view.width, hgt = view.height;
  const auto pixels = static_cast<std::size_t>(w) * static_cast<std::size_t>(hgt);
  out.first_hit.assign(pixels, std::numeric_limits<float>::infinity());
  out.thickness.assign(pixels, 0.0f);
  out.spans.assign(pixels, {});
  // Past a hit by more than float's rounding of t, so that the next query cannot find the same
  // triangle again (or its neighbour across a shared edge), yet far less than any feature the
  // volume can resolve.
  const float eps_voxel = static_cast<float>(1e-3 * options.voxel);
  tbb::parallel_for(tbb::blocked_range<int>(0, hgt), [&](const tbb::blocked_range<int>& rows) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (int py = rows.begin(); py != rows.end(); ++py)
      for (int px = 0; px < w; ++px) {
        const glm::dvec3 d = glm::normalize(view.world_ray(px, py));
        const std::size_t k = static_cast<std::size_t>(py) * w + static_cast<std::size_t>(px);
        float tnear = 0, entered_at = 0, inside = 0;
        int depth = 0;
        for (int hit = 0; hit < kMaxHitsPerRay; ++hit) {
          RTCRayHit r{};
          r.ray.org_x = float(view.eye.x), r.ray.org_y = float(view.eye.y);
          r.ray.org_z = float(view.eye.z);
          r.ray.dir_x = float(d.x), r.ray.dir_y = float(d.y), r.ray.dir_z = float(d.z);
          r.ray.tnear = tnear;
          r.ray.tfar = std::numeric_limits<float>::infinity();
          r.ray.mask = 0xffffffffu;
          r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          rtcIntersect1(scene.get(), &context, &r);
          if (r.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;
          const float t = r.ray.tfar;
          if (hit == 0) out.first_hit[k] = t;
          const double facing = outward * (d.x * r.hit.Ng_x + d.y * r.hit.Ng_y + d.z * r.hit.Ng_z);
          if (facing < 0) {
            if (depth++ == 0) entered_at = t;
          } else if (depth == 0) {
            inside += t;  // the eye is inside the fluid: inside from the eye on
            out.spans[k].insert(out.spans[k].end(), {0.0f, t});
          } else if (--depth == 0) {
            inside += t - entered_at;
            out.spans[k].insert(out.spans[k].end(), {entered_at, t});
          }
          tnear = t + std::max(eps_voxel, 1e-6f * t);
        }
        out.thickness[k] = inside;
      }
  });
  out.ms["cast"] = watch.ms();
  out.ms["total"] = total.ms();

  char text[256];
  std::snprintf(text, sizeof text,
                "VTK %s vtkSPHInterpolator (%s, h %.3g dx) on voxel %.3g dx (%dx%dx%d), "
                "vtkFlyingEdges3D iso %.3g, SMP %s; Embree %s (%s BVH)",
                VTK_VERSION, options.quintic ? "quintic" : "cubic", h / spacing,
                options.voxel / spacing, grid.dims[0], grid.dims[1], grid.dims[2], options.iso,
                vtk_smp_backend().c_str(), RTC_VERSION_STRING, kBuildQualityName);
  out.note = text;
  return out;
}

}  // namespace voxspan::tools
