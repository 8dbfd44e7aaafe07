#include "render/frame_origin.h"

#include "voxspan/classify.h"

namespace voxspan {

FrameOrigin FrameOrigin::near(glm::dvec3 point, double unit) {
  return of(frame_origin_near({point.x, point.y, point.z}, unit));
}

Camera FrameOrigin::camera(const Camera& world) const {
  Camera c = world;
  c.eye -= at;
  c.target -= at;
  return c;
}

Environment FrameOrigin::environment(const Environment& world) const {
  Environment e = world;
  e.origin += at;
  return e;
}

CellStatesView FrameOrigin::cells(const CellStatesView& world) const {
  CellStatesView c = world;
  for (int a = 0; a < 3; ++a) c.origin[std::size_t(a)] -= at[a];
  return c;
}

}  // namespace voxspan
