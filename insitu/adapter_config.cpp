// Adapter::from_config_file / from_config_text: an adapter with the in-situ runtime
// (insitu/insitu_pipeline.h) behind it, set up from a YAML config.
#include <algorithm>
#include <memory>

#include "insitu/adapter_config.h"

#include "insitu/insitu_pipeline.h"

namespace voxspan {
namespace {

void add_attributes(std::vector<std::string>& to, const OutputCommon& output,
                    const std::vector<std::string>& names) {
  if (!output.enabled) return;
  for (const std::string& n : names)
    if (std::find(to.begin(), to.end(), n) == to.end()) to.push_back(n);
}

}  // namespace

AdapterOptions adapter_options_for(const Config& config, AdapterOptions options) {
  options.render_every = 1;  // the config's triggers decide
  ClassifyOptions& c = options.classify;
  if (config.classification.particle_spacing) c.particle_spacing = *config.classification.particle_spacing;
  if (config.classification.full_count) c.full_count = int(*config.classification.full_count);
  c.validate = c.validate || config.classification.validate_grid;
  add_attributes(c.attributes, config.outputs.vdb, config.outputs.vdb.attributes);
  add_attributes(c.attributes, config.outputs.vtk, config.outputs.vtk.attributes);
  return options;
}

Adapter make_insitu_adapter(const Config& config, AdapterOptions options) {
  Adapter adapter(adapter_options_for(config, std::move(options)));  // checked before GL
  adapter.set_pipeline(
      std::make_shared<InsituPipeline>(config, adapter.options().classify.particle_spacing));
  return adapter;
}

Adapter Adapter::from_config_file(const std::string& path, AdapterOptions options) {
  return make_insitu_adapter(load_config_file(path), std::move(options));
}

Adapter Adapter::from_config_text(const std::string& yaml, AdapterOptions options,
                                  const std::string& source_name) {
  return make_insitu_adapter(load_config_string(yaml, source_name), std::move(options));
}

}  // namespace voxspan
