#pragma once
// An append-only scratch file for what a long run must keep but seldom reads (keyframe scans, registration
// features): blocks of bytes written once and read back exactly, so that the memory of a run does not grow with its
// keyframes (a 128-beam keyframe scan and its features are about 2 MB; a 9 km sequence has 4,500 keyframes).
// The file is made in `dir` (empty: the system's temp folder, TMPDIR) and unlinked at once: it takes disk space
// only while the process runs and disappears with it, also when the process dies. Thread-safe (positioned reads
// and writes; appends reserve their range under a lock).
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>

namespace cosmo::frontend {

class SpillFile {
 public:
  /// A block written to the file.
  struct Extent {
    std::uint64_t offset = 0;
    std::uint64_t size = 0;
  };

  /// Throws std::runtime_error naming the folder when the file cannot be made there.
  explicit SpillFile(const std::string& dir = "");
  ~SpillFile();
  SpillFile(const SpillFile&) = delete;
  SpillFile& operator=(const SpillFile&) = delete;

  /// Writes `size` bytes at the end of the file. Throws std::runtime_error (the folder, the reason) on a failure,
  /// e.g. a full disk.
  Extent append(const void* data, std::size_t size);
  /// Reads a block back into `out` (extent.size bytes). Throws std::runtime_error on a failure.
  void read(const Extent& extent, void* out) const;
  /// Bytes written so far.
  std::uint64_t size() const;
  /// The folder the file is in.
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
  int fd_ = -1;
  mutable std::mutex mutex_;
  std::uint64_t end_ = 0;
};

}  // namespace cosmo::frontend
