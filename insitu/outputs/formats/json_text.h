// insitu/outputs/formats/json_text.h - JSON values appended to a string, for the stats lines
// (stats_record.h) and the live page's state (insitu/live/live_feed.h): a string escaped as
// JSON asks, a number with 10 significant digits (`null` when not finite), an integer exactly.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace voxspan {

void append_string(std::string& out, std::string_view s);
void append_number(std::string& out, double v);
void append_number(std::string& out, std::int64_t v);

}  // namespace voxspan
