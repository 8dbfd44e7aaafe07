// insitu/views/view_attributes.h - the particle attributes a view's keys name, found in the
// step's particles, or an error that names the key with its line, the attribute and what the
// solver passes instead (a typo reads as one: `views[0].color_by "velocty": ... (did you mean
// "velocity"? it passes: velocity, p)`).
#pragma once

#include <string_view>

#include "voxspan/particles.h"

namespace voxspan {

// Throws voxspan::Error "<key> \"<name>\": the solver passes no attribute of that name (did you
// mean \"a\"? it passes: a, b)" when `name` is not among the step's attributes; `key` is the key
// path that names it ("run.yaml:12:5: views[2].color_by", ViewSettings::key_path).
const AttributeView& require_attribute(const ParticleView& particles, std::string_view name,
                                       std::string_view key);

}  // namespace voxspan
