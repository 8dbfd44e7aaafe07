#include "render/volume.h"

#include <cmath>

#include "render/model/volume_host.h"
#include "voxspan/error.h"

namespace voxspan {

static_assert(VX_TRANSFER_ENTRIES == kTransferEntries && VX_MAX_ISO == kMaxIsoSurfaces);
static_assert(VX_VOLUME_DVR == unsigned(VolumeMode::dvr) &&
              VX_VOLUME_ISO == unsigned(VolumeMode::iso) &&
              VX_VOLUME_MIXED == unsigned(VolumeMode::mixed));

void validate(const VolumeOptions& o) {
  const TransferTable& t = o.transfer;
  if (!(t.lo < t.hi) || !std::isfinite(t.lo) || !std::isfinite(t.hi))
    throw make_error("volume transfer range [", t.lo, ", ", t.hi, "] must be finite with lo < hi");
  if (t.log && !(t.lo > 0))
    throw make_error("volume transfer range [", t.lo, ", ", t.hi,
                     "] on a log scale must be above 0");
  for (const glm::vec4& e : t.rgba)
    if (!(e.a >= 0 && e.a <= 1) || !std::isfinite(e.r) || !std::isfinite(e.g) ||
        !std::isfinite(e.b) || e.r < 0 || e.g < 0 || e.b < 0)
      throw make_error(
          "volume transfer table: colours must be finite and >= 0, opacities in "
          "[0, 1]");
  if (!(o.opacity_length > 0) || !std::isfinite(o.opacity_length))
    throw make_error("volume opacity_length = ", o.opacity_length, " must be > 0");
  if (o.isos.size() > std::size_t(kMaxIsoSurfaces))
    throw make_error("volume: ", o.isos.size(), " iso surfaces, at most ", kMaxIsoSurfaces);
  for (const IsoSurface& s : o.isos)
    if (!std::isfinite(s.value) || !(s.opacity >= 0 && s.opacity <= 1))
      throw make_error("volume iso surface ", s.value,
                       ": its value must be finite and its "
                       "opacity in [0, 1]");
  if (o.mode != VolumeMode::dvr && o.isos.empty())
    throw make_error("volume mode ", name_of(kVolumeModeNames, o.mode), " needs iso surfaces");
  if (!(o.sampling > 0) || !std::isfinite(o.sampling))
    throw make_error("volume sampling = ", o.sampling, " must be > 0");
  if (!(o.anchor > 0) || !std::isfinite(o.anchor))
    throw make_error("volume lattice anchor = ", o.anchor, " must be > 0");
  if (!(o.termination >= 0 && o.termination < 1))
    throw make_error("volume termination = ", o.termination, " must be in [0, 1)");
  if (!(o.weight_floor >= 0) || !std::isfinite(o.weight_floor))
    throw make_error("volume weight_floor = ", o.weight_floor, " must be >= 0");
  if (!(o.ambient >= 0 && o.ambient <= 1))
    throw make_error("volume ambient = ", o.ambient, " must be in [0, 1]");
  const AdaptiveOptions& a = o.adaptive;
  if (!(a.error_tolerance >= 0 && a.error_tolerance <= 1))
    throw make_error("volume adaptive error_tolerance = ", a.error_tolerance, " must be in [0, 1]");
  if (!(a.relax >= 0 && a.relax <= 1))
    throw make_error("volume adaptive relax = ", a.relax, " must be in [0, 1]");
  if (!(a.share > 0 && a.share <= 1))
    throw make_error("volume adaptive share = ", a.share, " must be in (0, 1]");
  if (!(o.level_of_detail >= 0) || !std::isfinite(o.level_of_detail))
    throw make_error("volume level_of_detail = ", o.level_of_detail, " must be >= 0");
  ShadeOptions shade;
  shade.environment = o.environment;
  validate(shade);
}

TransferTable::Place TransferTable::place() const {
  const double a = log ? std::log2(lo) : lo, b = log ? std::log2(hi) : hi;
  return {float(a), float((kTransferEntries - 1) / (b - a))};
}

VolumeLattice volume_lattice(double tan_half_y, int height, const VolumeOptions& options) {
  return VolumeLattice(options.anchor, 2 * tan_half_y / height / options.sampling);
}

namespace model {
namespace {

ShadeUniforms environment_uniforms(const VolumeOptions& o) {
  if (!(o.level_of_detail >= 0) || !std::isfinite(o.level_of_detail))
    throw make_error("volume level_of_detail = ", o.level_of_detail, " must be >= 0");
  ShadeOptions shade;
  shade.environment = o.environment;
  return shade_uniforms(shade);
}

}  // namespace

VolumeHost::VolumeHost(const VolumeOptions& o) : ShadeUniforms(environment_uniforms(o)) {
  const TransferTable& t = o.transfer;
  u_tf_log = t.log ? 1u : 0u;
  const TransferTable::Place place = t.place();
  u_tf_lo = place.lo;
  u_tf_scale = place.scale;
  for (std::size_t k = 0; k < transfer_.size(); ++k) transfer_[k] = t.rgba[k];
  u_opacity_length = float(o.opacity_length);
  u_mode = uint(o.mode);
  u_iso_count = uint(o.isos.size());
  for (std::size_t k = 0; k < o.isos.size() && k < std::size_t(VX_MAX_ISO); ++k) {
    u_iso_value[k] = float(o.isos[k].value);
    u_iso_opacity[k] = float(o.isos[k].opacity);
    u_iso_color[k] = vec3(o.isos[k].color);
  }
  u_ambient = float(o.ambient);
  u_light = u_sun_direction;
}

}  // namespace model
}  // namespace voxspan
