# VOXSPAN_USE_LLD: links every target of the build with LLVM's lld where the compiler accepts
# it (tools/scripts/setup.sh installs `lld`), GNU ld otherwise: about a third of GNU ld's
# link time (docs/testing.md has the figures). Only this build's own links: a project that
# links the installed library keeps its own linker.
option(VOXSPAN_USE_LLD "Link with LLVM's lld where the compiler can (faster than GNU ld)" ON)
if(NOT VOXSPAN_USE_LLD)
  return()
endif()
include(CheckLinkerFlag)
check_linker_flag(CXX -fuse-ld=lld VOXSPAN_HAVE_LLD)
if(VOXSPAN_HAVE_LLD)
  add_link_options(-fuse-ld=lld)
endif()
