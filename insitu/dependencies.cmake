# The third-party packages of voxspan_insitu, found the same way wherever they are needed
# (imported targets are visible only in the directory that finds them): insitu/, its tests
# and the tools that read or write snapshots include this file.
find_package(yaml-cpp REQUIRED)
find_package(PNG REQUIRED)
find_package(VTK 9.1 REQUIRED COMPONENTS CommonCore CommonDataModel IOXML IOXMLParser)
find_package(HDF5 REQUIRED COMPONENTS C)
# Debian ships OpenVDB's find module (it needs Boost.Iostreams) beside its other CMake files.
list(APPEND CMAKE_MODULE_PATH /usr/lib/x86_64-linux-gnu/cmake/OpenVDB /usr/lib/cmake/OpenVDB)
find_package(OpenVDB REQUIRED)
