// voxspan/insitu.h: an adapter with the in-situ runtime (insitu/runtime/pipeline.h) behind it,
// set up from a YAML config.
#include "insitu/runtime/adapter_config.h"

#include <algorithm>
#include <memory>
#include <optional>
#include <string>

#include "insitu/parallel/communicator.h"
#include "insitu/runtime/config_file.h"
#include "insitu/runtime/pipeline.h"
#include "sim_adapter/floating_point_traps.h"
#include "voxspan/insitu.h"

namespace voxspan {

AdapterOptions adapter_options_for(const Config& config, AdapterOptions options) {
  options.render_every = 1;  // the config's triggers decide
  ClassifyOptions& c = options.classify;
  if (config.classification.particle_spacing)
    c.particle_spacing = *config.classification.particle_spacing;
  if (config.classification.full_count) c.full_count = int(*config.classification.full_count);
  c.validate = c.validate || config.classification.validate_grid;
  c.skip_missing_attributes = true;  // the outputs that name one say so (snapshot_copy.h)
  // In an MPI job each particle is its owner's to voxelize and to write: a ghost only counts
  // towards its cell's occupancy (compacted too, it came twice into the snapshots).
  if (options.mpi_comm) c.include_ghosts = false;
  for (const std::string& n : config.output_attributes())
    if (std::find(c.attributes.begin(), c.attributes.end(), n) == c.attributes.end())
      c.attributes.push_back(n);
  return options;
}

Adapter make_insitu_adapter(const std::function<Config()>& load, AdapterOptions options) {
  const FloatingPointTrapsHeld held;  // the GL context and the threads are made here
  const std::optional<int> mpi_comm = options.mpi_comm;
  std::optional<Config> config;
  std::optional<Adapter> adapter;
  std::string failure;
  try {
    config = load();
    adapter.emplace(adapter_options_for(*config, std::move(options)));  // checked before GL
  } catch (const std::exception& e) {
    if (!mpi_comm) throw;
    failure = e.what();
  }
  if (mpi_comm) Communicator(*mpi_comm).agree_or_throw(failure.empty(), failure);
  adapter->set_pipeline(std::make_shared<InsituPipeline>(
      *config, adapter->options().classify.particle_spacing, mpi_comm));
  return std::move(*adapter);
}

Adapter make_insitu_adapter(const Config& config, AdapterOptions options) {
  return make_insitu_adapter([&] { return config; }, std::move(options));
}

Adapter adapter_from_config_file(const std::string& path, AdapterOptions options) {
  return make_insitu_adapter([&] { return load_config_file(path); }, std::move(options));
}

Adapter adapter_from_config_text(const std::string& yaml, AdapterOptions options,
                                 const std::string& source_name) {
  return make_insitu_adapter([&] { return load_config_string(yaml, source_name); },
                             std::move(options));
}

}  // namespace voxspan
