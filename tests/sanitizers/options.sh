# tests/sanitizers/options.sh - the run-time options of the sanitizer suite (docs/testing.md).
# Sourced by tools/test.sh before it runs the tests of the sanitizer build; source it yourself
# to run one of them by hand:  . tests/sanitizers/options.sh && build-sanitize/tests/...
_voxspan_sanitizers=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# Leaks checked at every exit, but under mpiexec (tests/mpi/CMakeLists.txt turns them off
# there: Open MPI's leaks are made in components it dlopens and dlcloses, whose frames only a
# full unwind on every malloc ties back to the libraries lsan.supp names, and that unwinder
# takes a lock of libgcc's that llvmpipe's threads can hold: a GL test then hangs).
export ASAN_OPTIONS=detect_leaks=1:check_initialization_order=1
export LSAN_OPTIONS=suppressions=$_voxspan_sanitizers/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
unset _voxspan_sanitizers
