// tools/common/usage.h - how every tool answers --help and a command line it refuses: the usage
// text on stdout (exit status 0) or on stderr (exit status 2).
#pragma once

#include <cstdio>
#include <cstring>

namespace voxspan::tools {

// Prints `text` to `out` (stdout or stderr) and returns the exit status that goes with it.
inline int print_usage(FILE* out, const char* text) {
  std::fputs(text, out);
  return out == stdout ? 0 : 2;
}

// Whether the command line asks for the usage (--help or -h anywhere): a tool that starts MPI
// answers before MPI_Init, whose allocations it never gives back (LeakSanitizer saw them).
inline bool asks_for_help(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) return true;
  return false;
}

}  // namespace voxspan::tools
