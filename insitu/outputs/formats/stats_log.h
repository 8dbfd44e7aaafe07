// insitu/outputs/formats/stats_log.h - the per-step stats file: JSON lines appended to one file.
//
// A line is written with one write(2); if it fails part-way (ENOSPC, EFBIG), the file is cut
// back to its last complete line, so a reader never sees half a record. Failures throw
// WriteError (the background writer reports them). Not thread-safe: use it from one thread
// (the writer's).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string_view>

namespace voxspan {

class StatsLog {
 public:
  // Opens (creates, or truncates when !append) the file.
  explicit StatsLog(std::filesystem::path path, bool append = false);
  ~StatsLog();
  StatsLog(const StatsLog&) = delete;
  StatsLog& operator=(const StatsLog&) = delete;

  void append(std::string_view line);  // one complete line, '\n' included
  void sync();                         // fdatasync: durable up to the last line
  // Removes the file when no line was ever appended to it (and it is empty).
  void remove_if_empty();
  const std::filesystem::path& path() const { return path_; }
  std::uint64_t lines() const { return lines_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;  // bytes of complete lines
  std::uint64_t lines_ = 0;
};

}  // namespace voxspan
