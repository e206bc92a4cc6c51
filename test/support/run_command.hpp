#pragma once
// Test helpers for the tests that run programs: the folder of the running test binary (the build puts the tools
// beside it) and a shell command's exit status and output.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace cosmo::test {

/// The folder holding this test binary; empty when /proc/self/exe cannot be read.
inline std::filesystem::path binDir() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : self.parent_path();
}

struct CommandRun {
  int status = -1;     ///< exit status; -1 when the command could not start or did not exit normally
  std::string output;  ///< what it wrote on stdout (end the command with 2>&1 for stderr as well)
};

/// Runs `command` with /bin/sh and waits for it.
inline CommandRun runCommand(const std::string& command) {
  CommandRun r;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  for (std::size_t n; (n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0;) r.output.append(buf.data(), n);
  const int status = ::pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace cosmo::test
