// The live page's camera requests (`live.interactive`) without a server: what a POST /camera
// body may say, how the mailbox merges requests per view, and the offset they give a framed
// camera (orbit about its target, zoom along its axis, pan across its view, reset to it bit for
// bit). Over HTTP on a running job: tests/integration/live/test_live_interactive.py.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "insitu/live/camera_mailbox.h"

namespace voxspan {
namespace {

const std::vector<std::string> kViews = {"main", "side view"};

std::string error_of(std::string_view body) {
  CameraRequest r;
  return parse_camera_request(body, kViews, r);
}

TEST(CameraRequest, ReadsEachActionOfAnyView) {
  CameraRequest r;
  ASSERT_EQ(parse_camera_request("view=side+view&action=orbit&d_phi=30&d_theta=-12.5", kViews, r),
            "");
  EXPECT_EQ(r.view, 1u);
  EXPECT_EQ(r.change.requests, 1);
  EXPECT_EQ(r.change.d_phi, 30);
  EXPECT_EQ(r.change.d_theta, -12.5);
  ASSERT_EQ(parse_camera_request("action=pan&dy=0.25&view=main&dx=-0.5", kViews, r), "");
  EXPECT_EQ(r.view, 0u);
  EXPECT_EQ(r.change.pan_x, -0.5);
  EXPECT_EQ(r.change.pan_y, 0.25);
  ASSERT_EQ(parse_camera_request("view=side%20view&action=zoom&factor=1.5", kViews, r), "");
  EXPECT_EQ(r.change.zoom, 1.5);
  ASSERT_EQ(parse_camera_request("view=main&action=reset", kViews, r), "");
  EXPECT_EQ(r.change.reset, 1);
}

TEST(CameraRequest, RefusesWhatIsNotOneValidRequestAndSaysWhy) {
  EXPECT_EQ(error_of("view=top&action=reset"), "no view \"top\" (the views: main, side view)");
  EXPECT_EQ(error_of("action=reset"), "no view given (the views: main, side view)");
  EXPECT_EQ(error_of("view=main&action=spin"),
            "action must be orbit, pan, zoom or reset; got \"spin\"");
  EXPECT_EQ(error_of("view=main"), "action must be orbit, pan, zoom or reset; got none");
  EXPECT_EQ(error_of("view=main&action=orbit&d_phi=1"),
            "orbit needs d_phi, d_theta; d_theta is missing");
  EXPECT_EQ(error_of("view=main&action=zoom&factor=2&d_phi=1"),
            "unknown field d_phi for zoom (its fields: factor)");
  EXPECT_EQ(error_of("view=main&action=reset&eye=1"),
            "unknown field eye for reset (its fields: none)");
  EXPECT_EQ(error_of("view=main&view=side+view&action=reset"), "field view given twice");
  EXPECT_EQ(error_of("view=main&action=zoom&factor=nan"),
            "factor must be a finite number; got \"nan\"");
  EXPECT_EQ(error_of("view=main&action=zoom&factor=inf"),
            "factor must be a finite number; got \"inf\"");
  EXPECT_EQ(error_of("view=main&action=zoom&factor=2x"),
            "factor must be a finite number; got \"2x\"");
  EXPECT_EQ(error_of("view=main&action=zoom&factor="), "factor must be a finite number; got \"\"");
  EXPECT_EQ(error_of("view=main&action=zoom&factor=0"), "factor = 0 is outside [0.1, 10]");
  EXPECT_EQ(error_of("view=main&action=orbit&d_phi=1e9&d_theta=0"),
            "d_phi = 1e9 is outside [-360, 360]");
  EXPECT_EQ(error_of("view=main&action=pan&dx=11&dy=0"), "dx = 11 is outside [-10, 10]");
  EXPECT_EQ(error_of("view=ma%zzin&action=reset"),
            "malformed form field \"view=ma%zzin\" (expected name=value)");
  EXPECT_EQ(error_of("view=main&action=reset&"), "malformed form field \"\" (expected name=value)");
  EXPECT_EQ(error_of(""), "no view given (the views: main, side view)");
}

TEST(CameraMailbox, MergesEachViewsRequestsUntilTakenAndIsEmptyAfter) {
  CameraMailbox mailbox(2);
  std::vector<CameraChange> out(2);
  EXPECT_FALSE(mailbox.take(out));
  CameraRequest r;
  r.view = 1;
  r.change = {.requests = 1, .d_phi = 10, .d_theta = 5};
  mailbox.post(r);
  mailbox.post(r);
  r.change = {.requests = 1, .zoom = 2};
  mailbox.post(r);
  r.change = {.requests = 1, .pan_x = 0.5};  // on the view zoomed in: a quarter of it before
  mailbox.post(r);
  ASSERT_TRUE(mailbox.take(out));
  EXPECT_FALSE(out[0].any());
  EXPECT_EQ(out[1].requests, 4);
  EXPECT_EQ(out[1].d_phi, 20);
  EXPECT_EQ(out[1].d_theta, 10);
  EXPECT_EQ(out[1].zoom, 2);
  EXPECT_EQ(out[1].pan_x, 0.25);
  EXPECT_FALSE(mailbox.take(out));

  r.change = {.requests = 1, .d_phi = 10};
  mailbox.post(r);
  r.change = {.requests = 1, .reset = 1};  // drops what came before it
  mailbox.post(r);
  ASSERT_TRUE(mailbox.take(out));
  EXPECT_EQ(out[1].requests, 2);
  EXPECT_EQ(out[1].reset, 1);
  EXPECT_EQ(out[1].d_phi, 0);
}

Camera framed() {
  Camera c;
  c.eye = {1, 2, 7};
  c.target = {1, 2, 3};
  c.up = {0, 1, 0};
  c.fov_y_degrees = 60;
  c.width = 200;
  c.height = 100;
  return c;
}

void expect_near(glm::dvec3 a, glm::dvec3 b) {
  EXPECT_NEAR(a.x, b.x, 1e-12);
  EXPECT_NEAR(a.y, b.y, 1e-12);
  EXPECT_NEAR(a.z, b.z, 1e-12);
}

TEST(CameraOffset, OrbitsZoomsAndPansOnTopOfTheFramingUntilReset) {
  const Camera f = framed();
  CameraOffset offset;
  offset.add({.requests = 1, .d_phi = 90}, f);
  Camera c = offset.on(f, f.target);
  expect_near(c.target, f.target);
  expect_near(c.eye, {5, 2, 3});  // a quarter turn about +y: +z goes to +x
  offset.add({.requests = 1, .zoom = 2}, f);
  expect_near(offset.on(f, f.target).eye, {3, 2, 3});
  // Half the view's width to the right, as shown: the view at the target is 2 * 2 tan 30 high
  // after the zoom, twice as wide; looking along -x, right is -z.
  offset.add({.requests = 1, .pan_x = 0.5}, f);
  c = offset.on(f, f.target);
  const double width = 2 * 2 * std::tan(glm::radians(30.0)) * 2;
  expect_near(c.target, {1, 2, 3 - 0.5 * width});
  expect_near(c.eye - c.target, {2, 0, 0});
  // The offset follows the framing: a framing twice as far keeps the same angles and zoom.
  Camera far = f;
  far.eye = {1, 2, 11};
  expect_near(offset.on(far, far.target).eye - offset.on(far, far.target).target, {4, 0, 0});

  offset.add({.requests = 1, .reset = 1}, f);
  c = offset.on(f, f.target);
  EXPECT_EQ(c.eye, f.eye);
  EXPECT_EQ(c.target, f.target);
}

// The live page's turns go about the framing's pivot as Cinema's angles do (a camera framed
// beside a colour bar keeps the fluid's centre where the picture shows it); a zoom then moves the
// eye towards the turned target.
TEST(CameraOffset, TurnsAboutThePivotAsCinemasAnglesDo) {
  const Camera f = framed();
  const glm::dvec3 pivot = f.target + glm::dvec3(0.8, 0, -0.5);
  CameraOffset offset;
  offset.add({.requests = 1, .d_phi = 120, .d_theta = 25}, f);
  const Camera turned = orbited(f, 120, 25, pivot);
  Camera c = offset.on(f, pivot);
  expect_near(c.target, turned.target);
  expect_near(c.eye, turned.eye);
  EXPECT_GT(glm::length(c.target - f.target), 0.5);  // not about the target
  offset.add({.requests = 1, .zoom = 2}, f);
  c = offset.on(f, pivot);
  expect_near(c.target, turned.target);
  expect_near(c.eye, turned.target + 0.5 * (turned.eye - turned.target));
}

TEST(CameraOffset, KeepsTheElevationShortOfThePoleWithoutStoringWhatGoesPast) {
  const Camera f = framed();
  CameraOffset offset;
  offset.add({.requests = 1, .d_theta = 300}, f);
  Camera c = offset.on(f, f.target);
  EXPECT_NEAR(glm::degrees(std::asin((c.eye.y - c.target.y) / 4)), 89, 1e-9);
  offset.add({.requests = 1, .d_theta = -89}, f);  // back at once, not after 211 degrees
  c = offset.on(f, f.target);
  expect_near(c.eye, f.eye);
  offset.add({.requests = 1, .zoom = 0.1}, f);
  offset.add({.requests = 1, .zoom = 0.1}, f);
  offset.add({.requests = 1, .zoom = 0.1}, f);  // 1000 times: held at 100
  EXPECT_NEAR(glm::length(offset.on(f, f.target).eye - f.target), 400, 1e-9);
}

}  // namespace
}  // namespace voxspan
