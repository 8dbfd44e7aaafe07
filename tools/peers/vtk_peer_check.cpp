// vtk_peer_check: shows that the VTK peer (tools/peers/vtk_sph_surface.h) sees what it should.
// A ball of particles on a cubic lattice (centres within R = 20 spacings of the origin) is
// rendered by the peer, and its first hits and thicknesses are compared with the analytic sphere
// of radius R + spacing/2, where the fraction of a flat lattice face falls to 1/2. Prints the
// stages' median times over the runs, the triangle count, the first-hit and thickness errors in
// spacings, and the silhouette pixels the peer misses or adds.
//
//   vtk_peer_check [--h H] [--voxel V] [--quintic] [--iso I] [--size WxH] [--runs N]
//   (H and V in spacings; defaults 1.3 and 1)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <string>
#include <vector>

#include "tools/common/usage.h"
#include "tools/peers/vtk_sph_surface.h"

namespace {

using namespace voxspan;

struct Args {
  double h = 1.3, voxel = 1, iso = 0.5;
  bool quintic = false;
  int width = 800, height = 600, runs = 5;
};

constexpr char kUsage[] =
    "usage: vtk_peer_check [--h H] [--voxel V] [--quintic] [--iso I] [--size WxH] [--runs N]\n";

bool parse(int argc, char** argv, Args& a) {
  for (int i = 1; i < argc; ++i) {
    const char* flag = argv[i];
    if (std::strcmp(flag, "--help") == 0 || std::strcmp(flag, "-h") == 0)
      std::exit(voxspan::tools::print_usage(stdout, kUsage));
    const char* value = i + 1 < argc ? argv[i + 1] : nullptr;
    if (std::strcmp(flag, "--quintic") == 0) {
      a.quintic = true;
      continue;
    }
    if (value == nullptr) return false;
    ++i;
    if (std::strcmp(flag, "--h") == 0) {
      a.h = std::atof(value);
    } else if (std::strcmp(flag, "--voxel") == 0) {
      a.voxel = std::atof(value);
    } else if (std::strcmp(flag, "--iso") == 0) {
      a.iso = std::atof(value);
    } else if (std::strcmp(flag, "--runs") == 0) {
      a.runs = std::atoi(value);
    } else if (std::strcmp(flag, "--size") == 0) {
      if (std::sscanf(value, "%dx%d", &a.width, &a.height) != 2) return false;
    } else {
      return false;
    }
  }
  return a.runs > 0;
}

// The value below which a fraction q of v lies (nearest rank).
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const auto k = static_cast<std::size_t>(std::ceil(q * double(v.size()))) - (q > 0 ? 1 : 0);
  return v[std::min(k, v.size() - 1)];
}

int run(const Args& a) {
  // World units unlike 1, so that a spacing or voxel taken for a world length would show.
  constexpr double dx = 0.02;
  constexpr int n = 20;
  const double radius = n * dx, analytic = radius + dx / 2;
  std::vector<float> x, y, z;
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int k = -n; k <= n; ++k)
        if (i * i + j * j + k * k <= n * n) {
          x.push_back(float(i * dx)), y.push_back(float(j * dx)), z.push_back(float(k * dx));
        }

  // Off the lattice's axes, so that the silhouette crosses the lattice's rows at all angles.
  Camera camera;
  camera.eye = 3.2 * radius * glm::normalize(glm::dvec3(0.45, 0.3, 1));
  camera.target = {0, 0, 0};
  camera.up = {0, 1, 0};
  camera.fov_y_degrees = 40;
  camera.width = a.width;
  camera.height = a.height;

  tools::VtkSphOptions options;
  options.voxel = a.voxel * dx;
  options.smoothing_length = a.h * dx;
  options.quintic = a.quintic;
  options.iso = a.iso;

  // The lattice ball holds about as many particles as its volume, 4/3 pi R^3, has spacing^3
  // cubes: where the fraction of a curved, stepped lattice surface falls to 1/2 may well lie
  // nearer this radius than R + dx/2.
  const double equal_volume = std::cbrt(3 * double(x.size()) / (4 * M_PI)) * dx;
  std::printf(
      "%zu particles in a ball of %d spacings (the sphere of their volume: %.3f dx); "
      "image %dx%d\n",
      x.size(), n, equal_volume / dx, a.width, a.height);
  std::map<std::string, std::vector<double>> times;
  tools::PeerSurface s;
  // One run more, not counted: the first pays for the libraries' thread pools and page faults.
  for (int r = -1; r < a.runs; ++r) {
    s = tools::vtk_sph_surface(x, y, z, dx, camera, options);
    if (r < 0) continue;
    for (const auto& [stage, ms] : s.ms) times[stage].push_back(ms);
  }
  std::printf("%s\n", s.note.c_str());
  std::printf("median of %d runs:", a.runs);
  for (const char* stage : {"interpolate", "contour", "bvh", "cast", "total"})
    std::printf("  %s %.1f ms", stage, quantile(times[stage], 0.5));
  std::printf("\ntriangles: %zu\n", s.elements);

  const ViewFrame view(camera);
  std::vector<double> depth_err, signed_err, radial_err, thick_err;
  long missed = 0, extra = 0, hit = 0;
  for (int py = 0; py < view.height; ++py)
    for (int px = 0; px < view.width; ++px) {
      const glm::dvec3 d = glm::normalize(view.world_ray(px, py));
      const double b = glm::dot(view.eye, d);
      const double disc = b * b - (glm::dot(view.eye, view.eye) - analytic * analytic);
      const std::size_t k = static_cast<std::size_t>(py) * view.width + px;
      const bool peer = std::isfinite(s.first_hit[k]);
      if (disc < 0) {
        extra += peer;
        continue;
      }
      ++hit;
      if (!peer) {
        ++missed;
        continue;
      }
      const double e = (s.first_hit[k] - (-b - std::sqrt(disc))) / dx;
      signed_err.push_back(e);
      radial_err.push_back((glm::length(view.eye + double(s.first_hit[k]) * d) - analytic) / dx);
      depth_err.push_back(std::abs(e));
      thick_err.push_back(std::abs(s.thickness[k] - 2 * std::sqrt(disc)) / dx);
    }
  double mean = 0;
  for (double e : signed_err) mean += e;
  mean /= std::max<std::size_t>(signed_err.size(), 1);
  std::printf(
      "first hit against the sphere of R + dx/2, in spacings: |error| median %.3f  p99 %.3f  "
      "max %.3f  (mean signed %+.3f: > 0 is inside the sphere)\n",
      quantile(depth_err, 0.5), quantile(depth_err, 0.99), quantile(depth_err, 1), mean);
  std::printf(
      "hit points' distance from the centre against R + dx/2, in spacings: median %+.3f  "
      "p1 %+.3f  p99 %+.3f\n",
      quantile(radial_err, 0.5), quantile(radial_err, 0.01), quantile(radial_err, 0.99));
  std::printf("thickness against the chord, in spacings: |error| median %.3f  p99 %.3f  max %.3f\n",
              quantile(thick_err, 0.5), quantile(thick_err, 0.99), quantile(thick_err, 1));
  std::printf("silhouette: %ld pixels on the sphere, %ld missed, %ld extra\n", hit, missed, extra);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (!parse(argc, argv, a)) return voxspan::tools::print_usage(stderr, kUsage);
  try {
    return run(a);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vtk_peer_check: %s\n", e.what());
    return 1;
  }
}
