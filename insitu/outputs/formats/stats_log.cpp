#include "insitu/outputs/formats/stats_log.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>

#include "insitu/outputs/writer/atomic_file.h"

namespace voxspan {

StatsLog::StatsLog(std::filesystem::path path, bool append) : path_(std::move(path)) {
  // No O_APPEND: lines go at size_ with pwrite, which the cut-back after a failure keeps right.
  int flags = O_WRONLY | O_CREAT | O_CLOEXEC | (append ? 0 : O_TRUNC);
  fd_ = ::open(path_.c_str(), flags, 0644);
  if (fd_ < 0) throw_write_error("cannot open", path_, errno);
  struct stat st {};
  if (::fstat(fd_, &st) == 0) size_ = static_cast<std::uint64_t>(st.st_size);
}

StatsLog::~StatsLog() {
  if (fd_ >= 0) ::close(fd_);
}

void StatsLog::append(std::string_view line) {
  const char* p = line.data();
  std::size_t left = line.size();
  while (left > 0) {
    ssize_t n = ::pwrite(fd_, p, left, static_cast<off_t>(size_ + (line.size() - left)));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      int error = n < 0 ? errno : ENOSPC;
      // Cut the partial line off: the file stays a list of complete records.
      if (::ftruncate(fd_, static_cast<off_t>(size_)) != 0) { /* nothing more to do */
      }
      throw_write_error("cannot append a stats line to", path_, error);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  size_ += line.size();
  ++lines_;
}

void StatsLog::sync() {
  if (::fdatasync(fd_) != 0) throw_write_error("cannot sync", path_, errno);
}

void StatsLog::remove_if_empty() {
  if (lines_ != 0 || size_ != 0) return;
  std::error_code ec;
  if (std::filesystem::file_size(path_, ec) == 0 && !ec) std::filesystem::remove(path_, ec);
}

}  // namespace voxspan
