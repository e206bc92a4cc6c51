#pragma once
// What a file is, for deciding whether a dataset made from it is still current: its content hash (SHA-256) when
// it is small enough to read every time, else its size and modification time (a trial's bag of gigabytes); a
// folder (a ROS 2 bag) is the identities of its files. Output files are always hashed.
#include <cstdint>
#include <string>

namespace cosmo::suite {

/// Files up to this size are identified by their content, larger ones by size and modification time.
inline constexpr std::uintmax_t kHashedInputLimit = 64ull << 20;

/// SHA-256 of a file's bytes as 64 hex digits. Throws std::runtime_error naming the file when it cannot be read.
std::string sha256File(const std::string& path);
/// SHA-256 of a text as 64 hex digits.
std::string sha256Text(const std::string& text);

/// "sha256:<hex>" (a file up to kHashedInputLimit), "size:<bytes> mtime:<ns>" (a larger file), "folder:<hex>"
/// (the hash of the sorted names and identities of a folder's files), or "missing" (nothing at `path`).
std::string fileIdentity(const std::string& path);

}  // namespace cosmo::suite
