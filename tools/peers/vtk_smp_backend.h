// tools/peers/vtk_smp_backend.h - VTK's SMP backend as text, from a translation unit of its own:
// VTK 9.1's vtkSMPTools.h does not compile as C++20 (constructors named with template arguments,
// fixed in VTK 9.2), so that unit is built as C++17 (tools/CMakeLists.txt).
#pragma once

#include <string>

namespace voxspan::tools {

// The backend VTK's filters thread with and its thread count, e.g. "TBB, 16 threads".
std::string vtk_smp_backend();

}  // namespace voxspan::tools
