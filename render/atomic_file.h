#pragma once
// Outputs appear whole or not at all: they are written to a hidden temporary
// file beside the final name and renamed into place only on success.

#include <filesystem>
#include <string>

namespace passtrace {

// Removes the temporary file on every exit but a committed one.
class TemporaryFile {
 public:
  // ".STEM.tmp-PID.EXT" next to `finalPath`, keeping the extension for
  // writers that look at the name they open.
  explicit TemporaryFile(const std::filesystem::path& finalPath);
  ~TemporaryFile();
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // Renames the temporary file to the final name; throws
  // std::runtime_error("FINAL: reason") on failure.
  void commit();

 private:
  std::filesystem::path final_, path_;
  bool committed_ = false;
};

// Writes `text` to `path` atomically; throws std::runtime_error("PATH: reason").
void writeTextFile(const std::filesystem::path& path, const std::string& text);

// Throws std::runtime_error("PATH: reason") unless `path` names a file that
// could be created: its directory exists and is writable, and it is not a directory.
void checkWritable(const std::filesystem::path& path);

}  // namespace passtrace
