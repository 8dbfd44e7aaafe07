// render/model/volume_host.h - render/model/volume.glsl compiled as C++ (render/model/glsl_cpp.h's
// subset): the uniforms as members, made once from VolumeOptions, and the hits of the ray being
// composited recorded where the caller points. The CPU volume renderer and the reference
// composite every ray through it, one host per thread.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "render/camera.h"
#include "render/model/glsl_cpp.h"
#include "render/model/shade_uniforms.h"
#include "render/volume.h"

namespace voxspan::model {

// An iso crossing, lit once the field's gradient there is known.
struct IsoHit {
  float depth = 0;   // view depth
  float weight = 0;  // transmittance before it times the iso's opacity
  uint iso = 0;
};

// At most this many hits of one ray are lit; later ones (rare: each hides what is behind it
// by its opacity) take the ambient light alone.
inline constexpr int kMaxIsoHits = 8;

struct RayHits {
  std::array<IsoHit, kMaxIsoHits> hit{};
  int count = 0;
  vec3 unlit{0.0f};  // the light of the hits past kMaxIsoHits
  int unlit_count = 0;
};

#define VX_TRANSFER_ENTRIES 256
#define VX_MAX_ISO 4

// The environment's uniforms come from ShadeUniforms (render/model/environment.glsl).
class VolumeHost : public ShadeUniforms {
 public:
  explicit VolumeHost(const VolumeOptions& o);

  // Where vx_record_hit writes: the ray being composited.
  void record_into(RayHits* hits) { hits_ = hits; }

  vec4 vx_transfer_entry(int k) const { return transfer_[std::size_t(k)]; }
  void vx_record_hit(float depth, float weight, uint iso) {
    if (hits_->count < kMaxIsoHits) {
      hits_->hit[std::size_t(hits_->count++)] = {depth, weight, iso};
    } else {
      hits_->unlit += weight * u_ambient * u_iso_color[iso];
      ++hits_->unlit_count;
    }
  }

  uint u_tf_log = 0u;
  float u_tf_lo = 0.0f, u_tf_scale = 1.0f, u_opacity_length = 1.0f;
  uint u_mode = 0u;
  uint u_iso_count = 0u;
  float u_iso_value[VX_MAX_ISO] = {};
  float u_iso_opacity[VX_MAX_ISO] = {};
  vec3 u_iso_color[VX_MAX_ISO] = {};
  float u_ambient = 0.3f;
  vec3 u_light{0.0f, 1.0f, 0.0f};

#include "render/model/environment.glsl"
#include "render/model/volume.glsl"

  // An iso hit moved by one Newton step on Q - iso along its ray (`dir`: the view ray per unit
  // of depth), from the sums at the linear estimate between two samples: the estimate's error,
  // about squared. Kept where the step would leave the samples' interval (`step` of depth) or
  // the field is flat along the ray there.
  void refine_hit(IsoHit& hit, const FieldSums& f, glm::dvec3 dir, bool shepard,
                  double step) const {
    const double q = !shepard ? f.s : f.w > 0 ? f.s / f.w : 0.0;
    const double slope = glm::dot(field_gradient(f, shepard), dir);
    const double dt = (double(u_iso_value[hit.iso]) - q) / slope;
    if (std::isfinite(dt) && std::abs(dt) <= step) hit.depth = float(double(hit.depth) + dt);
  }

  // An iso hit's light on pixel (x, y), from the field's gradient there (view space).
  vec3 hit_light(const IsoHit& hit, glm::dvec3 grad_view, const ViewFrame& f, int x, int y) {
    const double len = glm::length(grad_view);
    const glm::dvec3 n = len > 0 ? -grad_view / len : glm::dvec3(0, 0, -1);
    const glm::dvec3 normal = n.x * f.right + n.y * f.up + n.z * f.forward;
    const glm::dvec3 to_eye = -glm::normalize(f.world_ray(x, y));
    return hit.weight * vx_iso_light(hit.iso, vec3(normal), vec3(to_eye));
  }
  // Pixel (x, y)'s colour: the ray's light and `hits` (its iso hits' light), over the
  // environment (alpha 1) or premultiplied with alpha = 1 - transmittance.
  vec4 pixel_color(const VolumeRay& r, vec3 hits, bool background, const ViewFrame& f, int x,
                   int y) {
    vec3 c = r.color + hits;
    if (!background) return vec4(c, 1.0f - r.transmittance);
    const vec3 dir = vec3(glm::normalize(f.world_ray(x, y)));
    return vec4(c + r.transmittance * environment(vec3(f.eye), dir), 1.0f);
  }

 private:
  std::array<vec4, VX_TRANSFER_ENTRIES> transfer_{};
  RayHits* hits_ = nullptr;
};

}  // namespace voxspan::model
