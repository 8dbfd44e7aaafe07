// The stability suite's automatic framing, through the public Adapter on both renderers: a
// 20^3 block with one particle escaped to 2, 1e6 or 1e30 world units is framed as the block
// alone (the stray left out, said in one warning with the count, the step done); and the same
// block framed alike at every decade of spacing from 1e-10 to 1e20 (and at 1e-30, 1e-20, 1e30
// and 1e36: frames far from unit scale are rendered in their own units, render/frame_units.h),
// and refused by name at 1e37 (its frame past the float depth images' range); the particles and
// volume views alike from 1e-20 to 1e30. Measured: the share of the view's pixels the fluid
// covers (the first-hit depth output), which automatic framing sets.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "insitu/runtime/pipeline.h"
#include "tests/support/log_capture.h"
#include "tests/support/temp_folder.h"
#include "tools/scenes/scenes.h"
#include "voxspan/insitu.h"

namespace voxspan {
namespace {

struct Block {
  std::vector<float> x, y, z;
  double spacing = 0;
};

// A 20^3 lattice block of `spacing`, and `strays` particles at those points.
Block block(double spacing, const std::vector<glm::dvec3>& strays = {}) {
  Block b;
  b.spacing = spacing;
  for (const ParticleSphere& p : test::lattice_block({0, 0, 0}, {20, 20, 20}, spacing, spacing))
    b.x.push_back(p.x), b.y.push_back(p.y), b.z.push_back(p.z);
  for (const glm::dvec3& s : strays)
    b.x.push_back(float(s.x)), b.y.push_back(float(s.y)), b.z.push_back(float(s.z));
  return b;
}

// The share of the view's pixels with fluid in them, on `backend` in a view of `kind`, after one
// step.
double coverage(const std::string& backend, const Block& b, const std::string& kind = "surface") {
  test::TempFolder dir;
  const std::string yaml =
      "output_folder: " + dir.path().string() +
      "\noutputs: {png: {enabled: false}, stats: {enabled: false}, "
      "depth: {enabled: true, trigger: {every_steps: 1}}}\ntrigger: {every_steps: 1}\n"
      "writer: {fsync: false}\nrenderer: {backend: " +
      backend + "}\nviews:\n  - {name: v, kind: " + kind + ", width: 96, height: 72}\n";
  AdapterOptions o;
  o.classify.particle_spacing = b.spacing;
  Adapter a = adapter_from_config_text(yaml, o, "framing.yaml");
  const Status s =
      a.execute(1, 0.0, ParticleView::soa(b.x.data(), b.y.data(), b.z.data(), b.x.size()));
  EXPECT_TRUE(s.ok()) << s.message;
  const ViewResult& r = dynamic_cast<const InsituPipeline&>(*a.pipeline()).latest_views()[0];
  if (r.first_hit_depth == nullptr) return -1;
  std::size_t covered = 0;
  const std::vector<float>& d = r.first_hit_depth->rgba;
  for (std::size_t k = 0; k < d.size(); k += 4) covered += d[k] > 0 ? 1 : 0;
  return double(covered) / double(d.size() / 4);
}

TEST(Stability, StrayParticlesLeaveTheFramingAndAreSaid) {
  for (const std::string backend : {"cpu", "gl"}) {
    SCOPED_TRACE(backend);
    const double alone = coverage(backend, block(0.01));
    std::printf("%s: the block alone covers %.4f of the view\n", backend.c_str(), alone);
    EXPECT_GT(alone, 0.1);
    for (double far : {2.0, 1e6, 1e30}) {
      test::LogCapture log;
      const double with = coverage(backend, block(0.01, {{far, 0.1, 0.05}}));
      std::printf("  one particle at %g: covers %.4f\n", far, with);
      EXPECT_NEAR(with, alone, 0.01 * alone) << far;
      const std::vector<std::string> warnings = log.at(LogLevel::warning);
      ASSERT_EQ(warnings.size(), 1u) << log.all();
      EXPECT_NE(warnings[0].find("leaves out 1 particle "), std::string::npos) << warnings[0];
    }
  }
}

// The particles and volume views need no frame units (their glyphs and marches work in double
// where lengths are squared): the same share of the view from 1e-20 to 1e30 too.
TEST(Stability, ParticlesAndVolumeViewsFrameAlikeAtEveryScale) {
  for (const std::string backend : {"cpu", "gl"})
    for (const std::string kind : {"particles", "volume"}) {
      SCOPED_TRACE(backend + " " + kind);
      const double unit = coverage(backend, block(1), kind);
      for (double spacing : {1e-20, 1e-10, 1e10, 1e20, 1e30}) {
        const double share = coverage(backend, block(spacing), kind);
        std::printf("%s %s: spacing %g covers %.4f of the view (%.4f at 1)\n", backend.c_str(),
                    kind.c_str(), spacing, share, unit);
        EXPECT_NEAR(share, unit, 0.01 * unit) << spacing;
      }
    }
}

TEST(Stability, TheSameFramingAtEveryScale) {
  for (const std::string backend : {"cpu", "gl"}) {
    SCOPED_TRACE(backend);
    const double unit = coverage(backend, block(1));
    // Every decade from 1e-10 to 1e20, and a few past it to each side.
    std::vector<double> spacings = {1e-30, 1e-20, 1e30, 1e36};
    for (int e = -10; e <= 20; ++e) spacings.push_back(std::pow(10.0, e));
    for (double spacing : spacings) {
      const double share = coverage(backend, block(spacing));
      std::printf("%s: spacing %g covers %.4f of the view (%.4f at 1)\n", backend.c_str(), spacing,
                  share, unit);
      EXPECT_NEAR(share, unit, 0.01 * unit) << spacing;
    }
  }
}

// Past 1e38 world units from the eye the float depth images (and span images) that leave
// the renderers would overflow: the step is refused, the bound named, not a wrong picture
// (docs/runtime.md). The 20^3 block at spacing 1e37 is framed from 6.9e38.
TEST(Stability, FramingPastTheFloatRangeIsRefusedByName) {
  for (const std::string backend : {"cpu", "gl"}) {
    SCOPED_TRACE(backend);
    test::TempFolder dir;
    const Block b = block(1e37);
    AdapterOptions o;
    o.classify.particle_spacing = b.spacing;
    Adapter a = adapter_from_config_text("output_folder: " + dir.path().string() +
                                             "\nrenderer: {backend: " + backend +
                                             "}\nviews: [{name: v, width: 32, height: 24}]\n",
                                         o, "far.yaml");
    const Status s =
        a.execute(1, 0.0, ParticleView::soa(b.x.data(), b.y.data(), b.z.data(), b.x.size()));
    EXPECT_FALSE(s.ok());
    EXPECT_NE(s.message.find("past the 1e+38 that its float span and depth images hold"),
              std::string::npos)
        << s.message;
  }
}

}  // namespace
}  // namespace voxspan
