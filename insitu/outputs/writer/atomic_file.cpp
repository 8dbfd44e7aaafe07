#include "insitu/outputs/writer/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <streambuf>
#include <vector>

namespace voxspan {

void throw_write_error(std::string_view what, const std::filesystem::path& path, int error_number) {
  throw WriteError(std::string(what) + " " + path.string() + ": " + std::strerror(error_number),
                   error_number);
}

// A buffered, seekable streambuf over a file descriptor that remembers the first error
// instead of setting badbit silently: the owner turns it into a WriteError.
class AtomicFile::FdBuffer : public std::streambuf {
 public:
  FdBuffer(int fd, std::filesystem::path path) : fd_(fd), path_(std::move(path)), data_(1 << 16) {
    setp(data_.data(), data_.data() + data_.size());
  }
  ~FdBuffer() override { close_quietly(); }

  int fd() const { return fd_; }
  int error() const { return error_; }
  std::size_t bytes() const { return bytes_; }
  const std::filesystem::path& path() const { return path_; }

  bool flush_buffer() {
    const char* p = pbase();
    std::size_t left = static_cast<std::size_t>(pptr() - pbase());
    while (left > 0 && error_ == 0) {
      ssize_t n = ::write(fd_, p, left);
      if (n < 0) {
        if (errno == EINTR) continue;
        error_ = errno;
        break;
      }
      p += n;
      left -= static_cast<std::size_t>(n);
      bytes_ = std::max<std::size_t>(bytes_, position_ += static_cast<std::size_t>(n));
    }
    setp(data_.data(), data_.data() + data_.size());
    return error_ == 0;
  }

  void close_checked() {
    if (fd_ < 0) return;
    int fd = fd_;
    fd_ = -1;
    // close() can report deferred write errors (NFS, quotas): it counts as a write.
    if (::close(fd) != 0 && error_ == 0) error_ = errno;
  }
  void close_quietly() noexcept {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  void set_error(int e) {
    if (error_ == 0) error_ = e;
  }

 protected:
  int_type overflow(int_type ch) override {
    if (!flush_buffer()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    std::streamsize done = 0;
    while (done < n) {
      if (pptr() == epptr() && !flush_buffer()) return done;
      std::streamsize room = epptr() - pptr();
      std::streamsize k = std::min(room, n - done);
      std::memcpy(pptr(), s + done, static_cast<std::size_t>(k));
      pbump(static_cast<int>(k));
      done += k;
    }
    return done;
  }
  int sync() override { return flush_buffer() ? 0 : -1; }
  pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override {
    if (!flush_buffer()) return pos_type(off_type(-1));
    int whence = dir == std::ios_base::beg   ? SEEK_SET
                 : dir == std::ios_base::cur ? SEEK_CUR
                                             : SEEK_END;
    off_t at = ::lseek(fd_, static_cast<off_t>(off), whence);
    if (at < 0) {
      set_error(errno);
      return pos_type(off_type(-1));
    }
    position_ = static_cast<std::size_t>(at);
    return pos_type(static_cast<off_type>(at));
  }
  pos_type seekpos(pos_type pos, std::ios_base::openmode mode) override {
    return seekoff(off_type(pos), std::ios_base::beg, mode);
  }

 private:
  int fd_;
  std::filesystem::path path_;
  std::vector<char> data_;
  int error_ = 0;
  std::size_t position_ = 0;
  std::size_t bytes_ = 0;
};

namespace {
std::filesystem::path temp_path_for(const std::filesystem::path& final_path) {
  static std::atomic<unsigned long> counter{0};
  std::string name(".");
  name.append(final_path.filename().string())
      .append(".tmp.")
      .append(std::to_string(::getpid()))
      .append(".")
      .append(std::to_string(counter.fetch_add(1)));
  return final_path.parent_path() / name;
}

void sync_folder(const std::filesystem::path& folder) {
  int fd = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;  // best effort: the file itself is already durable
  ::fsync(fd);
  ::close(fd);
}
}  // namespace

AtomicFile::AtomicFile(std::filesystem::path final_path)
    : final_path_(std::move(final_path)), temp_path_(temp_path_for(final_path_)) {
  int fd = ::open(temp_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) throw_write_error("cannot create", temp_path_, errno);
  buffer_ = std::make_unique<FdBuffer>(fd, temp_path_);
  stream_ = std::make_unique<std::ostream>(buffer_.get());
}

AtomicFile::~AtomicFile() {
  if (!committed_) discard();
}

void AtomicFile::discard() noexcept {
  stream_.reset();
  buffer_.reset();  // closes the descriptor
  ::unlink(temp_path_.c_str());
}

std::ostream& AtomicFile::stream() { return *stream_; }

std::size_t AtomicFile::bytes_written() const { return buffer_ ? buffer_->bytes() : 0; }

void AtomicFile::check() {
  if (buffer_->error() != 0) throw_write_error("cannot write", final_path_, buffer_->error());
  if (!*stream_) throw_write_error("cannot write", final_path_, EIO);
}

void AtomicFile::write(const void* data, std::size_t bytes) {
  stream_->write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
  check();
}

void AtomicFile::commit(bool sync) {
  if (committed_) return;
  stream_->flush();
  check();
  if (sync && ::fsync(buffer_->fd()) != 0) throw_write_error("cannot sync", final_path_, errno);
  buffer_->close_checked();
  check();
  if (::rename(temp_path_.c_str(), final_path_.c_str()) != 0)
    throw_write_error("cannot rename temporary file to", final_path_, errno);
  committed_ = true;
  if (sync) sync_folder(final_path_.parent_path());
}

void write_file_atomically(const std::filesystem::path& path, std::string_view bytes, bool sync) {
  AtomicFile file(path);
  file.write(bytes);
  file.commit(sync);
}

}  // namespace voxspan
