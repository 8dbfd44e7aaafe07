// insitu/views/volume_view.h - views[i] of kind `volume`: what is inside the fluid, an SPH field
// rendered as a participating medium (direct volume rendering), as iso surfaces, or both
// ([FAW10], [HOK16]; render/volume.h has the method). The field is a particle attribute (a
// vector: its magnitude) interpolated with the slice's SPH sum and keys, or with no `quantity`
// the fluid's volume fraction sum_j (m_j / rho_j) W. Its settings, for the code that reads them
// by type.
//
// Reads: every owned particle the solver passes (positions, the quantity, mass and density, a
// smoothing length per particle when named), the fluid's box (the ground under it). Writes: the
// picture (with the transfer function's colour bar), the depth (the first iso hit, or where the
// opacity reaches 0.5) when an output asks. Costs: render/cpu/volume_caster.h.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "insitu/config/settings.h"
#include "insitu/views/color_map.h"
#include "insitu/views/scenery.h"
#include "render/sph_kernel.h"
#include "render/volume.h"

namespace voxspan {

struct VolumeIsoSettings {
  double value = 0.5;
  Vec3d color{0.85, 0.85, 0.9};  // linear RGB
  double opacity = 1;
  bool operator==(const VolumeIsoSettings&) const = default;
};

// Adaptive sampling under an error tolerance ([HOK16]; render/volume.h's AdaptiveOptions).
struct VolumeAdaptiveSettings {
  double error_tolerance = 0;  // 0: every sample
  double relax = 0;            // 0: the tolerance is a guarantee
  bool operator==(const VolumeAdaptiveSettings&) const = default;
};

enum class VolumeBackground : std::uint8_t { sky, none };
inline constexpr EnumName<VolumeBackground> kVolumeBackgroundNames[] = {
    {"sky", VolumeBackground::sky}, {"none", VolumeBackground::none}};

struct VolumeSettings : CloneAs<VolumeSettings, ViewSettings> {
  std::string quantity;  // empty: the volume fraction
  SphKernel kernel = SphKernel::cubic_spline;
  std::optional<double> smoothing_length;  // h, world units; nullopt = 1.3 spacings
  std::string smoothing_attribute;         // h per particle; empty: smoothing_length for all
  bool shepard = true;                     // not for the volume fraction (it would be 1)
  std::string mass = "mass", density = "density";
  VolumeMode mode = VolumeMode::dvr;
  ColorMap color_map = ColorMap::viridis;
  std::string units;                           // after the colour bar's title; empty: none
  std::optional<std::array<double, 2>> range;  // nullopt = the particles' values' min and max
  ColorScale scale = ColorScale::linear;
  // The transfer function's opacity: (t, alpha) points, t in [0, 1] across the range, alpha the
  // opacity of `opacity_length` particle spacings of fluid at that value; linear between them.
  std::vector<std::array<double, 2>> opacity{{0.0, 0.08}, {1.0, 0.4}};
  double opacity_length = 1;  // particle spacings
  std::vector<VolumeIsoSettings> iso;
  double sampling = 1;  // samples per pixel spacing along each ray
  double termination = 1e-3;
  double weight_floor = 0.05;
  double ambient = 0.3;
  VolumeBackground background = VolumeBackground::sky;
  VolumeAdaptiveSettings adaptive;
  double level_of_detail = 0;  // VolumeOptions::level_of_detail: 0 off
  bool legend = true;
  ScenerySettings scenery;
  bool operator==(const VolumeSettings&) const = default;
};

// The transfer table of a colour map and (t, alpha) opacity points along `axis`.
TransferTable transfer_table(ColorMap map, const std::vector<std::array<double, 2>>& opacity,
                             const ColorAxis& axis);

}  // namespace voxspan
