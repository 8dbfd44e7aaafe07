// insitu/views/view_products.h - what a view makes on a render step for the outputs: the
// picture always, a depth image or the span image in host memory when an output due on the
// step asks for it.
#pragma once

#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "render/float_image.h"
#include "render/frame_stats.h"
#include "render/span_image.h"
#include "render/srgb8_image.h"
#include "render/volume.h"
#include "insitu/views/shared_picture.h"

namespace voxspan {

// What an output wants the views to produce on a step where it is due.
struct ViewNeeds {
  bool picture = false;          // the shaded picture (as 8-bit sRGB unless asked as floats)
  bool linear_picture = false;   // its linear floats (an EXR file's, a caller's)
  bool first_hit_depth = false;  // distance from the eye to the first span entry per pixel
  bool spans = false;            // the span image the picture was shaded from, in host memory
  bool field = false;            // a 2D view's raw values (a slice's), with their world mapping
  bool deep = false;             // a volume view's deep image (render/volume.h)
  // Whether 8-bit sRGB is all the step's readers take of the picture (PNG files, the live page):
  // then a renderer that converts on its device reads back a quarter of the bytes.
  bool srgb8_picture() const { return picture && !linear_picture; }
  bool any() const { return picture || first_hit_depth || spans || field || deep; }
  ViewNeeds& operator|=(const ViewNeeds& o) {
    picture |= o.picture;
    linear_picture |= o.linear_picture;
    first_hit_depth |= o.first_hit_depth;
    spans |= o.spans;
    field |= o.field;
    deep |= o.deep;
    return *this;
  }
};

// The values a slice view drew, before the colour map, and where each pixel lies in the world:
// pixel (i, j) of a W x H image (row 0 at the top) is at
//   origin + ((i + 0.5) / W - 0.5) * width * u + (0.5 - (j + 0.5) / H) * height * v.
struct FieldImage {
  FloatImage values;  // r: the quantity (0 where no particle reaches), g: the kernel weight
                      // sum_j (m_j / rho_j) W (0 there); b, a: 0
  std::string quantity;
  glm::dvec3 origin{0}, u{1, 0, 0}, v{0, 1, 0};
  double width = 0, height = 0;  // world units
};

// One view's products of the step; the images are null when not asked for or when the view
// failed.
struct ViewResult {
  std::string_view name;
  // The picture; its pixels may still be on their way (shared_picture's get() waits for them),
  // so an output reads them through shared_picture, the caller through
  // InsituPipeline::latest_views().
  const FloatImage* picture = nullptr;
  // The same picture for an output that keeps it past the step (its copy of the reference
  // keeps the pixels as they are: no copy of them; insitu/views/shared_picture.h).
  const SharedPicture* shared_picture = nullptr;
  const FloatImage* first_hit_depth = nullptr;  // one channel (r) per pixel, 0: no fluid
  const SpanImage* spans = nullptr;
  const FieldImage* field = nullptr;
  const DeepImage* deep = nullptr;
  const FrameStats* stats = nullptr;  // the view's passes and counts on this process
};

// An image an output keeps past the step: a view's picture by reference when it comes with one
// (`shared` refers to the same pixels), any other image as a copy whose storage stays for the
// next (no allocation once it has held `reserve_floats`, the largest it will hold).
struct KeptImage {
  SharedPicture shared;
  FloatImage copy;
  ImageRGBA8 copy_srgb8;  // srgb8() of a copy

  void keep(const FloatImage& image, const SharedPicture* same, std::size_t reserve_floats = 0) {
    if (same != nullptr && same->refers_to(image)) {
      shared = *same;
      return;
    }
    shared.reset();
    copy.rgba.reserve(reserve_floats);
    copy.width = image.width;
    copy.height = image.height;
    copy.rgba.assign(image.rgba.begin(), image.rgba.end());
  }
  const FloatImage& image() const { return shared ? *shared : copy; }
  // The image as 8-bit sRGB (a PNG frame's): a referenced picture's own, a copy's encoded here.
  const ImageRGBA8& srgb8() {
    if (shared) return *shared.srgb8();
    linear_to_srgb8(copy, copy_srgb8);
    return copy_srgb8;
  }
  // Gives a referenced picture back to its view (once written).
  void release() { shared.reset(); }
};

// A view's products of one step, kept from step to step (their storage is reused).
struct ViewProducts {
  FloatImage picture;  // linear RGBA, row 0 at the top
  // Where the step's picture came as 8-bit sRGB (ViewNeeds::srgb8_picture, from a renderer that
  // converts on its device), it is here instead and `picture` is not this step's.
  ImageRGBA8 srgb8_picture;
  bool picture_is_srgb8 = false;
  // Where the picture's pixels are still on their way from the GPU (sized, not yet filled),
  // their read: the pipeline hands it to the picture's pool (PictureFinish). Null otherwise.
  PendingPicture* pending_picture = nullptr;
  FloatImage first_hit_depth;  // when asked: distance to the first entry in r, 0: no fluid
  // When asked: the span image the picture was shaded from (after the stages: the composite),
  // valid for this step: the CPU renderer's own, or the GL renderer's read back into `spans`.
  const SpanImage* shaded_spans = nullptr;
  SpanImage spans;
  // When asked, from a view that has one: its raw values; null otherwise.
  const FieldImage* shaded_field = nullptr;
  FieldImage field;
  // When asked, from a volume view: its deep image; null otherwise.
  const DeepImage* shaded_deep = nullptr;
};

}  // namespace voxspan
