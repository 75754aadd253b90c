#include "render/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace passtrace {

TemporaryFile::TemporaryFile(const fs::path& finalPath) : final_(finalPath) {
  std::string name = ".";  // appended piecewise: GCC 12 misreports a chain of + (-Wrestrict)
  name += finalPath.stem().string();
  name += ".tmp-" + std::to_string(::getpid());
  name += finalPath.extension().string();
  path_ = finalPath.parent_path() / name;
}

TemporaryFile::~TemporaryFile() {
  std::error_code ignored;
  if (!committed_) fs::remove(path_, ignored);
}

void TemporaryFile::commit() {
  std::error_code error;
  fs::rename(path_, final_, error);
  if (error) throw std::runtime_error(final_.string() + ": cannot rename the finished file into place: " + error.message());
  committed_ = true;
}

void writeTextFile(const fs::path& path, const std::string& text) {
  TemporaryFile temp(path);
  {
    std::ofstream out(temp.path(), std::ios::binary);
    if (!out) throw std::runtime_error(path.string() + ": cannot write: " + std::strerror(errno));
    out << text;
    out.close();
    if (!out) throw std::runtime_error(path.string() + ": write failed: " + std::strerror(errno));
  }
  temp.commit();
}

void checkWritable(const fs::path& path) {
  if (path.empty()) throw std::runtime_error("empty output file name");
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code error;
  if (fs::is_directory(path, error)) throw std::runtime_error(path.string() + ": is a directory");
  if (!fs::is_directory(dir, error)) throw std::runtime_error(path.string() + ": directory " + dir.string() + " does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    throw std::runtime_error(path.string() + ": directory " + dir.string() + " is not writable");
}

}  // namespace passtrace
