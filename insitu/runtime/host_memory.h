// insitu/runtime/host_memory.h - the process's resident memory, for the per-step stats.
#pragma once

#include <cstdint>

namespace voxspan {

struct HostMemory {
  std::uint64_t rss_bytes = 0;   // resident now (/proc/self/statm)
  std::uint64_t peak_bytes = 0;  // high-water mark (getrusage ru_maxrss), >= rss_bytes
};

HostMemory host_memory();

}  // namespace voxspan
