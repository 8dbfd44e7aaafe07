// Built as C++17: see tools/peers/vtk_smp_backend.h.
#include "tools/peers/vtk_smp_backend.h"

#include <vtkSMPTools.h>

namespace voxspan::tools {

std::string vtk_smp_backend() {
  return std::string(vtkSMPTools::GetBackend()) + ", " +
         std::to_string(vtkSMPTools::GetEstimatedNumberOfThreads()) + " threads";
}

}  // namespace voxspan::tools
