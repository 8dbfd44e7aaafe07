// The stability suite's translations: the same blob far from the world's origin (1e5, 4.2e6 as
// in UTM coordinates, 1e7, each rounded to whole periods of the ground's checker) with its camera
// moved alike gives the picture it gives at the origin, in the volume views (DVR and iso) on both
// renderers. Positions reach the passes as floats, whose step at 4.2e6 is 0.5: a view that stored
// world positions in float before shifting them to the eye drew a 0.05-spacing blob as slabs
// (render/frame_origin.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "insitu/runtime/pipeline.h"
#include "tests/support/temp_folder.h"
#include "voxspan/insitu.h"

namespace voxspan {
namespace {

constexpr double kSpacing = 0.05;

// A ball of radius 0.5 on a lattice of kSpacing, centred on (offset, 0, 0), its values a
// Gaussian of the distance from the centre (computed before the shift: the same at any offset).
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
        b.x.push_back(offset + i * kSpacing), b.y.push_back(j * kSpacing);
        b.z.push_back(k * kSpacing), b.value.push_back(std::exp(-r2 / (2 * 0.15 * 0.15)));
      }
  return b;
}

// The linear picture of one view of the blob at `offset`, seen from 2 in front of it.
FloatImage picture(const std::string& backend, const std::string& view, double offset) {
  test::TempFolder dir;
  const std::string target = std::to_string(offset) + ", 0, 0";
  const std::string eye = std::to_string(offset) + ", -2, 0";
  const std::string yaml =
      "output_folder: " + dir.path().string() +
      "\noutputs: {png: {enabled: false}, stats: {enabled: false}}\n"
      "trigger: {every_steps: 1}\nwriter: {fsync: false}\nrenderer: {backend: " +
      backend + "}\nviews:\n  - {name: v, " + view +
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
  return r.shared_picture != nullptr ? **r.shared_picture : *r.picture;
}

double largest_difference(const FloatImage& a, const FloatImage& b) {
  EXPECT_EQ(a.rgba.size(), b.rgba.size());
  double most = 0;
  for (std::size_t k = 0; k < std::min(a.rgba.size(), b.rgba.size()); ++k)
    most = std::max(most, double(std::abs(a.rgba[k] - b.rgba[k])));
  return most;
}

TEST(Stability, VolumeViewsFarFromTheOriginDrawWhatTheyDrawAtIt) {
  const std::string views[] = {
      "kind: volume, quantity: T, background: none",
      "kind: volume, quantity: T, mode: iso, iso: [{value: 0.5}], background: none",
      "kind: volume, quantity: T, background: sky"};
  for (const std::string backend : {"cpu", "gl"})
    for (const std::string& view : views) {
      SCOPED_TRACE(backend + " " + view);
      const FloatImage at_origin = picture(backend, view, 0);
      // Whole periods of the ground's checker (2 tiles of 12 spacings): the ground stays where
      // the world has it, so only there does the sky's picture repeat.
      for (double offset : {1.2 * 83334, 4.2e6, 1.2 * 8333334}) {
        const double d = largest_difference(picture(backend, view, offset), at_origin);
        std::printf("%s {%s} at %g: largest difference %.2e\n", backend.c_str(), view.c_str(),
                    offset, d);
        EXPECT_LT(d, 2e-3) << offset;
      }
    }
}

}  // namespace
}  // namespace voxspan
