// insitu/outputs/writer/atomic_file.h - a file that appears under its final name only when it is
// complete.
//
// Writes go to a hidden temporary file in the same folder (".<name>.tmp.<pid>.<n>"), so that
// the final rename(2) is atomic; commit() flushes, optionally fsyncs, closes and renames.
// A file that is never committed (an error, an exception, a drop) is removed by the
// destructor: no partial file ever keeps a final name. Every failing system call throws a
// WriteError that carries errno (ENOSPC, EFBIG, EIO...) and names the file.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <ostream>
#include <string_view>

#include "voxspan/error.h"

namespace voxspan {

class WriteError : public Error {
 public:
  WriteError(const std::string& what, int error_number) : Error(what), errno_(error_number) {}
  int error_number() const { return errno_; }

 private:
  int errno_;
};

// Throws WriteError("<what> <path>: <strerror(errno)>").
[[noreturn]] void throw_write_error(std::string_view what, const std::filesystem::path& path,
                                    int error_number);

class AtomicFile {
 public:
  // Creates the temporary file beside final_path (the folder must exist).
  explicit AtomicFile(std::filesystem::path final_path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void write(const void* data, std::size_t bytes);
  void write(std::string_view text) { write(text.data(), text.size()); }
  // A seekable binary stream over the same file, for libraries that write to std::ostream
  // (OpenVDB). Its errors surface as WriteError from the next write(), flush() or commit().
  std::ostream& stream();

  // fsync before the rename makes the new content durable before the name points to it.
  void commit(bool sync = true);

  // Throws WriteError if a write through stream() has failed so far.
  void check();

  const std::filesystem::path& final_path() const { return final_path_; }
  const std::filesystem::path& temp_path() const { return temp_path_; }
  std::size_t bytes_written() const;

 private:
  class FdBuffer;
  void discard() noexcept;

  std::filesystem::path final_path_;
  std::filesystem::path temp_path_;
  std::unique_ptr<FdBuffer> buffer_;
  std::unique_ptr<std::ostream> stream_;
  bool committed_ = false;
};

// Writes bytes to path atomically (temp file, fsync when sync, rename).
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes,
                           bool sync = true);

}  // namespace voxspan
