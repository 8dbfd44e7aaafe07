#include "insitu/live/camera_mailbox.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

namespace voxspan {
namespace {

using L = CameraRequestLimits;

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// A form field's name or value as sent (`+` a space, `%XX` a byte); false when malformed.
bool form_decode(std::string_view in, std::string& out) {
  out.clear();
  for (std::size_t i = 0; i < in.size(); ++i) {
    if (in[i] == '+') {
      out += ' ';
    } else if (in[i] != '%') {
      out += in[i];
    } else {
      const int hi = i + 2 < in.size() ? hex_digit(in[i + 1]) : -1;
      const int lo = hi >= 0 ? hex_digit(in[i + 2]) : -1;
      if (lo < 0) return false;
      out += char(hi * 16 + lo);
      i += 2;
    }
  }
  return true;
}

struct Field {
  std::string name, value;
};

// The action's number fields, with their ranges and where each goes.
struct NumberField {
  const char* name;
  double lo, hi;
  double CameraChange::*to;
};

constexpr NumberField kOrbit[] = {
    {"d_phi", -L::kMaxDegrees, L::kMaxDegrees, &CameraChange::d_phi},
    {"d_theta", -L::kMaxDegrees, L::kMaxDegrees, &CameraChange::d_theta}};
constexpr NumberField kPan[] = {{"dx", -L::kMaxPan, L::kMaxPan, &CameraChange::pan_x},
                                {"dy", -L::kMaxPan, L::kMaxPan, &CameraChange::pan_y}};
constexpr NumberField kZoom[] = {{"factor", L::kMinFactor, L::kMaxFactor, &CameraChange::zoom}};

struct Action {
  const char* name;
  std::span<const NumberField> fields;
};

constexpr Action kActions[] = {{"orbit", kOrbit}, {"pan", kPan}, {"zoom", kZoom}, {"reset", {}}};

std::string names_of(std::span<const NumberField> fields) {
  std::string s;
  for (const NumberField& f : fields) s += (s.empty() ? "" : ", ") + std::string(f.name);
  return s.empty() ? "none" : s;
}

std::string number(const NumberField& f, const std::string& text, CameraChange& change) {
  double v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
    return std::string(f.name) + " must be a finite number; got \"" + text + "\"";
  if (v < f.lo || v > f.hi) {
    std::ostringstream s;
    s << f.name << " = " << text << " is outside [" << f.lo << ", " << f.hi << "]";
    return s.str();
  }
  change.*f.to = v;
  return {};
}

std::string split_fields(std::string_view body, std::vector<Field>& fields) {
  if (body.empty()) return {};
  for (;;) {
    const std::size_t end = body.find('&');
    const std::string_view pair = body.substr(0, end);
    const std::size_t eq = pair.find('=');
    Field f;
    if (eq == std::string_view::npos || !form_decode(pair.substr(0, eq), f.name) ||
        !form_decode(pair.substr(eq + 1), f.value))
      return "malformed form field \"" + std::string(pair) + "\" (expected name=value)";
    for (const Field& other : fields)
      if (other.name == f.name) return "field " + f.name + " given twice";
    fields.push_back(std::move(f));
    if (end == std::string_view::npos) return {};
    body.remove_prefix(end + 1);
  }
}

const std::string* value_of(const std::vector<Field>& fields, std::string_view name) {
  for (const Field& f : fields)
    if (f.name == name) return &f.value;
  return nullptr;
}

std::string view_index(const std::string* name, std::span<const std::string> views,
                       std::size_t& out) {
  std::string known;
  for (std::size_t i = 0; i < views.size(); ++i) {
    if (name != nullptr && views[i] == *name) {
      out = i;
      return {};
    }
    known += (i ? ", " : "") + views[i];
  }
  if (name == nullptr) return "no view given (the views: " + known + ")";
  return "no view \"" + *name + "\" (the views: " + known + ")";
}

}  // namespace

std::string parse_camera_request(std::string_view body, std::span<const std::string> views,
                                 CameraRequest& out) {
  std::vector<Field> fields;
  if (std::string e = split_fields(body, fields); !e.empty()) return e;
  CameraRequest request;
  if (std::string e = view_index(value_of(fields, "view"), views, request.view); !e.empty())
    return e;
  const std::string* action_name = value_of(fields, "action");
  const Action* action = nullptr;
  for (const Action& a : kActions)
    if (action_name != nullptr && *action_name == a.name) action = &a;
  if (action == nullptr)
    return "action must be orbit, pan, zoom or reset; got " +
           (action_name ? "\"" + *action_name + "\"" : std::string("none"));
  for (const Field& f : fields) {
    if (f.name == "view" || f.name == "action") continue;
    const auto known = std::find_if(action->fields.begin(), action->fields.end(),
                                    [&](const NumberField& n) { return f.name == n.name; });
    if (known == action->fields.end())
      return "unknown field " + f.name + " for " + action->name +
             " (its fields: " + names_of(action->fields) + ")";
  }
  for (const NumberField& n : action->fields) {
    const std::string* value = value_of(fields, n.name);
    if (value == nullptr)
      return std::string(action->name) + " needs " + names_of(action->fields) + "; " + n.name +
             " is missing";
    if (std::string e = number(n, *value, request.change); !e.empty()) return e;
  }
  request.change.requests = 1;
  request.change.reset = std::string_view(action->name) == "reset" ? 1 : 0;
  out = request;
  return {};
}

void CameraMailbox::post(const CameraRequest& request) {
  std::lock_guard lock(mutex_);
  pending_.at(request.view).merge(request.change);
  any_.store(true, std::memory_order_release);
}

bool CameraMailbox::take(std::span<CameraChange> out) {
  if (!any_.load(std::memory_order_acquire)) return false;
  std::lock_guard lock(mutex_);
  for (std::size_t i = 0; i < pending_.size() && i < out.size(); ++i) {
    out[i] = pending_[i];
    pending_[i] = {};
  }
  any_.store(false, std::memory_order_relaxed);
  return true;
}

}  // namespace voxspan
