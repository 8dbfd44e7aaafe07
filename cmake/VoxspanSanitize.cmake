# VOXSPAN_SANITIZE: every target of the build (C, C++, Fortran) with AddressSanitizer (leaks
# included) and UndefinedBehaviorSanitizer; any report fails the process (no recovery), so a
# test that triggers one fails. tools/test.sh builds it in build-sanitize/ and runs the suite
# with the options and suppressions of tests/sanitizers/ (docs/testing.md).
#
# -O1 -g1: the sanitizers' usual optimisation level with line tables for the reports; at -O2
# -g the OpenVDB-heavy files alone take about 9 minutes each on two cores.
if(NOT VOXSPAN_SANITIZE)
  return()
endif()
set(VOXSPAN_SANITIZER_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=all)
add_compile_options(${VOXSPAN_SANITIZER_FLAGS} -fno-omit-frame-pointer -O1 -g1
  # GCC 12 warns of uninitialized members inside std::regex and std::function when the
  # sanitizers instrument them (false positives, not in our code); -Werror would stop the build.
  $<$<COMPILE_LANGUAGE:CXX>:-Wno-maybe-uninitialized>)
add_link_options(${VOXSPAN_SANITIZER_FLAGS})
