// render_particles: the offline renderer. Particle files written by a solver (VTK .vtp/.vtu/.vtk,
// CSV, XYZ, HDF5 of PySPH or the GADGET family: insitu/io/particle_data.h) go through the same
// runtime as an in-situ run, with the same YAML config: each file is one step, classified by the
// solver-side classifier (voxspan/classify.h, the adapter sorting the particles into its own grid),
// every view rendered and written as PNG, with the stats line and, where the config enables them,
// the OpenVDB and VTK snapshots on their own triggers (counted in files).
//
//   render_particles [--config FILE] [--output DIR] [--spacing DX] [--radius R]
//                    [--arrays NAME,...] [--scenery NAME,...|none]
//                    [--split slabs|uneven|interleaved] FILE...
//   mpiexec -n N render_particles ... FILE...
//
// Under mpiexec every rank reads each file and keeps its part (tools/common/rank_split.h: compact
// slabs by default; --split interleaved gives every rank particles all over the fluid), with
// the particles near its part as ghosts; the ranks' span images are composited exactly and
// rank 0 writes the same pictures one process would.
// --spacing: the particles' rest spacing (else the config's classification.particle_spacing,
// else that of the first file with particles: its masses and densities (PySPH, GADGET), else
// estimated from its
// positions: the median nearest-neighbour distance). --radius: the sphere radius where a file
// has none (default: the spacing). --arrays: PySPH particle arrays or GADGET particle types to
// read, or `all` (default: PySPH's fluid, picked by name or motion and printed:
// insitu/io/read_pysph_hdf5.cpp; GADGET's gas, PartType0); an error on the other formats, which
// have no arrays. --scenery: the PySPH arrays drawn as walls and
// obstacles (docs/runtime.md, "Scenery"; default: every array not read as the fluid), or
// `none`. Exit status 0 when every file was read and
// rendered, 1 otherwise, 2 on bad arguments; each failure is one line on stderr naming the
// file. A file with no particles is rendered (no fluid in its pictures) with a warning.
#include <mpi.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "insitu/io/particle_data.h"
#include "insitu/io/spacing_estimate.h"
#include "insitu/runtime/adapter_config.h"
#include "insitu/runtime/config_file.h"
#include "tools/common/rank_split.h"
#include "tools/common/usage.h"
#include "voxspan/adapter.h"
#include "voxspan/error.h"

namespace {

struct Options {
  std::string config;  // empty: the defaults (one translucent view, PNG and stats)
  std::string output;
  double spacing = 0;
  double radius = 0;
  voxspan::ParticleReadOptions read;
  voxspan::tools::Split split = voxspan::tools::Split::slabs;
  std::vector<std::filesystem::path> files;
};

constexpr char kUsage[] =
    "usage: render_particles [--config FILE] [--output DIR] [--spacing DX] "
    "[--radius R] [--arrays NAME,...] [--scenery NAME,...|none] "
    "[--split slabs|uneven|interleaved] FILE...\n"
    "  FILE: .vtp .vtu .vtk .csv/.txt/.dat .xyz .hdf5/.h5 (PySPH, GADGET/SWIFT); each file is one "
    "step\n"
    "  under mpiexec each rank renders its part (--split) and rank 0 writes the pictures\n";

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
    else if (a == "--split") {
      const std::string v = value();
      const auto split = voxspan::value_of(voxspan::tools::kSplitNames, v);
      if (!split)
        throw voxspan::make_error("--split expects one of ",
                                  voxspan::names_of(voxspan::tools::kSplitNames), "; got \"", v,
                                  "\"");
      o.split = *split;
    } else if (a == "--arrays" || a == "--scenery") {
      std::istringstream names(value());
      for (std::string n; std::getline(names, n, ',');)
        if (!n.empty()) (a == "--arrays" ? o.read.arrays : o.read.scenery).push_back(n);
    } else if (!a.empty() && a[0] == '-') {
      throw voxspan::make_error("unknown option ", a);
    } else {
      o.files.emplace_back(a);
    }
  }
  if (o.files.empty()) throw voxspan::make_error("no particle file given");
  return true;
}

// Every file is a render step (offline_config).
voxspan::Config offline_config(const Options& o) {
  return voxspan::offline_config(
      o.config.empty() ? voxspan::default_config() : voxspan::load_config_file(o.config), o.output);
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

// Whether mpiexec started this process (Open MPI, MPICH/Hydra and PMIx say so in the
// environment): only then is MPI initialized, so that a plain run needs no MPI runtime.
bool under_mpiexec() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(v) != nullptr) return true;
  return false;
}

struct Ranks {
  int rank = 0, size = 1;
  bool mpi = false;
};

// This rank's part of a file's particles: its own, then its ghosts (tools/common/rank_split.h).
voxspan::ParticleData part_of(const voxspan::ParticleData& d, const Options& o, const Ranks& r,
                              double spacing, std::size_t& owned) {
  const voxspan::tools::RankPart part = voxspan::tools::split_particles(
      d.positions, o.split, r.rank, r.size, voxspan::tools::ghost_margin(spacing));
  voxspan::ParticleData p;
  p.time = d.time;
  p.step = d.step;
  if (r.rank == 0) p.scenery = d.scenery;  // the root gives the adapter the walls
  for (std::size_t i : part.indices) p.positions.push_back(d.positions[i]);
  if (!d.radii.empty())
    for (std::size_t i : part.indices) p.radii.push_back(d.radii[i]);
  for (const voxspan::Attribute& a : d.attributes) {
    voxspan::Attribute& b = p.attributes.emplace_back();
    b.name = a.name;
    b.components = a.components;
    for (std::size_t i : part.indices)
      for (int c = 0; c < a.components; ++c)
        b.values.push_back(a.values[i * std::size_t(a.components) + std::size_t(c)]);
  }
  owned = part.owned;
  return p;
}

// The particles' rest spacing: --spacing, else the config's, else from the first file that
// holds particles (its masses and densities, else estimated from the positions). The files
// before it hold none, and where no file holds any nothing is drawn: any spacing will do.
double spacing_of(const Options& o, const voxspan::Config& config,
                  const voxspan::ParticleData& first, bool talk) {
  if (o.spacing > 0) return o.spacing;
  if (config.classification.particle_spacing.value_or(0) > 0)
    return *config.classification.particle_spacing;
  const voxspan::ParticleData* data = &first;
  std::size_t file = 0;
  voxspan::ParticleData later;
  while (data->size() == 0 && file + 1 < o.files.size()) {
    try {
      later = voxspan::read_particles(o.files[++file], o.read);
      data = &later;
    } catch (const voxspan::Error&) {
      // said when the file's step comes
    }
  }
  if (data->size() == 0) return 1;
  const std::string name = o.files[file].string();
  if (data->spacing) {
    if (talk)
      std::printf(
          "particle spacing %.6g (from the particles' mass and density in %s; --spacing sets "
          "it)\n",
          *data->spacing, name.c_str());
    return *data->spacing;
  }
  const double spacing = voxspan::estimate_particle_spacing(data->positions);
  if (!(spacing > 0))
    throw voxspan::make_error(name,
                              ": cannot estimate the particle spacing (fewer than two particles "
                              "at finite, distinct positions); pass --spacing");
  if (talk)
    std::printf("particle spacing %.6g (estimated from %s; --spacing sets it)\n", spacing,
                name.c_str());
  return spacing;
}

// A file's radii far from the spacing are most often another column read as radii (an .xyz
// file's fourth column is the radius by convention; a density or a velocity there gives giant or
// missing spheres): said once, with the way out.
void warn_of_odd_radii(const voxspan::ParticleData& d, const std::filesystem::path& file,
                       double spacing) {
  if (d.radii.empty()) return;
  std::vector<float> r = d.radii;
  const auto middle = r.begin() + std::ptrdiff_t(r.size() / 2);
  std::nth_element(r.begin(), middle, r.end());
  const double median = *middle;
  if (median >= 0.1 * spacing && median <= 10 * spacing) return;
  std::fprintf(stderr,
               "render_particles: warning: %s: the particles' radii (median %.3g) are far from "
               "their spacing %.3g: is another column read as radii (an .xyz file's fourth "
               "column is its radius)?\n",
               file.string().c_str(), median, spacing);
}

// A series whose names end in their steps, given in the shell's order ("_10" before "_2" when
// the numbers are not padded): rendered in the order of the steps, and said.
void order_by_steps_in_names(std::vector<std::filesystem::path>& files, bool talk) {
  std::vector<std::int64_t> steps;
  for (const std::filesystem::path& f : files) {
    const std::optional<std::int64_t> s = voxspan::step_in_name(f);
    if (!s) return;
    steps.push_back(*s);
  }
  if (std::is_sorted(steps.begin(), steps.end())) return;
  std::vector<std::size_t> order(files.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return steps[a] < steps[b]; });
  std::vector<std::filesystem::path> sorted;
  for (std::size_t i : order) sorted.push_back(files[i]);
  const auto late = std::is_sorted_until(steps.begin(), steps.end()) - steps.begin();
  if (talk)
    std::printf(
        "render_particles: the files are rendered in the order of the numbers that end "
        "their names (%s was given before %s)\n",
        files[std::size_t(late - 1)].filename().string().c_str(),
        files[std::size_t(late)].filename().string().c_str());
  files = std::move(sorted);
}

int render(Options o, const Ranks& ranks) {
  const bool talk = ranks.rank == 0;
  order_by_steps_in_names(o.files, talk);
  try {
    const voxspan::Config config = offline_config(o);
    // The first file is read before the runtime starts: it may give the spacing.
    voxspan::ParticleData first = voxspan::read_particles(o.files[0], o.read);
    if (talk && !first.chosen.empty()) std::printf("reading %s\n", first.chosen.c_str());
    const double spacing = spacing_of(o, config, first, talk);
    if (talk) warn_of_odd_radii(first, o.files[0], spacing);
    if (talk && first.radii.empty() && first.size() > 0)
      std::printf("sphere radius %.6g (%s; --radius sets it)\n", o.radius > 0 ? o.radius : spacing,
                  o.radius > 0 ? "--radius" : "the spacing, as the file gives no radii");
    voxspan::AdapterOptions options;
    options.classify.particle_spacing = spacing;
    options.classify.radius = o.radius;
    if (ranks.mpi) options.mpi_comm = int(MPI_Comm_c2f(MPI_COMM_WORLD));
    voxspan::Adapter adapter = voxspan::make_insitu_adapter(config, options);

    int failures = 0;
    std::int64_t previous_step = -1;
    bool told_time = false;                      // that the files give no time: once
    std::vector<std::array<double, 3>> scenery;  // the last given
    for (std::size_t i = 0; i < o.files.size(); ++i) {
      voxspan::ParticleData data;
      try {
        data = i == 0 ? std::move(first) : voxspan::read_particles(o.files[i], o.read);
      } catch (const voxspan::Error& e) {
        if (talk) std::fprintf(stderr, "render_particles: %s\n", e.what());  // once, not per rank
        ++failures;
        continue;  // every rank reads the same files: they all skip it
      }
      // Not an error (an inlet's fluid before it flows in), but a picture without fluid that
      // looks like a bug unless said.
      if (data.size() == 0 && talk)
        std::fprintf(stderr,
                     "render_particles: warning: %s holds no particles; its pictures show none\n",
                     o.files[i].string().c_str());
      std::size_t owned = data.size();
      if (ranks.size > 1) data = part_of(data, o, ranks, spacing, owned);
      // The file's own step where it gives one (PySPH's iteration), else the next: triggers
      // need them in order, and the frames sort by them.
      const std::int64_t step = data.step_after(previous_step);
      if (talk && data.step && *data.step != step)
        std::fprintf(stderr,
                     "render_particles: warning: %s is step %lld, not after the file before it "
                     "(step %lld): rendered as step %lld; give the files in the order of their "
                     "steps\n",
                     o.files[i].string().c_str(), static_cast<long long>(*data.step),
                     static_cast<long long>(previous_step), static_cast<long long>(step));
      previous_step = step;
      const double time = data.time.value_or(double(i));
      if (talk && !data.time && !told_time) {
        told_time = true;  // a caption's "t = 2" would read as a simulated time
        std::printf(
            "render_particles: %s gives no time: the time (a caption's {time}) is the "
            "file's index, 0, 1, 2...\n",
            o.files[i].string().c_str());
      }
      // The walls, given again only when they moved (each time the views draw them anew); by
      // the root alone, as every rank read them all.
      if (ranks.rank == 0 && data.scenery != scenery) {
        scenery = std::move(data.scenery);
        adapter.set_scenery(voxspan::ParticleView::aos(
            scenery.empty() ? nullptr : scenery[0].data(), scenery.size()));
      }
      const voxspan::ParticleView view = view_of(data).with_owned(owned);
      const voxspan::Status s = i + 1 == o.files.size() ? adapter.execute_last(step, time, view)
                                                        : adapter.execute(step, time, view);
      const voxspan::StepStats& st = adapter.last_stats();
      if (!s.ok()) {
        // The library has logged the step's failures (every view's and output's) just above.
        if (talk)
          std::fprintf(stderr, "render_particles: %s: not rendered (the error above)\n",
                       o.files[i].string().c_str());
        ++failures;
        continue;
      }
      if (talk)
        std::printf(
            "%s: step %lld, %zu particles, %zu in the surface shell, %zu left out (NaN/inf or "
            "negative radius), %.2f "
            "s%s\n",
            o.files[i].string().c_str(), static_cast<long long>(step), st.counts.particles,
            st.counts.boundary, st.counts.dropped_nonfinite, st.seconds_total,
            ranks.size > 1 ? " (rank 0's part)" : "");
    }
    adapter.finish();
    if (talk)
      std::printf("%s\noutputs in %s\n", adapter.summary().c_str(), config.output_folder.c_str());
    return failures > 0 ? 1 : 0;
  } catch (const voxspan::Error& e) {
    if (talk) std::fprintf(stderr, "render_particles: error: %s\n", e.what());
    return 1;
  }
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
  Ranks ranks;
  if (under_mpiexec()) {
    MPI_Init(&argc, &argv);
    ranks.mpi = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &ranks.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks.size);
  }
  const int status = render(o, ranks);
  if (ranks.mpi) MPI_Finalize();
  return status;
}
