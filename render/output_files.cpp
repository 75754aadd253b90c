#include "render/output_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <set>
#include <stdexcept>

namespace fs = std::filesystem;

namespace passtrace {
namespace {

[[noreturn]] void fail(const fs::path& path, const std::string& what, int error) {
  throw std::runtime_error(path.string() + ": " + what + ": " + std::strerror(error));
}

// Every byte, or an error naming `path`: a short write is retried, so a disk
// that fills part-way ends in ENOSPC here.
void writeAll(int fd, std::string_view bytes, const fs::path& path) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(path, "write failed", n < 0 ? errno : EIO);
    bytes.remove_prefix(size_t(n));
  }
}

// Writes, syncs and closes; `stream`: a device or pipe, where fsync may be
// unsupported (EINVAL, ENOTSUP), which is no error.
void writeFile(const fs::path& path, const fs::path& opened, int flags, std::string_view bytes, bool stream) {
  const int fd = ::open(opened.c_str(), flags | O_WRONLY | O_CLOEXEC, 0666);
  if (fd < 0) fail(path, stream ? "cannot open" : "cannot create a temporary file beside it", errno);
  try {
    writeAll(fd, bytes, path);
    if (::fsync(fd) != 0 && !(stream && (errno == EINVAL || errno == ENOTSUP || errno == EROFS)))
      fail(path, "fsync failed", errno);
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) fail(path, "close failed", errno);
}

// ".STEM.tmp-PID.EXT" beside `path`.
fs::path temporaryName(const fs::path& path) {
  std::string name = ".";  // appended piecewise: GCC 12 misreports a chain of + (-Wrestrict)
  name += path.stem().string();
  name += ".tmp-" + std::to_string(::getpid());
  name += path.extension().string();
  return path.parent_path() / name;
}

// The file a chain of symbolic links names, existing or not (/dev/stdout
// redirected to a file, a link to a file not yet written): that file is
// replaced, never the link.
fs::path followLinks(fs::path path) {
  std::error_code error;
  for (int hops = 0; fs::is_symlink(fs::symlink_status(path, error)); ++hops) {
    const fs::path link = fs::read_symlink(path, error);
    if (error || hops == 40) fail(path, "cannot follow the symbolic link", error ? error.value() : ELOOP);
    path = link.is_absolute() ? link : path.parent_path() / link;
  }
  return path;
}

// Flushes the renames themselves; a directory that cannot be synced is no
// reason to fail a run whose files are all in place.
void syncDirectory(const fs::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

OutputFiles::~OutputFiles() {
  std::error_code ignored;
  for (const Pending& p : pending_)
    if (!p.temp.empty()) fs::remove(p.temp, ignored);
}

void OutputFiles::write(const fs::path& path, std::string_view bytes) {
  struct stat info;
  const bool exists = ::stat(path.c_str(), &info) == 0;
  if (exists && S_ISDIR(info.st_mode)) throw std::runtime_error(path.string() + ": is a directory");
  const bool stream = exists && !S_ISREG(info.st_mode);
  const fs::path target = stream ? path : followLinks(path);
  const fs::path key = fs::absolute(target).lexically_normal();
  for (const Pending& p : pending_)
    if (fs::absolute(p.target).lexically_normal() == key)
      throw std::runtime_error(path.string() + ": named by two outputs of the run");
  if (stream) {
    pending_.push_back({target, {}, std::string(bytes)});
    return;
  }
  pending_.push_back({target, temporaryName(target), {}});  // before writing: the destructor removes a partial file
  writeFile(path, pending_.back().temp, O_CREAT | O_TRUNC, bytes, false);
}

void OutputFiles::commitAll() {
  for (const Pending& p : pending_)
    if (p.temp.empty()) writeFile(p.target, p.target, 0, p.bytes, true);
  std::vector<const Pending*> renamed;
  for (const Pending& p : pending_) {
    if (p.temp.empty()) continue;
    std::error_code error;
    fs::rename(p.temp, p.target, error);
    if (error) {
      std::error_code ignored;
      for (const Pending* done : renamed) fs::remove(done->target, ignored);
      throw std::runtime_error(p.target.string() + ": cannot rename the finished file into place: " + error.message());
    }
    renamed.push_back(&p);
  }
  std::set<fs::path> dirs;
  for (const Pending* p : renamed) dirs.insert(p->target.parent_path());
  for (const fs::path& dir : dirs) syncDirectory(dir);
  pending_.clear();
}

void checkWritable(const fs::path& path) {
  if (path.empty()) throw std::runtime_error("empty output file name");
  struct stat info;
  if (::stat(path.c_str(), &info) == 0 && !S_ISREG(info.st_mode) && !S_ISDIR(info.st_mode)) {
    if (::access(path.c_str(), W_OK) != 0) throw std::runtime_error(path.string() + ": is not writable");
    return;
  }
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code error;
  if (fs::is_directory(path, error)) throw std::runtime_error(path.string() + ": is a directory");
  if (!fs::is_directory(dir, error)) throw std::runtime_error(path.string() + ": directory " + dir.string() + " does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    throw std::runtime_error(path.string() + ": directory " + dir.string() + " is not writable");
}

}  // namespace passtrace
