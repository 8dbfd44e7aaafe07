// tools/common/usage.h - how every tool answers --help and a command line it refuses: the usage
// text on stdout (exit status 0) or on stderr (exit status 2).
#pragma once

#include <cstdio>

namespace voxspan::tools {

// Prints `text` to `out` (stdout or stderr) and returns the exit status that goes with it.
inline int print_usage(FILE* out, const char* text) {
  std::fputs(text, out);
  return out == stdout ? 0 : 2;
}

}  // namespace voxspan::tools
