#pragma once
// A run's outputs appear together, whole, or not at all. Every output (image,
// hit buffers, heat map, JSON, exported scene, a sequence's frames) is written
// into the run's OutputFiles, which puts them in place only once the whole run
// has succeeded:
//
//  - write() writes a file's bytes to a hidden temporary file beside its final
//    name (".STEM.tmp-PID.EXT"), checking every write, the fsync and the close,
//    so a full disk is an error here and not a truncated file later;
//  - commitAll() renames every temporary file into place;
//  - on any failure before that (or a destruction without commitAll) every
//    temporary file is removed and no final name is touched.
//
// A target that exists and is not a regular file (a device such as /dev/null
// or /dev/full, a FIFO, /dev/stdout) cannot be renamed into: its bytes are
// kept in memory and commitAll writes them into it, checking write and close
// (fsync too, where the target supports it), before any rename. So a device
// that refuses the bytes (ENOSPC on /dev/full) fails the run before any
// regular file appears; what a device or pipe has already accepted cannot be
// taken back. A symbolic link is followed to the file it names, which is
// replaced (so /dev/stdout redirected to a file gets a new file there).
//
// Every failure throws std::runtime_error("PATH: reason"), one line.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace passtrace {

class OutputFiles {
 public:
  OutputFiles() = default;
  ~OutputFiles();  // removes the temporary files unless commitAll succeeded
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;

  // Writes `bytes` as the future content of `path`; nothing appears under
  // `path` before commitAll. A path given twice is an error.
  void write(const std::filesystem::path& path, std::string_view bytes);

  // Writes the streams (devices, pipes), then renames every temporary file
  // into place and syncs the directories. A rename that fails (it should not,
  // within one file system) removes the files already renamed, best effort.
  void commitAll();

 private:
  struct Pending {
    std::filesystem::path target;
    std::filesystem::path temp;  // empty for a stream target
    std::string bytes;           // a stream target's content
  };
  std::vector<Pending> pending_;
};

// Throws std::runtime_error("PATH: reason") unless `path` names a file that
// could be created: its directory exists and is writable and it is not a
// directory, or it is an existing writable device or pipe.
void checkWritable(const std::filesystem::path& path);

}  // namespace passtrace
