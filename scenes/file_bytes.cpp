#include "scenes/file_bytes.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "scenes/scene_error.h"

namespace passtrace {

std::string readFileBytes(const std::filesystem::path& file, std::uintmax_t maxBytes) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer.
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw SceneError(file, std::string("cannot open: ") + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat info {};
  if (::fstat(fd, &info) != 0) throw SceneError(file, std::string("cannot open: ") + std::strerror(errno));
  if (!S_ISREG(info.st_mode)) throw SceneError(file, "cannot open: not a regular file");
  if (static_cast<std::uintmax_t>(info.st_size) > maxBytes)
    throw SceneError(file, "file too large (" + std::to_string(info.st_size) + " bytes; the limit is " +
                               std::to_string(maxBytes >> 30) + " GiB)");
  std::string data(static_cast<std::size_t>(info.st_size), '\0');
  std::size_t filled = 0;
  while (filled < data.size()) {
    const ssize_t n = ::read(fd, data.data() + filled, data.size() - filled);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw SceneError(file, std::string("read failed: ") + std::strerror(errno));
    if (n == 0) break;
    filled += static_cast<std::size_t>(n);
  }
  data.resize(filled);
  return data;
}

}  // namespace passtrace
