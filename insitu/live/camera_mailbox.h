// insitu/live/camera_mailbox.h - the live page's camera requests (`live.interactive`), from the
// server's threads to the solver's next render step.
//
// In: the body of a POST /camera, as an HTML form sends it (application/x-www-form-urlencoded):
//   view=<name>&action=orbit&d_phi=<degrees>&d_theta=<degrees>
//   view=<name>&action=pan&dx=<width of the view>&dy=<height of the view>
//   view=<name>&action=zoom&factor=<factor>
//   view=<name>&action=reset
// every field of the action given once, nothing else, each number finite and in its range.
// Out: per view, the requests since the last take, merged into one CameraChange (the mailbox
// holds one per view, whatever the clients send). A server thread holds the mutex to merge one
// request; the solver's thread holds it to copy the views' changes out, and only when a flag
// says there is one: a step without requests costs one atomic load.
#pragma once

#include <atomic>
#include <cstddef>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "insitu/views/camera_offset.h"

namespace voxspan {

// The range of each request's numbers.
struct CameraRequestLimits {
  static constexpr double kMaxDegrees = 360;  // |d_phi|, |d_theta|
  static constexpr double kMaxPan = 10;       // |dx|, |dy|, in views
  static constexpr double kMinFactor = 0.1, kMaxFactor = 10;
};

struct CameraRequest {
  std::size_t view = 0;  // index in the config's views
  CameraChange change;
};

// Reads a request's body; empty when it is valid, else what is wrong (said to the client).
std::string parse_camera_request(std::string_view body, std::span<const std::string> views,
                                 CameraRequest& out);

class CameraMailbox {
 public:
  explicit CameraMailbox(std::size_t views) : pending_(views) {}

  // Any thread: merged with what the view's slot holds.
  void post(const CameraRequest& request);
  // The solver's thread: every view's merged change since the last take, into `out` (one per
  // view), the slots emptied; false (and `out` untouched) when none was asked.
  bool take(std::span<CameraChange> out);

 private:
  std::mutex mutex_;
  std::vector<CameraChange> pending_;
  std::atomic<bool> any_{false};
};

}  // namespace voxspan
