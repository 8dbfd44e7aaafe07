// insitu/runtime/registry.h - every view kind and output kind the runtime knows, in one list
// (registry.cpp): what the config reads, what the pipeline makes, what the summary counts.
#pragma once

#include <string_view>
#include <vector>

#include "insitu/config/config.h"
#include "insitu/outputs/output.h"
#include "insitu/views/view.h"

namespace voxspan {

struct Kinds {
  std::vector<ViewKind> views;      // the first is the default kind
  std::vector<OutputKind> outputs;  // in the order they are handed a step and summed up
  ConfigKinds config;               // their config sides, for the config's reader and writer
};

const Kinds& registered_kinds();
// The kind of that name; throws voxspan::Error when there is none.
const ViewKind& registered_view_kind(std::string_view name);
const OutputKind& registered_output_kind(std::string_view name);

}  // namespace voxspan
