// Automatic framing: the fluid's box just fits the view (every corner inside the pyramid, one
// on its edge), the box follows the fluid as the view's `framing` says, leaves out far strays
// (BulkBox), or is the user's `bounds`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "insitu/views/surface_view.h"
#include "insitu/views/view_framing.h"

namespace voxspan {
namespace {

SurfaceSettings view_looking(Vec3d direction, Framing framing = Framing::grow) {
  SurfaceSettings v;
  v.width = 960;
  v.height = 540;
  v.camera.direction = direction;
  v.camera.framing = framing;
  return v;
}

// The largest of |x| / (tan_x z) and |y| / (tan_y z) over the corners of the box grown by the
// margin: <= 1 when every corner is inside the view, 1 when one touches its edge.
double fill(const Camera& camera, const Bounds& b, double margin) {
  const ViewFrame frame(camera);
  const glm::dvec3 lo(b.lo[0], b.lo[1], b.lo[2]), hi(b.hi[0], b.hi[1], b.hi[2]);
  const glm::dvec3 c = 0.5 * (lo + hi), half = 0.5 * margin * (hi - lo);
  double most = 0;
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 p = c + glm::dvec3(k & 1 ? half.x : -half.x, k & 2 ? half.y : -half.y,
                                        k & 4 ? half.z : -half.z);
    const glm::dvec3 v = frame.to_view(p);
    EXPECT_GT(v.z, 0);
    most = std::max(
        {most, std::abs(v.x) / (frame.tan_half_x * v.z), std::abs(v.y) / (frame.tan_half_y * v.z)});
  }
  return most;
}

// Spheres of radius 0.01 at 0.05 spacing over [x0, x1] x [0, 0.25] x [0, z1].
std::vector<ParticleSphere> block(float x0, float x1, float z1) {
  std::vector<ParticleSphere> s;
  const auto steps = [](float length) { return int(std::lround(length / 0.05f)); };
  for (int i = 0; i <= steps(x1 - x0); ++i)
    for (int j = 0; j <= steps(0.25f); ++j)
      for (int k = 0; k <= steps(z1); ++k)
        s.push_back({x0 + 0.05f * i, 0.05f * j, 0.05f * k, 0.01f});
  return s;
}

TEST(ViewFraming, TheFluidsBoxJustFitsTheView) {
  for (Vec3d direction :
       {Vec3d{0.3, 1, -0.45}, Vec3d{-1, 2, -0.8}, Vec3d{0, 0.01, -1}, Vec3d{1, 0, 0}}) {
    SurfaceSettings v = view_looking(direction);
    if (std::abs(direction[2]) > 0.99) v.camera.up = {0, 1, 0};
    const std::vector<ParticleSphere> spheres = block(0, 1, 0.5);
    const Bounds box = Bounds::of_spheres(spheres);
    EXPECT_FLOAT_EQ(float(box.lo[0]), -0.01f);
    const Camera camera = frame_camera(v, box);
    EXPECT_NEAR(fill(camera, box, v.camera.margin), 1.0, 1e-9) << direction[0];
    validate(camera);
  }
}

// Between a legend's margins: every corner of the grown box projects inside the space they
// leave (one on its edge), the camera still looking along the configured direction.
TEST(ViewFraming, TheFluidsBoxJustFitsBetweenTheLegendsMargins) {
  const LegendMargins clear{.left = 40, .right = 150, .top = 30, .bottom = 10};
  for (Vec3d direction : {Vec3d{0.3, 1, -0.45}, Vec3d{-1, 2, -0.8}, Vec3d{1, 0, 0}}) {
    SurfaceSettings v = view_looking(direction);
    const Bounds box = Bounds::of_spheres(block(0, 1, 0.5));
    const Camera camera = frame_camera(v.camera, v.width, v.height, box, clear);
    const ViewFrame frame(camera);
    const glm::dvec3 lo(box.lo[0], box.lo[1], box.lo[2]), hi(box.hi[0], box.hi[1], box.hi[2]);
    const glm::dvec3 c = 0.5 * (lo + hi), half = 0.5 * v.camera.margin * (hi - lo);
    double inside = 1e300;  // the least distance in pixels from a corner to the space's edges
    for (int k = 0; k < 8; ++k) {
      const glm::dvec3 p =
          frame.to_view(c + glm::dvec3(k & 1 ? half.x : -half.x, k & 2 ? half.y : -half.y,
                                       k & 4 ? half.z : -half.z));
      const double x = (0.5 + 0.5 * p.x / (frame.tan_half_x * p.z)) * v.width;
      const double y = (0.5 - 0.5 * p.y / (frame.tan_half_y * p.z)) * v.height;
      inside = std::min({inside, x - clear.left, v.width - clear.right - x, y - clear.top,
                         v.height - clear.bottom - y});
    }
    EXPECT_NEAR(inside, 0, 1e-6) << direction[0];
    const glm::dvec3 d = glm::normalize(glm::dvec3(direction[0], direction[1], direction[2]));
    EXPECT_NEAR(glm::dot(glm::normalize(camera.target - camera.eye), d), 1, 1e-12);
    // No margins: the camera at the box's centre, as without them.
    const Camera plain = frame_camera(v.camera, v.width, v.height, box, {});
    EXPECT_EQ(plain.target, c);
  }
}

// Cinema's angles turn a camera framed beside a legend about the fluid's centre: the centre
// stays where the picture shows it (not swung under the bar at phi 180); about its target, the
// camera turns as before.
TEST(ViewFraming, TurnsAboutThePivotKeepItWhereThePictureShowsIt) {
  SurfaceSettings v = view_looking({-1, 2, -0.8});
  ViewFraming framing(v, {.right = 150});
  const Camera camera = framing.update(Bounds::of_spheres(block(0, 1, 0.5)));
  const glm::dvec3 pivot = framing.pivot();
  const auto seen = [&](const Camera& c) {
    const glm::dvec3 p = ViewFrame(c).to_view(pivot);
    return glm::dvec2(p.x / p.z, p.y / p.z);
  };
  ASSERT_LT(seen(camera).x, -0.05);  // left of the middle, clear of the bar
  for (const auto& [phi, theta] :
       {std::pair{90.0, 0.0}, std::pair{180.0, 0.0}, std::pair{-45.0, 30.0}}) {
    const Camera turned = orbited(camera, phi, theta, pivot);
    EXPECT_NEAR(glm::length(seen(turned) - seen(camera)), 0, 1e-9) << phi;
    EXPECT_NEAR(glm::length(turned.eye - turned.target), glm::length(camera.eye - camera.target),
                1e-9);
    const Camera plain = orbited(camera, phi, theta, camera.target);
    EXPECT_EQ(plain.target, camera.target);
    EXPECT_EQ(plain.eye, orbited(camera, phi, theta).eye);
  }
}

TEST(ViewFraming, GrowEachStepAndFirstFollowTheFluidDifferently) {
  const std::vector<ParticleSphere> column = block(0, 0.25, 0.5), spread = block(0, 1, 0.1);
  ViewFraming grow(view_looking({0.3, 1, -0.45}, Framing::grow));
  ViewFraming each(view_looking({0.3, 1, -0.45}, Framing::each_step));
  ViewFraming first(view_looking({0.3, 1, -0.45}, Framing::first));
  for (ViewFraming* f : {&grow, &each, &first}) f->update(column);
  for (ViewFraming* f : {&grow, &each, &first}) f->update(spread);
  // grow: the union (tall and long); each_step: the spread only; first: the column only.
  EXPECT_NEAR(grow.box().hi[0], 1.01, 1e-6);
  EXPECT_NEAR(grow.box().hi[2], 0.51, 1e-6);
  EXPECT_NEAR(each.box().hi[0], 1.01, 1e-6);
  EXPECT_NEAR(each.box().hi[2], 0.11, 1e-6);
  EXPECT_NEAR(first.box().hi[0], 0.26, 1e-6);
  EXPECT_NEAR(first.box().hi[2], 0.51, 1e-6);
  // No particle at all (or only NaN): the box keeps what it had.
  const std::vector<ParticleSphere> none = {{NAN, 0, 0, 0.01f}};
  each.update(none);
  EXPECT_NEAR(each.box().hi[0], 1.01, 1e-6);
}

TEST(ViewFraming, ManualCameraIsAsGivenAndStillTracksTheBox) {
  SurfaceSettings v;
  v.width = 320;
  v.height = 200;
  v.camera.automatic = false;
  v.camera.eye = {1, -2, 3};
  v.camera.target = {0.5, 0, 0};
  v.camera.fov_degrees = 30;
  ViewFraming framing(v);
  const Camera c = framing.update(block(0, 1, 0.5));
  EXPECT_EQ(c.eye, glm::dvec3(1, -2, 3));
  EXPECT_EQ(c.target, glm::dvec3(0.5, 0, 0));
  EXPECT_EQ(c.fov_y_degrees, 30);
  EXPECT_EQ(c.width, 320);
  EXPECT_NEAR(framing.box().lo[2], -0.01, 1e-6);  // the ground goes under the fluid
}

// The bulk's box leaves out a body of under 1 % of the spheres 8 diameters or more away, at
// either end and on any axis; keeps two large bodies far apart (a splash that landed), and a
// small one that is close (a droplet just off the surface).
TEST(BulkBox, LeavesOutOnlySmallFarBodies) {
  const std::vector<ParticleSphere> main = block(0, 1, 0.5);  // 21 x 6 x 11 spheres
  const auto with = [&](std::vector<ParticleSphere> extra) {
    std::vector<ParticleSphere> all = main;
    all.insert(all.end(), extra.begin(), extra.end());
    return bulk_box(all);
  };
  const BulkBox::Split alone = bulk_box(main);
  EXPECT_EQ(alone.left_out, 0);
  for (const ParticleSphere far :
       {ParticleSphere{5, 0.1f, 0.1f, 0.01f}, ParticleSphere{0.5f, 0.1f, -3, 0.01f},
        ParticleSphere{0.5f, 1e20f, 0.2f, 0.01f}}) {
    const BulkBox::Split s = with({far, far});
    EXPECT_EQ(s.left_out, 2);
    EXPECT_EQ(s.box.lo, alone.box.lo);
    EXPECT_EQ(s.box.hi, alone.box.hi);
    EXPECT_EQ(s.left_out_box.lo[0], double(far.x));
  }
  // A second block as large, 3 m away: both framed.
  std::vector<ParticleSphere> second = block(4, 5, 0.5);
  const BulkBox::Split both = with(second);
  EXPECT_EQ(both.left_out, 0);
  EXPECT_NEAR(both.box.hi[0], 5.01, 1e-6);
  // A droplet 3 diameters off the top: part of the fluid.
  const BulkBox::Split droplet = with({{0.5f, 0.1f, 0.56f, 0.01f}});
  EXPECT_EQ(droplet.left_out, 0);
  EXPECT_NEAR(droplet.box.hi[2], 0.57, 1e-6);
}

// camera.bounds frames the user's box whatever the fluid does.
TEST(ViewFraming, FixedBoundsAreFramedWhateverTheFluid) {
  SurfaceSettings v = view_looking({-1, 2, -0.8});
  v.camera.bounds = {{{0, 3}}, {{0, 1}}, {{0, 0.5}}};
  ViewFraming framing(v);
  const Camera a = framing.update(block(0, 0.2, 0.2));
  const Camera b = framing.update(block(0, 1, 0.5));
  EXPECT_EQ(a.eye, b.eye);
  EXPECT_EQ(framing.box().hi[0], 3);
  EXPECT_NEAR(fill(a, framing.box(), v.camera.margin), 1.0, 1e-9);
  EXPECT_FALSE(framing.jumped());
}

// A 2D run's centres lie in one plane to rounding; a 3D block's, a line's and a point's do not.
TEST(ViewFraming, FlatAxisIsThePlaneOfATwoDimensionalRun) {
  const auto centres = [](Vec3d lo, Vec3d hi) {
    Bounds b;
    b.lo = lo, b.hi = hi;
    return b;
  };
  EXPECT_EQ(flat_axis(centres({0, 0, 0}, {1, 0.5, 0})), 2);
  EXPECT_EQ(flat_axis(centres({0, 3, 0}, {1, 3 + 1e-12, 2})), 1);
  EXPECT_EQ(flat_axis(centres({0, 0, 0}, {1, 0.5, 0.02})), -1);  // a shallow 3D layer
  EXPECT_EQ(flat_axis(centres({0, 0, 0}, {1, 0, 0})), -1);       // a line
  EXPECT_EQ(flat_axis(centres({1, 1, 1}, {1, 1, 1})), -1);       // a point
  EXPECT_EQ(flat_axis(Bounds{}), -1);
}

// Head-on with the plane's upward axis up at the default direction and up; the view's own
// direction or up wins over it, and the box still just fits.
TEST(ViewFraming, TwoDimensionalRunsAreSeenHeadOnUnlessTheViewSaysOtherwise) {
  Bounds sheet;
  sheet.lo = {0, 0, -0.01}, sheet.hi = {1, 0.5, 0.01};
  SurfaceSettings v = view_looking(CameraConfig{}.direction);
  Camera c = frame_camera(v.camera, v.width, v.height, sheet, {}, 2);
  glm::dvec3 forward = glm::normalize(c.target - c.eye);
  EXPECT_NEAR(forward.z, -1, 1e-12);
  EXPECT_EQ(c.up, glm::dvec3(0, 1, 0));
  EXPECT_NEAR(fill(c, sheet, v.camera.margin), 1, 1e-9);

  sheet.lo = {0, -0.01, 0}, sheet.hi = {1, 0.01, 0.5};
  c = frame_camera(v.camera, v.width, v.height, sheet, {}, 1);
  EXPECT_NEAR(glm::normalize(c.target - c.eye).y, 1, 1e-12);
  EXPECT_EQ(c.up, glm::dvec3(0, 0, 1));

  v.camera.direction = {0.3, 1, -0.45};
  c = frame_camera(v.camera, v.width, v.height, sheet, {}, 1);
  forward = glm::normalize(c.target - c.eye);
  EXPECT_NEAR(glm::dot(forward, glm::normalize(glm::dvec3(0.3, 1, -0.45))), 1, 1e-12);
}

}  // namespace
}  // namespace voxspan
