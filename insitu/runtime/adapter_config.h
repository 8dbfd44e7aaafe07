// insitu/runtime/adapter_config.h - an Adapter (voxspan/adapter.h) with the in-situ runtime
// behind it, from a Config already loaded (voxspan/insitu.h loads the file and calls this; the
// offline tools and benchmarks adjust the Config first).
#pragma once

#include <functional>

#include "insitu/config/config.h"
#include "voxspan/adapter.h"

namespace voxspan {

// The solver's options as the config amends them: render_every 1 (the config's triggers
// decide), the classification section's spacing, full count and validation, and the particle
// attributes the enabled outputs ask for.
AdapterOptions adapter_options_for(const Config& config, AdapterOptions options);

// Checks the options, then makes the pipeline (folders, GL context, passes): throws
// voxspan::Error naming the problem. adapter.pipeline() is an InsituPipeline.
Adapter make_insitu_adapter(const Config& config, AdapterOptions options);

// The same from a loader that reads the config (a file, a text) and may amend it. With ranks
// (options.mpi_comm), what fails on one rank before the pipeline's collectives (a config file
// missing on its node, a typo in its copy, an option its part of the particles gives wrong) is
// thrown on every rank as "rank <r>: <why>": the others would wait in those collectives.
Adapter make_insitu_adapter(const std::function<Config()>& load, AdapterOptions options);

}  // namespace voxspan
