// tools/common/dambreak_volume.h - the dam break (tools/common/dambreak_state.h) as the volume
// benchmarks draw it: its particles as Shepard particles of h = 1.3 spacings, and the volume
// view's options over them.
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "insitu/views/volume_view.h"
#include "render/volume.h"
#include "tools/common/dambreak_state.h"

namespace voxspan::tools {

// Each particle's value: its height above the floor (`height`), else 1 (the volume fraction).
inline std::vector<VolumeParticle> dam_break_particles(const DamBreakState& s, bool height) {
  std::vector<VolumeParticle> out;
  const double weight = 1 / (1.3 * 1.3 * 1.3);  // m / (rho h^3), h = 1.3 spacings
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    const double z = glm::dot(glm::dvec3(s.x[i], s.y[i], s.z[i]), s.up) - s.ground;
    out.push_back(
        {s.x[i], s.y[i], s.z[i], float(1.3 * s.spacing), float(weight), height ? float(z) : 1.0f});
  }
  return out;
}

// The view's default transfer function (viridis and its default opacity points, or with
// `opacity` >= 0 that opacity per spacing for every value) over the values' range (the height's,
// else [0, 1], Shepard-normalised for the height); an iso surface at the middle of the range
// outside DVR; the scene's ground and sky.
inline VolumeOptions dam_break_volume_options(const DamBreakState& s,
                                              const std::vector<VolumeParticle>& p, bool height,
                                              double opacity, VolumeMode mode, double sampling) {
  VolumeOptions o;
  o.mode = mode;
  o.shepard = height;
  double lo = 0, hi = 1;
  if (height) {
    lo = 1e300, hi = -1e300;
    for (const VolumeParticle& q : p)
      lo = std::min(lo, double(q.value)), hi = std::max(hi, double(q.value));
  }
  const std::vector<std::array<double, 2>> constant{{0.0, opacity}, {1.0, opacity}};
  o.transfer = transfer_table(ColorMap::viridis, opacity < 0 ? VolumeSettings{}.opacity : constant,
                              {lo, hi});
  o.opacity_length = s.spacing;
  if (mode != VolumeMode::dvr) o.isos = {IsoSurface{0.5 * (lo + hi), {0.8, 0.85, 0.95}, 0.6}};
  o.sampling = sampling;
  o.anchor = s.spacing;
  o.environment.up = s.up;
  o.environment.rest_on_floor(s.ground, s.spacing);
  o.environment.ground_tile = s.length / 3;
  return o;
}

}  // namespace voxspan::tools
