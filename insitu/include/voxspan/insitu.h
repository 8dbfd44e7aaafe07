// voxspan/insitu.h - an Adapter (voxspan/adapter.h) with the in-situ runtime behind it,
// configured by a YAML file (docs/runtime.md): views, triggers, PNG frames, stats, OpenVDB and
// VTK snapshots, depth images.
//
//   voxspan::AdapterOptions options;
//   options.classify.particle_spacing = dx;
//   voxspan::Adapter adapter = voxspan::adapter_from_config_file("insitu.yaml", options);
//   for (step...) adapter.execute(step, time, particles, grid);   // last: execute_last(...)
//   adapter.finish();                                               // waits for the files
//
// The config's triggers decide the render steps (options.render_every is set to 1); its
// classification section overrides the options it sets; the attributes its outputs ask for
// are added to options.classify.attributes. Everything that can fail before step 1 throws
// voxspan::Error here, naming the problem: an unknown key or bad value (with the file and
// line), an output folder that cannot be written, no usable GL platform, a pass that does not
// compile. Standard library only.
#pragma once

#include <string>

#include "voxspan/adapter.h"

namespace voxspan {

Adapter adapter_from_config_file(const std::string& path, AdapterOptions options);
// The same from the YAML text itself; `source_name` names it in error messages.
Adapter adapter_from_config_text(const std::string& yaml, AdapterOptions options,
                                 const std::string& source_name = "<config>");

}  // namespace voxspan
