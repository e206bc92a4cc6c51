#include "cosmo/frontend/spill_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace cosmo::frontend {

namespace {
std::string reason() { return std::strerror(errno); }
}  // namespace

SpillFile::SpillFile(const std::string& dir)
    : dir_(dir.empty() ? std::filesystem::temp_directory_path().string() : dir) {
  std::string path = (std::filesystem::path(dir_) / "cosmo-spill-XXXXXX").string();
  std::vector<char> name(path.begin(), path.end());
  name.push_back('\0');
  fd_ = ::mkstemp(name.data());
  if (fd_ < 0) throw std::runtime_error("spill file: cannot create a file in " + dir_ + ": " + reason());
  ::unlink(name.data());  // the open descriptor keeps it until the process ends
}

SpillFile::~SpillFile() {
  if (fd_ >= 0) ::close(fd_);
}

SpillFile::Extent SpillFile::append(const void* data, std::size_t size) {
  Extent e;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    e.offset = end_;
    e.size = size;
    end_ += size;
  }
  const char* p = static_cast<const char*>(data);
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::pwrite(fd_, p + done, size - done, static_cast<off_t>(e.offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw std::runtime_error("spill file in " + dir_ + ": write failed: " + (n < 0 ? reason() : "no progress"));
    done += static_cast<std::size_t>(n);
  }
  return e;
}

void SpillFile::read(const Extent& extent, void* out) const {
  char* p = static_cast<char*>(out);
  std::size_t done = 0;
  while (done < extent.size) {
    const ssize_t n = ::pread(fd_, p + done, extent.size - done, static_cast<off_t>(extent.offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw std::runtime_error("spill file in " + dir_ + ": read failed: " + (n < 0 ? reason() : "short file"));
    done += static_cast<std::size_t>(n);
  }
}

std::uint64_t SpillFile::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return end_;
}

}  // namespace cosmo::frontend
