// bench_embree: Embree's sphere traversal against the CPU renderer's caster
// (render/cpu/span_caster.h) on the spans alone, on the same spheres and camera in one run.
//
// Embree (Debian's libembree-dev, 3.x) holds the boundary spheres as RTC_GEOMETRY_TYPE_SPHERE_POINT
// in the classification's own float4 array (no copy) and rebuilds its BVH every frame, as the
// particles move. A pixel's centre ray collects every sphere it meets: an intersection filter
// records each hit's sphere and rejects it, so the traversal goes on to the end of the grid.
// The chords are then computed in double and joined like the caster's (gap bridging, no cap),
// and the spans compared with the caster's. The caster runs without inner-full cells here so
// that both see the same spheres. Also timed: Embree's closest hit alone (no filter), the least
// any Embree query costs, which gives the first surface only. Medians over --frames frames,
// the frames alternating between the two.
//
//   bench_embree [--particles N] [--time T] [--state FILE] [--ritter] [--size WxH] [--frames F]
#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "render/cpu/cpu_renderer.h"
#include "render/cpu/span_caster.h"
#include "tools/common/dambreak_state.h"
#include "tools/common/tool_args.h"
#include "tools/scenes/span_compare.h"
#include "voxspan/error.h"
#include "voxspan/stopwatch.h"

namespace {

using namespace voxspan;

struct Args : tools::BenchArgs, tools::StateFlags {};

constexpr char kUsage[] =
    "usage: bench_embree [--particles N] [--time T] [--state FILE] [--ritter] [--size WxH]\n"
    "         [--frames F]\n";

bool read_flag(tools::Arg& arg, Args& a) {
  return tools::read_bench_flag(arg, a) || tools::read_state_flag(arg, a);
}

bool parse(int argc, char** argv, Args& a) {
  return tools::read_args(argc, argv, a, read_flag) && a.particles > 0;
}

// The intersect context Embree hands to the filter, with the ray's list of spheres met.
struct CollectContext {
  RTCIntersectContext base;
  std::vector<unsigned>* met;
};

void collect_and_go_on(const RTCFilterFunctionNArguments* args) {
  auto* context = reinterpret_cast<CollectContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    context->met->push_back(RTCHitN_primID(args->hit, args->N, i));
    args->valid[i] = 0;  // rejected: the traversal goes on
  }
}

class EmbreeSpheres {
 public:
  EmbreeSpheres() : device_(rtcNewDevice(nullptr)) {
    if (device_ == nullptr)
      throw make_error("Embree: no device (", rtcGetDeviceError(nullptr), ")");
  }
  ~EmbreeSpheres() {
    if (scene_ != nullptr) rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  EmbreeSpheres(const EmbreeSpheres&) = delete;
  EmbreeSpheres& operator=(const EmbreeSpheres&) = delete;

  // A fresh BVH over `spheres` (x, y, z, radius: Embree's own FLOAT4 layout, shared).
  void build(const std::vector<ParticleSphere>& spheres, bool filter) {
    if (scene_ != nullptr) rtcReleaseScene(scene_);
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_DYNAMIC);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_LOW);  // rebuilt every frame
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, spheres.data(), 0,
                               sizeof(ParticleSphere), spheres.size());
    if (filter) rtcSetGeometryIntersectFilterFunction(g, collect_and_go_on);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw make_error("Embree: the build failed");
  }

  // Every sphere the ray of pixel (x, y) meets between the grid's near and far depths, into
  // `met` (cleared; a sphere may come twice, once per hit).
  void all_hits(const PerspectiveGrid& grid, int x, int y, std::vector<unsigned>& met) const {
    met.clear();
    CollectContext context;
    rtcInitIntersectContext(&context.base);
    context.met = &met;
    RTCRayHit ray = make_ray(grid, x, y);
    rtcIntersect1(scene_, &context.base, &ray);
  }

  // The nearest sphere's depth, or -1 for none.
  float closest(const PerspectiveGrid& grid, int x, int y) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit ray = make_ray(grid, x, y);
    rtcIntersect1(scene_, &context, &ray);
    return ray.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1.0f : ray.ray.tfar;
  }

 private:
  // Depth is the ray parameter: eye + z * world_ray(x, y) is the point at depth z.
  static RTCRayHit make_ray(const PerspectiveGrid& grid, int x, int y) {
    const glm::dvec3 o = grid.view().eye, d = grid.view().world_ray(x, y);
    RTCRayHit r{};
    r.ray.org_x = float(o.x), r.ray.org_y = float(o.y), r.ray.org_z = float(o.z);
    r.ray.dir_x = float(d.x), r.ray.dir_y = float(d.y), r.ray.dir_z = float(d.z);
    r.ray.tnear = float(grid.near());
    r.ray.tfar = float(grid.grid_far());
    r.ray.mask = 0xffffffffu;
    r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    return r;
  }

  RTCDevice device_;
  RTCScene scene_ = nullptr;
};

struct Chord {
  double entry, exit;
};

// The spans of the spheres `met` on pixel (x, y)'s ray: chords in double (closest-approach
// form), clipped to [near, grid_far], joined where they overlap or their gap along the ray is
// under `gap`.
PixelSpans spans_of(const PerspectiveGrid& grid, int x, int y, const std::vector<unsigned>& met,
                    const std::vector<glm::dvec4>& view_spheres, double gap,
                    std::vector<Chord>& chords, SpanListBuilder& builder) {
  const glm::dvec3 d = grid.view().view_ray(x, y);
  const double dd = glm::dot(d, d), scale = std::sqrt(dd);
  chords.clear();
  for (unsigned i : met) {
    const glm::dvec4 s = view_spheres[i];
    const glm::dvec3 c(s);
    const double mid = glm::dot(d, c) / dd;
    const glm::dvec3 off = c - mid * d;
    const double h2 = s.w * s.w - glm::dot(off, off);
    if (!(h2 > 0)) continue;
    const double half = std::sqrt(h2 / dd);
    const double a = std::max(mid - half, grid.near()), b = std::min(mid + half, grid.grid_far());
    if (a < b) chords.push_back({a, b});
  }
  std::sort(chords.begin(), chords.end(),
            [](const Chord& p, const Chord& q) { return p.entry < q.entry; });
  builder.begin();
  for (std::size_t k = 0; k < chords.size();) {
    Chord run = chords[k++];
    while (k < chords.size() && (chords[k].entry - run.exit) * scale < gap)
      run.exit = std::max(run.exit, chords[k++].exit);
    builder.add(run.entry, run.exit, scale);
  }
  return builder.end();
}

int run(const Args& a) {
  tools::DamBreakState s = tools::dam_break_state(a, a);
  s.camera.width = a.width;
  s.camera.height = a.height;
  const std::vector<ParticleSphere>& spheres = s.classification.boundary;
  const double gap = s.spacing;
  std::printf("scene: %s; %dx%d, %zu boundary spheres (no inner-full cells, for both)\n",
              s.description.c_str(), a.width, a.height, spheres.size());
  SpanOptions options;
  options.gap_bridging = gap;
  const PerspectiveGrid grid = [&] {
    CpuRenderer fit;
    Recorder recorder;
    return fit.cast(s.camera, spheres, CellStatesView{}, options, recorder).grid;
  }();
  std::vector<glm::dvec4> view_spheres;
  view_spheres.reserve(spheres.size());
  for (const ParticleSphere& p : spheres)
    view_spheres.emplace_back(grid.view().to_view(glm::dvec3(p.x, p.y, p.z)), p.radius);

  SpanCaster caster;
  EmbreeSpheres embree;
  SpanImage ours, theirs;
  theirs.grid = grid;
  const int w = grid.width(), h = grid.height();
  std::vector<double> cast_ms, build_ms, trace_ms, closest_build_ms, closest_ms;
  std::vector<std::vector<Span>> rows(static_cast<std::size_t>(h));
  std::int64_t spheres_met = 0;
  for (int f = -1; f < a.frames; ++f) {
    Stopwatch watch;
    caster.run(grid, spheres, CellStatesView{}, {gap, 0, false}, ours);
    const double cast = watch.ms();

    watch.restart();
    embree.build(spheres, true);
    const double build = watch.ms();
    watch.restart();
    theirs.pixels.assign(static_cast<std::size_t>(w) * h, PixelSpans{});
    std::vector<std::int64_t> met_per_row(static_cast<std::size_t>(h), 0);
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& r) {
      std::vector<unsigned> met;
      std::vector<Chord> chords;
      for (int y = r.begin(); y != r.end(); ++y) {
        auto& row = rows[static_cast<std::size_t>(y)];
        row.clear();
        SpanListBuilder builder(row, 0);
        for (int x = 0; x < w; ++x) {
          embree.all_hits(grid, x, y, met);
          met_per_row[static_cast<std::size_t>(y)] += std::int64_t(met.size());
          theirs.pixels[static_cast<std::size_t>(x) + static_cast<std::size_t>(y) * w] =
              spans_of(grid, x, y, met, view_spheres, gap, chords, builder);
        }
      }
    });
    theirs.spans.clear();
    for (int y = 0; y < h; ++y) {
      const auto offset = static_cast<std::uint32_t>(theirs.spans.size());
      for (int x = 0; x < w; ++x)
        theirs.pixels[static_cast<std::size_t>(x) + static_cast<std::size_t>(y) * w].offset +=
            offset;
      const auto& row = rows[static_cast<std::size_t>(y)];
      theirs.spans.insert(theirs.spans.end(), row.begin(), row.end());
    }
    const double trace = watch.ms();

    watch.restart();
    embree.build(spheres, false);
    const double closest_build = watch.ms();
    watch.restart();
    std::vector<float> first(static_cast<std::size_t>(w) * h);
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& r) {
      for (int y = r.begin(); y != r.end(); ++y)
        for (int x = 0; x < w; ++x)
          first[static_cast<std::size_t>(x) + static_cast<std::size_t>(y) * w] =
              embree.closest(grid, x, y);
    });
    const double closest = watch.ms();
    if (f < 0) continue;
    cast_ms.push_back(cast);
    build_ms.push_back(build);
    trace_ms.push_back(trace);
    closest_build_ms.push_back(closest_build);
    closest_ms.push_back(closest);
    spheres_met = 0;
    for (std::int64_t m : met_per_row) spheres_met += m;
  }
  const test::SpanComparison c = test::compare_spans(theirs, ours, 1e-3);
  const double cast = tools::median(cast_ms);
  const double all = tools::median(build_ms) + tools::median(trace_ms);
  const double first = tools::median(closest_build_ms) + tools::median(closest_ms);
  std::printf("CPU renderer's cast (every span)             %8.1f ms\n", cast);
  std::printf(
      "Embree, every span: build %.1f + traverse and join %.1f = %8.1f ms  (%.2f x the cast)\n",
      tools::median(build_ms), tools::median(trace_ms), all, all / cast);
  std::printf(
      "Embree, closest hit only: build %.1f + traverse %.1f  = %8.1f ms  (%.2f x the cast)\n",
      tools::median(closest_build_ms), tools::median(closest_ms), first, first / cast);
  std::printf("hits reported to the filter: %.1f per pixel\n",
              double(spheres_met) / (double(w) * h));
  std::printf(
      "Embree's spans against the cast's: %.4f %% of %lld pixels with the same count, boundaries "
      "within 1e-3 layer %.4f %%, worst %.2g layers\n",
      100 * c.count_match(), static_cast<long long>(c.pixels_hit), 100 * c.boundary_match(),
      c.worst_boundary_layers);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return voxspan::tools::tool_main<Args>("bench_embree", argc, argv, kUsage, parse, run);
}
