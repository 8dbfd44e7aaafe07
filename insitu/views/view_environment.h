// insitu/views/view_environment.h - what surrounds the fluid in a 3D view's picture when the
// config leaves it to us: the sun a little off `up` whatever axis is up, and the floor the fluid
// rests on, under the box of the step's boundary spheres; the box's smallest side as the depth
// scale of automatic absorption.
#pragma once

#include <glm/glm.hpp>

#include "insitu/views/view_framing.h"

namespace voxspan {

// Towards the sun: mostly up, a little to two sides.
glm::dvec3 sun_direction(glm::dvec3 up);

// The floor the fluid rests on, seen from the spheres' box: half a spacing above its lowest
// point along `up`, where a solver's wall lies with the default radius (one spacing); for any
// radius the union's bottom lies under it.
double floor_height(const Bounds& sphere_box, glm::dvec3 up, double spacing);

// The box's smallest side.
double smallest_side(const Bounds& box);

}  // namespace voxspan
