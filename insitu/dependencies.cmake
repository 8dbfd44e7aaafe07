# The third-party packages of the insitu/ libraries. Their imported targets are made global, so that
# the tests and tools that link them (whose private dependencies they are) and those
# that read its files back with VTK, OpenVDB or HDF5 see them too.
set(CMAKE_FIND_PACKAGE_TARGETS_GLOBAL ON)
find_package(yaml-cpp REQUIRED)
find_package(PNG REQUIRED)
# libdeflate: the PNG frames' compression (libpng decodes them); Debian ships only its .pc file.
pkg_check_modules(LIBDEFLATE REQUIRED IMPORTED_TARGET GLOBAL libdeflate)
# muparser: the triggers' conditions (insitu/config/condition.h); found by its .pc file.
pkg_check_modules(MUPARSER REQUIRED IMPORTED_TARGET GLOBAL muparser)
# civetweb: the live page's HTTP server (insitu/live/live_server.h). Found by hand: Debian's
# CMake files for it name a server program the -dev package does not ship, and fail.
find_path(CIVETWEB_INCLUDE_DIR civetweb.h REQUIRED)
find_library(CIVETWEB_LIBRARY civetweb REQUIRED)
add_library(civetweb::civetweb UNKNOWN IMPORTED GLOBAL)
set_target_properties(civetweb::civetweb PROPERTIES IMPORTED_LOCATION "${CIVETWEB_LIBRARY}"
                      INTERFACE_INCLUDE_DIRECTORIES "${CIVETWEB_INCLUDE_DIR}")
find_package(VTK 9.1 REQUIRED COMPONENTS CommonCore CommonDataModel IOLegacy IOXML IOXMLParser
             IOParallelXML)
find_package(HDF5 REQUIRED COMPONENTS C)
# Imath first (OpenVDB and OpenEXR both need it), so that its target is made global here too.
find_package(Imath 3 REQUIRED CONFIG)
# Debian ships OpenVDB's find module (it needs Boost.Iostreams) beside its other CMake files.
list(APPEND CMAKE_MODULE_PATH /usr/lib/x86_64-linux-gnu/cmake/OpenVDB /usr/lib/cmake/OpenVDB)
find_package(OpenVDB REQUIRED)
# CONFIG: OpenEXR's own package, not the find module beside OpenVDB's (which leaves out Imath).
find_package(OpenEXR 3 REQUIRED CONFIG)
set(CMAKE_FIND_PACKAGE_TARGETS_GLOBAL OFF)
