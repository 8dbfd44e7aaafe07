// tools/peers/peer_surface.h - what every method of the peers benchmark
// (tools/bench/bench_peers.cpp) hands back for one frame, in one form, so that the error against
// the exact reference is measured the same way for all: per pixel of the camera (row 0 at the top,
// the ray through the pixel's centre, render/camera.h) the distance along the unit ray from the eye
// to the first surface and the length of the ray inside the fluid, and the time of each stage.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace voxspan::tools {

struct PeerSurface {
  std::vector<float> first_hit;  // +infinity: the ray meets no surface
  std::vector<float> thickness;  // 0: none
  // Per pixel the stretches of the ray inside the fluid, as distances along it: entry, exit,
  // entry, exit, ... in order (what a compositor or our shading needs of a surface).
  std::vector<std::vector<float>> spans;
  std::map<std::string, double> ms;  // per stage, and "total"
  std::size_t elements = 0;          // what the method built: voxels, triangles, spans
  std::string note;                  // what the reader should know (dropped particles, ...)
};

}  // namespace voxspan::tools
