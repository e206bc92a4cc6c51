#pragma once
// The on-disk caches of cosmo, in one place: where they are, what they hold, how big they may grow, and how their
// entries go. Two caches use it: the scan cache (decoded scans of compressed ROS 1 bags, trials/scan_cache.hpp)
// and the simulation cache (sequences written by cosmo_simulate). `cosmo_cache` lists and clears them.
//
// An entry is one top-level item of a cache's root: a folder (a simulated sequence), or the files that share a
// name up to their last extension (a bag's `<id>.scans`, `<id>.span`, `<id>.info`). `<id>.info` beside a file
// entry, `entry.info` inside a folder entry, says in one line what it holds. Names holding ".tmp-<pid>" are a
// writer's temporaries (not entries; removed by a clear once their process is gone); names starting with '.' are
// the cache's own (an entry being removed).
//
// Size limit: after a writer completes an entry it calls enforceLimit, which removes the least recently used whole
// entries until the cache holds at most the limit; the entry just written is kept. An entry is removed by first
// renaming it out of its name (atomic: a reader finds the whole entry or none) and then deleting it; a process that
// has its files open keeps reading them (POSIX unlink). An entry a reader holds an EntryUse on is skipped.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace cosmo::cache {

enum class Kind { Scan, Sim };

/// "scan" / "sim".
const char* kindName(Kind kind);
/// Parses "scan" / "sim"; throws std::invalid_argument naming the choices.
Kind parseKind(const std::string& name);

/// The cache's root. Scan: $COSMO_SCAN_CACHE ("off": none, empty path), else $XDG_CACHE_HOME/cosmo/scans, else
/// ~/.cache/cosmo/scans. Sim: $COSMO_SIM_CACHE, else $XDG_CACHE_HOME/cosmo/sim, else ~/.cache/cosmo/sim.
std::filesystem::path cacheRoot(Kind kind);

/// The environment variable of the cache's size limit: COSMO_SCAN_CACHE_MAX_SIZE / COSMO_SIM_CACHE_MAX_SIZE.
const char* maxSizeVariable(Kind kind);
/// The default limit: 100G (scan), 20G (sim).
std::uint64_t defaultMaxSize(Kind kind);
/// The limit: its variable when set, else the default. Throws std::invalid_argument (naming the variable) on a
/// value parseSize refuses.
std::uint64_t maxSize(Kind kind);

/// "123", "512K", "1.5G", "100G", "2T" (binary multiples: K = 1024); throws std::invalid_argument saying what
/// `what` (an option or variable name) expects and what it got.
std::uint64_t parseSize(const std::string& text, const std::string& what);
/// "1.5G", "200M", "17K", "12B": for listings.
std::string formatSize(std::uint64_t bytes);

struct Entry {
  std::string id;                            ///< the top-level name (file entries: without extension)
  std::vector<std::filesystem::path> paths;  ///< the folder, or the files
  bool folder = false;
  std::uint64_t bytes = 0;                      ///< on disk, every file below it
  std::filesystem::file_time_type last_used{};  ///< the newest modification time of its top-level items
  std::string info;                             ///< the first line of its .info; "" when it has none
};

/// The entries of `root`, least recently used first (ties: by id). Temporaries and the cache's own items are left
/// out. An empty or missing root has none.
std::vector<Entry> listEntries(const std::filesystem::path& root);

/// Bytes of the writers' temporaries and of entries being removed (in the total, never evicted by enforceLimit).
std::uint64_t pendingBytes(const std::filesystem::path& root);

/// Marks an entry used now (its modification time, so that it is evicted last). `path`: any of its top-level items.
void touch(const std::filesystem::path& path);

/// Writes `<file entry path without extension>.info` or `<folder>/entry.info`: one line saying what it holds.
/// Through a temporary file; a failed write leaves none (the entry only lists without a description).
void writeInfo(const std::filesystem::path& info_path, const std::string& line);
/// `<path without its extension>.info`: the info file of a file entry.
std::filesystem::path infoPathOf(const std::filesystem::path& entry_file);
/// "entry.info": the info file's name inside a folder entry.
inline constexpr const char* kFolderInfoName = "entry.info";

/// Removes a whole entry: renamed out of its name first, then deleted. False when another process holds an
/// EntryUse on it or removed it meanwhile.
bool removeEntry(const std::filesystem::path& root, const Entry& entry);

struct Eviction {
  std::vector<Entry> removed;
  std::uint64_t bytes_before = 0, bytes_after = 0;  ///< entries and pending items
};

/// Removes least recently used whole entries until the cache holds at most `max_bytes`; entries whose id is
/// `keep` (the one just written) or that are in use stay.
Eviction enforceLimit(const std::filesystem::path& root, std::uint64_t max_bytes, const std::string& keep = "");

/// Removes every entry (or the one whose id is `id`; std::invalid_argument when there is none) and the
/// temporaries whose writing process is gone. Entries in use stay (listed in the result's `kept`).
struct Cleared {
  std::vector<Entry> removed, kept;
  std::uint64_t bytes = 0;  ///< freed
};
Cleared clear(const std::filesystem::path& root, const std::string& id = "");

/// A reader's hold on an entry (a shared flock on `path`, one of the entry's files or its folder): removeEntry
/// skips it while held. A path that cannot be opened is simply not held.
class EntryUse {
 public:
  explicit EntryUse(const std::filesystem::path& path);
  ~EntryUse();
  EntryUse(const EntryUse&) = delete;
  EntryUse& operator=(const EntryUse&) = delete;

 private:
  int fd_ = -1;
};

/// The cache's limit applied after a write: enforceLimit(root, maxSize(kind), keep), with one line on stderr per
/// entry removed ("cosmo cache (scan): removed X (1.2G, last used 3 days ago) to stay under
/// COSMO_SCAN_CACHE_MAX_SIZE=100G"). A bad limit variable is an error (std::invalid_argument).
Eviction applyLimit(Kind kind, const std::filesystem::path& root, const std::string& keep);

/// A fast 64-bit hash of bytes (xxHash64's round on four lanes; not cryptographic): cache keys and the damage
/// check of a cache's records. `seed` chains it.
std::uint64_t hashBytes(const void* data, std::size_t size, std::uint64_t seed = 0);

/// A large file's identity from its content, cheap to compute: its size and the hash of its first and last 1 MiB
/// and of 16 blocks of 64 KiB evenly spread between (the whole file when it is smaller than 3 MiB). Equal for the
/// same file reached through any path (symlinks, bind mounts, copies); different when the size or any sampled
/// byte differs. Throws std::runtime_error when the file cannot be read.
std::uint64_t fileIdentity(const std::filesystem::path& file);

/// "3 h", "12 min", "4 days": the time since `t`.
std::string formatAge(std::filesystem::file_time_type t);

}  // namespace cosmo::cache
