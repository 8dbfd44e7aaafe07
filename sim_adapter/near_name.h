// sim_adapter/near_name.h - the "did you mean" of the messages that name a config key, an
// attribute or a condition's word that does not exist.
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "voxspan/particles.h"

namespace voxspan {

// The name in `known` nearest to `name` when it is a near miss (under 3 edits), else empty.
std::string near_name(std::string_view name, std::span<const std::string_view> known);

// What the solver passes instead of the attribute `name`: "did you mean \"p\"? it passes: p, v",
// or "it passes none".
std::string attributes_instead(const ParticleView& particles, std::string_view name);

}  // namespace voxspan
