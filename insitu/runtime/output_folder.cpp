#include "insitu/runtime/output_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "voxspan/error.h"
#include "voxspan/log.h"

namespace voxspan {

std::vector<std::filesystem::path> prepare_output_folder(const std::filesystem::path& folder,
                                                         std::string_view what) {
  auto fail = [&](const std::string& why) -> Error {
    return make_error("cannot use ", what, " ", folder.string(), ": ", why);
  };
  if (folder.empty()) throw fail("the folder name is empty");
  std::error_code ec;
  std::vector<std::filesystem::path> made;
  for (std::filesystem::path p = std::filesystem::absolute(folder, ec);
       !ec && p.has_relative_path() && !std::filesystem::exists(p, ec); p = p.parent_path())
    made.push_back(p);
  std::filesystem::create_directories(folder, ec);
  if (ec) throw fail(ec.message());
  if (!std::filesystem::is_directory(folder, ec)) throw fail("it exists but is not a folder");
  // access(W_OK) says yes to root on a read-only mount; creating a file is the real test.
  std::filesystem::path probe = folder / (".voxspan-probe." + std::to_string(::getpid()));
  int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw fail(std::string("cannot create a file in it (") + std::strerror(errno) + ")");
  ::close(fd);
  ::unlink(probe.c_str());
  return made;
}

std::vector<std::filesystem::path> prepare_output_folders(const Config& config) {
  std::vector<std::filesystem::path> made;
  for (const ConfiguredOutput& o : config.outputs) {
    if (!o.settings->enabled) continue;
    const std::vector<std::filesystem::path> now =
        prepare_output_folder(config.folder_of(*o.settings), "outputs." + o.kind + " folder");
    made.insert(made.end(), now.begin(), now.end());
  }
  return made;
}

FolderLock::FolderLock(const std::filesystem::path& folder, std::string_view key)
    : file_(folder / ".voxspan.lock") {
  fd_ = ::open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw make_error("cannot lock output folder ", folder.string(), ": ", std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    std::string holder(256, '\0');
    const ssize_t n = ::pread(fd_, holder.data(), holder.size() - 1, 0);
    holder.resize(n > 0 ? std::size_t(n) : 0);
    while (!holder.empty() && (holder.back() == '\n' || holder.back() == '\0')) holder.pop_back();
    ::close(fd_);
    throw make_error("output folder ", folder.string(), " is in use by another run (",
                     holder.empty() ? std::string("its lock file is empty") : holder,
                     "): give each run its own ", key);
  }
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  const std::string holder = "process " + std::to_string(::getpid()) + " on " + host + "\n";
  // Without its text the lock still holds; another run's message then says less.
  const bool said = ::ftruncate(fd_, 0) == 0 &&
                    ::pwrite(fd_, holder.data(), holder.size(), 0) == ssize_t(holder.size());
  if (!said) log_debug("output folder ", folder.string(), ": the lock file holds no holder's name");
}

FolderLock::~FolderLock() {
  // Removed while still locked: a run that opens it now locks a file no longer in the folder
  // and makes its own, so at worst the two runs' start-ups race as they would without a lock.
  ::unlink(file_.c_str());
  ::close(fd_);
}

void remove_empty_folders(const std::vector<std::filesystem::path>& made) {
  for (const std::filesystem::path& folder : made) {
    std::error_code ec;
    if (std::filesystem::is_empty(folder, ec) && !ec) std::filesystem::remove(folder, ec);
  }
}

}  // namespace voxspan
