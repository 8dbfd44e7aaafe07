# VOXSPAN_USE_LLD: links every target of the build with LLVM's lld where the compiler accepts
# it (tools/scripts/setup.sh installs `lld`), GNU ld otherwise. The build's ~80 links took
# 62 s with GNU ld and 16 s with lld in the Release build, 119 s and 46 s in the sanitizer
# build (two cores; docs/testing.md). Only this build's own links: a project that links the
# installed library keeps its own linker.
option(VOXSPAN_USE_LLD "Link with LLVM's lld where the compiler can (faster than GNU ld)" ON)
if(NOT VOXSPAN_USE_LLD)
  return()
endif()
include(CheckLinkerFlag)
check_linker_flag(CXX -fuse-ld=lld VOXSPAN_HAVE_LLD)
if(VOXSPAN_HAVE_LLD)
  add_link_options(-fuse-ld=lld)
endif()
