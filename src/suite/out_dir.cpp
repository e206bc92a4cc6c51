#include "cosmo/suite/out_dir.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "cosmo/dataset/atomic_file.hpp"
#include "cosmo/suite/job_record.hpp"
#include "cosmo/common/whole_file.hpp"

namespace fs = std::filesystem;

namespace cosmo::suite {
namespace {

std::string flat(const std::string& job_id) {
  std::string s = job_id;
  for (char& c : s)
    if (c == '/') c = '+';
  return s;
}

}  // namespace

std::string suiteDir(const std::string& out_dir, const std::string& sub) {
  const fs::path p = fs::path(out_dir) / ".suite" / sub;
  fs::create_directories(p);
  return p.string();
}

FileLock::FileLock(const std::string& path, bool wait, const std::string& busy_message) {
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error(path + ": cannot open the lock file: " + std::strerror(errno));
  while (::flock(fd_, LOCK_EX | (wait ? 0 : LOCK_NB)) != 0) {
    if (errno == EINTR) continue;
    const int err = errno;
    ::close(fd_);
    fd_ = -1;
    if (err == EWOULDBLOCK) {
      const std::string holder = readWholeFileOrEmpty(path);
      throw std::runtime_error(busy_message + (holder.empty() ? "" : "\n  held by: " + holder));
    }
    throw std::runtime_error(path + ": flock: " + std::strerror(err));
  }
}

FileLock::~FileLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the flock
}

void FileLock::note(const std::string& text) {
  if (fd_ < 0) return;
  if (::ftruncate(fd_, 0) != 0) return;
  if (::pwrite(fd_, text.data(), text.size(), 0) < 0) return;
}

std::unique_ptr<FileLock> lockOutDir(const std::string& out_dir, const std::string& command) {
  auto lock = std::make_unique<FileLock>(
      suiteDir(out_dir) + "/lock", false,
      out_dir + " is in use by another cosmo_suite: wait for it to finish, or give another --out");
  lock->note("pid " + std::to_string(::getpid()) + ": " + command);
  return lock;
}

std::unique_ptr<FileLock> lockJob(const std::string& out_dir, const std::string& job_id, bool wait) {
  const std::string path = suiteDir(out_dir, "locks") + "/" + flat(job_id) + ".lock";
  try {
    auto lock = std::make_unique<FileLock>(path, wait, job_id + " is being written by another process");
    lock->note("pid " + std::to_string(::getpid()));
    return lock;
  } catch (const std::runtime_error&) {
    if (wait) throw;
    return nullptr;
  }
}

std::string makeJobTmpDir(const std::string& out_dir, const std::string& job_id) {
  const fs::path p = fs::path(suiteDir(out_dir, "tmp")) / (flat(job_id) + "." + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p.string();
}

void moveIntoPlace(const std::string& out_dir, const std::string& tmp_dir, const std::string& job_folder) {
  fs::create_directories(fs::path(job_folder).parent_path());
  syncPath(tmp_dir);
  const fs::path trash = fs::path(suiteDir(out_dir, "trash")) / fs::path(tmp_dir).filename();
  std::error_code ec;
  if (fs::exists(job_folder)) fs::rename(job_folder, trash);
  fs::rename(tmp_dir, job_folder);
  syncPath(fs::path(job_folder).parent_path().string());
  fs::remove_all(trash, ec);
}

bool removePartial(const std::string& out_dir, const std::string& job_id) {
  bool found = false;
  const std::string prefix = flat(job_id) + ".";
  for (const char* sub : {"tmp", "trash"})
    for (const auto& e : fs::directory_iterator(suiteDir(out_dir, sub)))
      if (e.path().filename().string().rfind(prefix, 0) == 0) {
        found |= std::string(sub) == "tmp";
        fs::remove_all(e.path());
      }
  return found;
}

void writeManifest(const Plan& plan) {
  const FileLock lock(suiteDir(plan.out_dir) + "/manifest.lock", true, "");
  std::string text;
  for (const auto& job : plan.jobs) {
    JobRecord r;
    if (readRecord(jobFolder(plan, job), r)) text += r.toJson() + "\n";
  }
  dataset::writeFileAtomically((fs::path(plan.out_dir) / "manifest.jsonl").string(), text);
}

void syncPath(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;
  if (fs::is_directory(path)) {
    for (const auto& e : fs::directory_iterator(path))
      if (e.is_regular_file()) syncPath(e.path().string());
  }
  ::fsync(fd);
  ::close(fd);
}

}  // namespace cosmo::suite
