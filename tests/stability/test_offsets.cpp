// The stability suite's translations: the same blob far from the world's origin (1e5, 4.2e6 as
// in UTM coordinates, 1e7, each rounded to whole periods of the ground's checker) with its camera
// moved alike gives the picture it gives at the origin, in the volume views (DVR and iso) and
// the surface views (opaque, translucent, refractive) on both renderers; and the snapshots hold
// it where the world has it. Positions reach the passes as floats, whose step at 4.2e6 is 0.5: a
// view that stored world positions in float before shifting them drew a 0.05-spacing blob as
// slabs (render/frame_origin.h, ClassifyOptions::origin).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "insitu/io/particle_data.h"
#include "insitu/runtime/pipeline.h"
#include "tests/support/temp_folder.h"
#include "voxspan/insitu.h"

namespace voxspan {
namespace {

constexpr double kSpacing = 0.05;
constexpr double kOffFaces = 0.25 * kSpacing;  // blob()'s

// A ball of radius 0.5 on a lattice of kSpacing, centred on (offset, 0, 0), its values a
// Gaussian of the distance from the centre (computed before the shift: the same at any offset).
// The lattice stands a quarter spacing off the faces of the adapter's cells (multiples of 2
// spacings): a particle on a face falls in the cell its rounding picks, which differs with the
// offset, and so would the cell states.
struct Blob {
  std::vector<double> x, y, z, value;
};
Blob blob(double offset) {
  Blob b;
  for (int i = -10; i <= 10; ++i)
    for (int j = -10; j <= 10; ++j)
      for (int k = -10; k <= 10; ++k) {
        const double r2 = (i * i + j * j + k * k) * kSpacing * kSpacing;
        if (r2 > 0.25 + 1e-9) continue;
        b.x.push_back(offset + i * kSpacing + kOffFaces), b.y.push_back(j * kSpacing + kOffFaces);
        b.z.push_back(k * kSpacing + kOffFaces);
        b.value.push_back(std::exp(-r2 / (2 * 0.15 * 0.15)));
      }
  return b;
}

// One render step of the blob at `offset` with one view, seen from 2 in front of it, and
// `outputs` (YAML) into `dir`; returns the view's linear picture.
FloatImage picture(const std::string& backend, const std::string& view, double offset,
                   const std::filesystem::path& dir, const std::string& outputs) {
  const std::string target = std::to_string(offset) + ", 0, 0";
  const std::string eye = std::to_string(offset) + ", -2, 0";
  const std::string yaml =
      "output_folder: " + dir.string() +
      "\noutputs: {png: {enabled: false}, stats: {enabled: false}" + outputs +
      "}\ntrigger: {every_steps: 1}\nwriter: {fsync: false}\nrenderer: {backend: " + backend +
      "}\nviews:\n  - {name: v, " + view +
      ", width: 96, height: 96, caption: '', legend: false, camera: {eye: [" + eye +
      "], target: [" + target + "], up: [0, 0, 1], fov: 40}}\n";
  AdapterOptions o;
  o.classify.particle_spacing = kSpacing;
  Adapter a = adapter_from_config_text(yaml, o, "offsets.yaml");
  const Blob b = blob(offset);
  const Status s = a.execute(1, 0.0,
                             ParticleView::soa(b.x.data(), b.y.data(), b.z.data(), b.x.size())
                                 .with_scalar("T", b.value.data()));
  EXPECT_TRUE(s.ok()) << s.message;
  const ViewResult& r = dynamic_cast<const InsituPipeline&>(*a.pipeline()).latest_views()[0];
  FloatImage linear = r.shared_picture != nullptr ? **r.shared_picture : *r.picture;
  a.finish();  // the files written
  return linear;
}

FloatImage picture(const std::string& backend, const std::string& view, double offset) {
  test::TempFolder dir;
  return picture(backend, view, offset, dir.path(), "");
}

// How far two pictures are apart: their largest difference in any channel, and the share of the
// pixels with a channel more than 2e-3 apart.
struct Difference {
  double largest = 0, share_apart = 0;
};
Difference difference(const FloatImage& a, const FloatImage& b) {
  EXPECT_EQ(a.rgba.size(), b.rgba.size());
  Difference d;
  std::size_t apart = 0;
  for (std::size_t p = 0; p + 4 <= std::min(a.rgba.size(), b.rgba.size()); p += 4) {
    double most = 0;
    for (std::size_t c = p; c < p + 4; ++c)
      most = std::max(most, double(std::abs(a.rgba[c] - b.rgba[c])));
    d.largest = std::max(d.largest, most);
    apart += most > 2e-3 ? 1 : 0;
  }
  d.share_apart = double(apart) / double(std::max<std::size_t>(a.rgba.size() / 4, 1));
  return d;
}

// Every view on both renderers draws the blob far from the origin as it draws it at the origin:
// every pixel within 2e-3, or, for views `chaotic` on the CPU renderer, all but `chaotic` of
// them.
void expect_the_same_far_away(std::span<const std::string> views, double chaotic = 0) {
  for (const std::string backend : {"cpu", "gl"})
    for (const std::string& view : views) {
      SCOPED_TRACE(backend + " " + view);
      const FloatImage at_origin = picture(backend, view, 0);
      // Whole periods of the ground's checker (2 tiles of 12 spacings): the ground stays where
      // the world has it, so only there does the sky's picture repeat.
      for (double offset : {1.2 * 83334, 4.2e6, 1.2 * 8333334}) {
        const Difference d = difference(picture(backend, view, offset), at_origin);
        std::printf("%s {%s} at %g: largest difference %.2e, %.2f %% of the pixels over 2e-3\n",
                    backend.c_str(), view.c_str(), offset, d.largest, 100 * d.share_apart);
        if (backend == "cpu" && chaotic > 0) EXPECT_LE(d.share_apart, chaotic) << offset;
        else EXPECT_LT(d.largest, 2e-3) << offset;
      }
    }
}

TEST(Stability, VolumeViewsFarFromTheOriginDrawWhatTheyDrawAtIt) {
  const std::string views[] = {
      "kind: volume, quantity: T, background: none",
      "kind: volume, quantity: T, mode: iso, iso: [{value: 0.5}], background: none",
      "kind: volume, quantity: T, background: sky"};
  expect_the_same_far_away(views);
}

// The boundary spheres are measured from a point of the fluid (ClassifyOptions::origin); each
// picture has the ground under the blob.
TEST(Stability, SurfaceViewsFarFromTheOriginDrawWhatTheyDrawAtIt) {
  const std::string views[] = {"kind: surface, shading: opaque",
                               "kind: surface, shading: translucent"};
  expect_the_same_far_away(views);
  // The CPU renderer's refraction turns a few pixels (under 1 %) by 1e-2 to 7e-2 when the
  // spheres move by a float's rounding, at the origin too (they were measured from 0.5 away).
  const std::string refractive[] = {"kind: surface, shading: refractive"};
  expect_the_same_far_away(refractive, 0.01);
}

// The snapshots add the spheres' origin back in double: the .vtp's points (Float64 there) are
// the boundary particles where the world has them.
TEST(Stability, SnapshotsFarFromTheOriginHoldWorldPositions) {
  for (const double offset : {0.0, 4.2e6, 1e7}) {
    SCOPED_TRACE(offset);
    test::TempFolder dir;
    picture("cpu", "kind: surface", offset, dir.path(),
            ", vtk: {enabled: true, cells: false, trigger: {first: true}}, vdb: {enabled: true, "
            "trigger: {first: true}}");
    std::filesystem::path vtp;
    for (const auto& f : std::filesystem::recursive_directory_iterator(dir.path()))
      if (f.path().filename() == "particles_00000001.vtp") vtp = f.path();
    ASSERT_FALSE(vtp.empty());
    const ParticleData d = read_particles(vtp);
    ASSERT_GT(d.size(), 0u);
    double mean[3] = {0, 0, 0}, lo = 1e300, hi = -1e300;
    for (const std::array<double, 3>& p : d.positions) {
      for (int a = 0; a < 3; ++a) mean[a] += p[std::size_t(a)] / double(d.size());
      lo = std::min(lo, p[0]), hi = std::max(hi, p[0]);
    }
    // The shell is symmetric about the blob's centre, and reaches 0.5 either side.
    const double centre[3] = {offset + kOffFaces, kOffFaces, kOffFaces};
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(mean[a], centre[a], kSpacing / 100) << a;
    EXPECT_NEAR(lo, centre[0] - 0.5, 1e-6 * kSpacing);
    EXPECT_NEAR(hi, centre[0] + 0.5, 1e-6 * kSpacing);
  }
}

}  // namespace
}  // namespace voxspan
