// insitu/config/settings.h - what every output and every view kind has in the config, and how
// a kind plugs its own keys in.
//
// An output kind (insitu/outputs/) derives its settings from OutputSettings (enabled, folder,
// trigger) and a view kind (insitu/views/) from ViewSettings (name, size, camera); each
// describes itself with a ConfigKind: its name, its default settings and its schema section
// (insitu/config/schema.h). The config holds the settings by value through Cloned<>, so the
// loader, to_yaml, the schedule and the summary treat every kind alike and a new kind is one
// new file plus its line in insitu/runtime/registry.cpp.
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "insitu/config/caption.h"
#include "insitu/config/schema.h"
#include "insitu/config/trigger.h"

namespace voxspan {

using Vec3d = std::array<double, 3>;

// A deep-copying owner of a value derived from Base (Base has clone() and equals()).
template <class Base> class Cloned {
 public:
  template <class D> explicit Cloned(D value) : p_(std::make_unique<D>(std::move(value))) {}
  Cloned(const Cloned& o) : p_(o.p_->clone()) {}
  Cloned& operator=(const Cloned& o) {
    if (this != &o) p_ = o.p_->clone();
    return *this;
  }
  Cloned(Cloned&&) noexcept = default;
  Cloned& operator=(Cloned&&) noexcept = default;

  Base& operator*() { return *p_; }
  const Base& operator*() const { return *p_; }
  Base* operator->() { return p_.get(); }
  const Base* operator->() const { return p_.get(); }
  bool operator==(const Cloned& o) const { return p_->equals(*o.p_); }

 private:
  std::unique_ptr<Base> p_;
};

// clone() and equals() of a settings type D derived from Base, from D's copy and ==.
template <class D, class Base> struct CloneAs : Base {
  using Base::Base;
  std::unique_ptr<Base> clone() const override {
    return std::make_unique<D>(static_cast<const D&>(*this));
  }
  bool equals(const Base& other) const override {
    const D* o = dynamic_cast<const D*>(&other);
    return o != nullptr && *o == static_cast<const D&>(*this);
  }
};

// ---- outputs: outputs.<kind>

struct OutputSettings {
  bool enabled = false;
  std::string folder = ".";  // relative to Config::output_folder unless absolute
  TriggerSpec trigger;
  // Not a key: the kind's trigger defaults to the render trigger (PNG frames, stats lines).
  bool follows_render_trigger = false;
  // Where the config gave the output ("run.yaml:7:3: outputs.vdb"), for what is found wrong
  // only when the solver's data arrives (an attribute it does not pass).
  ConfigSource source;

  OutputSettings(bool enabled_by_default, std::string default_folder, TriggerSpec default_trigger)
      : enabled(enabled_by_default), folder(std::move(default_folder)), trigger(default_trigger) {}
  virtual ~OutputSettings() = default;
  virtual std::unique_ptr<OutputSettings> clone() const = 0;
  virtual bool equals(const OutputSettings& other) const = 0;
  // The particle attributes the output needs compacted with the boundary particles.
  virtual std::span<const std::string> needed_attributes() const { return {}; }
  // The views it names under its key `views` (checked against the config's views).
  virtual std::span<const std::string> named_views() const { return {}; }
  bool operator==(const OutputSettings&) const = default;

 protected:
  OutputSettings(const OutputSettings&) = default;
  OutputSettings& operator=(const OutputSettings&) = default;
};

const schema::Section<TriggerSpec>& trigger_section();

// The keys every output has, then `own`, for a section of S (S derives from OutputSettings).
// `trigger_default`: the reference's default for the trigger; empty: S{}'s.
template <class S>
std::vector<schema::Key<S>> output_keys(std::vector<schema::Key<S>> own = {},
                                        std::string trigger_default = {}) {
  std::vector<schema::Key<S>> keys = {
      schema::flag<S>("enabled", &OutputSettings::enabled, "write this output"),
      schema::text<S>("folder", &OutputSettings::folder,
                      "its folder, relative to `output_folder` unless absolute"),
      schema::map<S, TriggerSpec>("trigger", &OutputSettings::trigger, trigger_section(),
                                  "when it writes", true)};
  keys.back().shown_default = std::move(trigger_default);
  return schema::joined(std::move(keys), std::move(own));
}

// ---- views: views[i]

// Automatic framing follows the fluid's bounds: grown over every render step so far (the
// camera only ever backs away: a steady video), refitted every step, or fixed at the first.
enum class Framing { grow, each_step, first };
inline constexpr EnumName<Framing> kFramingNames[] = {
    {"grow", Framing::grow}, {"each_step", Framing::each_step}, {"first", Framing::first}};

struct CameraConfig {
  // Automatic framing: look along `direction` at the box of the particles (the boundary
  // particles' spheres, which enclose the fluid), from the distance at which the box, grown
  // by `margin` about its centre, just fits the view; `framing` says which box.
  // Manual: from `eye` at `target`.
  bool automatic = true;
  Vec3d eye{0, 0, 0};
  Vec3d target{0, 0, 0};
  Vec3d up{0, 0, 1};
  double fov_degrees = 40;  // vertical
  Vec3d direction{-1, 2, -0.8};
  double margin = 1.05;
  Framing framing = Framing::grow;
  // Automatic framing of this box instead of the fluid's: [[x0, x1], [y0, y1], [z0, z1]].
  std::vector<std::array<double, 2>> bounds;
  bool operator==(const CameraConfig&) const = default;
};
const schema::Section<CameraConfig>& camera_section();

struct ViewSettings {
  std::string name;  // default "view<i>"; names the PNG files and the stats section
  int width = 960;
  int height = 540;
  CameraConfig camera;
  std::string caption = "step {step}, t = {time}";  // drawn at the top left (config/caption.h)
  // Where the config gave the view, so that a key found wrong only when the solver's data
  // arrives (an attribute it does not pass) is named with its line.
  ConfigSource source;

  ViewSettings() = default;
  virtual ~ViewSettings() = default;
  virtual std::unique_ptr<ViewSettings> clone() const = 0;
  virtual bool equals(const ViewSettings& other) const = 0;
  bool operator==(const ViewSettings&) const = default;
  // The key path of one of the view's keys for messages: "run.yaml:12:5: views[2].quantity",
  // or the key alone for a default view.
  std::string key_path(std::string_view key) const { return source.key_path(key, key); }

 protected:
  ViewSettings(const ViewSettings&) = default;
  ViewSettings& operator=(const ViewSettings&) = default;
};

// The keys every view has, then `own`, for a section of S (S derives from ViewSettings);
// `kind` is the view kind's name.
template <class S>
std::vector<schema::Key<S>> view_keys(std::string_view kind, std::vector<schema::Key<S>> own) {
  schema::Key<S> kind_key;
  kind_key.name = "kind";
  kind_key.type = "a view kind";
  kind_key.help = "what the view shows (the kinds below)";
  kind_key.shown_default = "`surface`";
  kind_key.read = [](yaml::MapReader&, S&) {};  // read first, to choose the section
  kind_key.emit = [kind = std::string(kind)](YAML::Emitter& e, const S&) { e << kind; };
  std::vector<schema::Key<S>> keys = {
      std::move(kind_key),
      schema::text<S>("name", &ViewSettings::name,
                      "names the PNG files and the stats section; letters, digits, `_` "
                      "`-` `.`; unique")
          .default_shown_as("`view<i>` (`main` for the default view)"),
      schema::integer<S, int>("width", &ViewSettings::width, 1, 16384, "pixels"),
      schema::integer<S, int>("height", &ViewSettings::height, 1, 16384, "pixels"),
      schema::map<S, CameraConfig>("camera", &ViewSettings::camera, camera_section(),
                                   "automatic framing unless `eye` and `target` are given"),
      schema::text<S>("caption", &ViewSettings::caption,
                      "text drawn at the picture's top left, in which " +
                          std::string(kCaptionFields) + " are filled in each step; empty: none")};
  return schema::joined(std::move(keys), std::move(own));
}

// ---- how a kind describes itself to the config

template <class Settings> struct ConfigKind {
  std::string_view name;
  std::function<Cloned<Settings>()> defaults;
  // Reads the kind's section into `settings` (made by defaults()).
  std::function<void(yaml::Checker&, const YAML::Node&, const std::string& path, Settings&)> read;
  std::function<void(YAML::Emitter&, const Settings&)> emit;  // the section as a YAML map
  std::function<std::string()> reference;                     // its table for docs/runtime.md
  std::function<std::span<const std::string_view>()> keys;
};

// The ConfigKind of settings type S (default-constructed for its defaults) read and written
// by `section`.
template <class Settings, class S>
ConfigKind<Settings> config_kind(std::string_view name, const schema::Section<S>& section) {
  ConfigKind<Settings> k;
  k.name = name;
  k.defaults = [] { return Cloned<Settings>(S{}); };
  k.read = [&section](yaml::Checker& checker, const YAML::Node& node, const std::string& path,
                      Settings& out) { section.read(checker, node, path, dynamic_cast<S&>(out)); };
  k.emit = [&section](YAML::Emitter& e, const Settings& s) {
    section.emit(e, dynamic_cast<const S&>(s));
  };
  k.reference = [&section] { return section.reference(); };
  k.keys = [&section] { return section.names(); };
  return k;
}

using OutputConfigKind = ConfigKind<OutputSettings>;
using ViewConfigKind = ConfigKind<ViewSettings>;

}  // namespace voxspan
