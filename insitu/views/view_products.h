// insitu/views/view_products.h - what a view makes on a render step for the outputs: the
// picture always, a depth image or the span image in host memory when an output due on the
// step asks for it.
#pragma once

#include <string_view>

#include "render/float_image.h"
#include "render/span_image.h"

namespace voxspan {

// What an output wants the views to produce on a step where it is due.
struct ViewNeeds {
  bool picture = false;          // the shaded picture (linear RGBA)
  bool first_hit_depth = false;  // distance from the eye to the first span entry per pixel
  bool spans = false;            // the span image the picture was shaded from, in host memory
  bool any() const { return picture || first_hit_depth || spans; }
  ViewNeeds& operator|=(const ViewNeeds& o) {
    picture |= o.picture;
    first_hit_depth |= o.first_hit_depth;
    spans |= o.spans;
    return *this;
  }
};

// One view's products of the step; the images are null when not asked for or when the view
// failed.
struct ViewResult {
  std::string_view name;
  const FloatImage* picture = nullptr;
  const FloatImage* first_hit_depth = nullptr;  // one channel (r) per pixel, 0: no fluid
  const SpanImage* spans = nullptr;
};

// A view's products of one step, kept from step to step (their storage is reused).
struct ViewProducts {
  FloatImage picture;          // linear RGBA, row 0 at the top
  FloatImage first_hit_depth;  // when asked: distance to the first entry in r, 0: no fluid
  // When asked: the span image the picture was shaded from (after the stages: the composite),
  // valid for this step: the CPU renderer's own, or the GL renderer's read back into `spans`.
  const SpanImage* shaded_spans = nullptr;
  SpanImage spans;
};

}  // namespace voxspan
