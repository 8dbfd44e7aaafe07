// insitu/config/caption.h - a view's `caption`: text drawn on its picture, with the step's
// numbers put in where the pattern names them, so that a frame says when it shows.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace voxspan {

// The names a caption may hold, each in braces.
inline constexpr std::string_view kCaptionFields =
    "{step} (the solver's step), {time} (simulated time, 4 significant digits), {view} (the "
    "view's name)";

inline constexpr std::size_t kCaptionMaxLength = 200;

struct CaptionValues {
  std::int64_t step = 0;
  double time = 0;
  std::string_view view;
};

// What is wrong with `pattern` (an unknown or unclosed field, a character the font lacks),
// empty when nothing is.
std::string caption_problem(std::string_view pattern);
// `pattern` with its fields replaced, into `out` (its storage reused: the caption of a checked
// pattern allocates nothing once `out` has held one).
void expand_caption(std::string_view pattern, const CaptionValues& values, std::string& out);

}  // namespace voxspan
