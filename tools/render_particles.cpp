// render_particles: the offline renderer. Particle files written by a solver (VTK .vtp/.vtu,
// CSV, XYZ, PySPH HDF5: insitu/io/particle_data.h) go through the same runtime as an in-situ run,
// with the same YAML config: each file is one step, classified by the solver-side classifier
// (voxspan/classify.h, the adapter sorting the particles into its own grid), every view
// rendered and written as PNG, with the stats line and, where the config enables them, the
// OpenVDB and VTK snapshots on their own triggers (counted in files).
//
//   render_particles [--config FILE] [--output DIR] [--spacing DX] [--radius R]
//                    [--arrays NAME,...] FILE...
//
// --spacing: the particles' rest spacing (else the config's classification.particle_spacing,
// else estimated from the first file: the median nearest-neighbour distance). --radius: the
// sphere radius where a file has none (default: the spacing). --arrays: PySPH particle arrays
// to read (default: all). Exit status 0 when every file was read and rendered, 1 otherwise,
// 2 on bad arguments; each failure is one line on stderr naming the file.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "insitu/runtime/adapter_config.h"
#include "insitu/runtime/config_file.h"
#include "insitu/io/particle_data.h"
#include "insitu/io/spacing_estimate.h"
#include "usage.h"
#include "voxspan/adapter.h"
#include "voxspan/error.h"

namespace {

struct Options {
  std::string config;  // empty: the defaults (one translucent view, PNG and stats)
  std::string output;
  double spacing = 0;
  double radius = 0;
  voxspan::ParticleReadOptions read;
  std::vector<std::filesystem::path> files;
};

constexpr char kUsage[] =
    "usage: render_particles [--config FILE] [--output DIR] [--spacing DX] "
    "[--radius R] [--arrays NAME,...] FILE...\n"
    "  FILE: .vtp .vtu .csv .xyz .hdf5/.h5 (PySPH); each file is one step\n";

bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw voxspan::make_error(a, " needs a value");
      return argv[++i];
    };
    auto positive = [&](const std::string& text) {
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      if (end == text.c_str() || *end != '\0' || !(v > 0))
        throw voxspan::make_error(a, " expects a positive number; got \"", text, "\"");
      return v;
    };
    if (a == "--help" || a == "-h") std::exit(voxspan::tools::print_usage(stdout, kUsage));
    else if (a == "--config") o.config = value();
    else if (a == "--output") o.output = value();
    else if (a == "--spacing") o.spacing = positive(value());
    else if (a == "--radius") o.radius = positive(value());
    else if (a == "--arrays") {
      std::istringstream names(value());
      for (std::string n; std::getline(names, n, ',');)
        if (!n.empty()) o.read.arrays.push_back(n);
    } else if (!a.empty() && a[0] == '-') {
      throw voxspan::make_error("unknown option ", a);
    } else {
      o.files.emplace_back(a);
    }
  }
  if (o.files.empty()) throw voxspan::make_error("no particle file given");
  return true;
}

// Every file is a render step: the config's render, PNG and stats triggers become "every
// step"; the snapshots keep their own triggers, counted in files.
voxspan::Config offline_config(const Options& o) {
  voxspan::Config c =
      o.config.empty() ? voxspan::default_config() : voxspan::load_config_file(o.config);
  if (!o.output.empty()) c.output_folder = o.output;
  const voxspan::TriggerSpec every{1, 0, true, true};
  c.trigger = c.output("png").trigger = c.output("stats").trigger = every;
  return c;
}

// The solver's view of a file's particles: positions as doubles (AoS), radii when the file has
// them, every attribute by name (scalars and 3-vectors of floats, interleaved).
voxspan::ParticleView view_of(const voxspan::ParticleData& d) {
  auto view =
      voxspan::ParticleView::aos(d.positions.empty() ? nullptr : d.positions[0].data(), d.size());
  if (!d.radii.empty()) view.with_radii(d.radii.data());
  for (const voxspan::Attribute& a : d.attributes) {
    if (a.components == 3) view.with_vector(a.name, a.values.data());
    else view.with_scalar(a.name, a.values.data());
  }
  return view;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  try {
    parse(argc, argv, o);
  } catch (const voxspan::Error& e) {
    std::fprintf(stderr, "render_particles: error: %s (--help lists the options)\n", e.what());
    return 2;
  }
  try {
    const voxspan::Config config = offline_config(o);
    // The first file is read before the runtime starts: it may give the spacing.
    voxspan::ParticleData first = voxspan::read_particles(o.files[0], o.read);
    double spacing = o.spacing > 0 ? o.spacing : config.classification.particle_spacing.value_or(0);
    if (!(spacing > 0)) {
      spacing = voxspan::estimate_particle_spacing(first.positions);
      if (!(spacing > 0))
        throw voxspan::make_error(o.files[0].string(),
                                  ": cannot estimate the particle spacing "
                                  "(fewer than two particles); pass --spacing");
      std::printf("particle spacing %.6g (estimated from %s; --spacing sets it)\n", spacing,
                  o.files[0].string().c_str());
    }
    voxspan::AdapterOptions options;
    options.classify.particle_spacing = spacing;
    options.classify.radius = o.radius;
    voxspan::Adapter adapter = voxspan::make_insitu_adapter(config, options);

    int failures = 0;
    for (std::size_t i = 0; i < o.files.size(); ++i) {
      voxspan::ParticleData data;
      try {
        data = i == 0 ? std::move(first) : voxspan::read_particles(o.files[i], o.read);
      } catch (const voxspan::Error& e) {
        std::fprintf(stderr, "render_particles: %s\n", e.what());
        ++failures;
        continue;
      }
      // Steps count the files: triggers need them in order, and the frames sort by them.
      const auto step = static_cast<std::int64_t>(i);
      const double time = data.time.value_or(double(i));
      const voxspan::ParticleView view = view_of(data);
      const voxspan::Status s = i + 1 == o.files.size() ? adapter.execute_last(step, time, view)
                                                        : adapter.execute(step, time, view);
      const voxspan::StepStats& st = adapter.last_stats();
      if (!s.ok()) {
        std::fprintf(stderr, "render_particles: %s: %s\n", o.files[i].string().c_str(),
                     s.message.c_str());
        ++failures;
        continue;
      }
      std::printf("%s: step %lld, %zu particles, %zu boundary, %zu left out (NaN/inf), %.2f s\n",
                  o.files[i].string().c_str(), static_cast<long long>(step), st.counts.particles,
                  st.counts.boundary, st.counts.dropped_nonfinite, st.seconds_total);
    }
    adapter.finish();
    std::printf("%s\noutputs in %s\n", adapter.summary().c_str(), config.output_folder.c_str());
    return failures > 0 ? 1 : 0;
  } catch (const voxspan::Error& e) {
    std::fprintf(stderr, "render_particles: error: %s\n", e.what());
    return 1;
  }
}
