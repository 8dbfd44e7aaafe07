#include "insitu/config/caption.h"

#include <cstdio>
#include <string>

namespace voxspan {
namespace {

// Calls field(name) for each {name} and text(piece) for what lies between; false at an
// unclosed brace.
template <class Text, class Field> bool walk(std::string_view pattern, Text&& text, Field&& field) {
  while (!pattern.empty()) {
    const std::size_t open = pattern.find('{');
    text(pattern.substr(0, open));
    if (open == std::string_view::npos) return true;
    const std::size_t close = pattern.find('}', open);
    if (close == std::string_view::npos) return false;
    field(pattern.substr(open + 1, close - open - 1));
    pattern.remove_prefix(close + 1);
  }
  return true;
}

bool known(std::string_view name) { return name == "step" || name == "time" || name == "view"; }

}  // namespace

std::string caption_problem(std::string_view pattern) {
  if (pattern.size() > kCaptionMaxLength)
    return "is longer than " + std::to_string(kCaptionMaxLength) + " characters";
  std::string problem;
  const bool closed = walk(
      pattern,
      [&](std::string_view piece) {
        for (char c : piece)
          if ((c < ' ' || c > '~') && problem.empty())
            problem = "holds a character the picture's font lacks (printable ASCII only)";
      },
      [&](std::string_view name) {
        if (!known(name) && problem.empty())
          problem = "has an unknown field {" + std::string(name) +
                    "}; known: " + std::string(kCaptionFields);
      });
  if (!closed && problem.empty()) problem = "has a '{' with no '}'";
  return problem;
}

void expand_caption(std::string_view pattern, const CaptionValues& values, std::string& out) {
  out.clear();
  out.reserve(512);
  walk(
      pattern, [&](std::string_view piece) { out += piece; },
      [&](std::string_view name) {
        char number[32];
        if (name == "step") {
          std::snprintf(number, sizeof number, "%lld", static_cast<long long>(values.step));
          out += number;
        } else if (name == "time") {
          std::snprintf(number, sizeof number, "%.4g", values.time);
          out += number;
        } else if (name == "view") {
          out += values.view;
        }
      });
}

}  // namespace voxspan
