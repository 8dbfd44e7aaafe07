// insitu/outputs/kinds/vtk_output.h - outputs.vtk: the boundary particles as .vtp, the cell states
// as .vti, each with its .pvd series, for ParaView (insitu/outputs/formats/vtk_files.h). Its
// settings, for the code that reads them by type (the tests).
#pragma once

#include <string>
#include <vector>

#include "insitu/config/settings.h"

namespace voxspan {

struct VtkSettings : CloneAs<VtkSettings, OutputSettings> {
  VtkSettings() : CloneAs(false, "vtk", TriggerSpec{100, 0, false, true}) {}
  bool particles = true;  // .vtp of the boundary particles
  bool cells = true;      // .vti of the cell states
  std::vector<std::string> attributes;
  std::span<const std::string> needed_attributes() const override { return attributes; }
  bool operator==(const VtkSettings&) const = default;
};

}  // namespace voxspan
