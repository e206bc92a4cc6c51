// cosmo_cache: lists and clears cosmo's on-disk caches (cache/cache.hpp): the scan cache (decoded scans of
// compressed ROS 1 bags, one entry per bag, topic and stamp convention) and the simulation cache (one entry per
// sequence cosmo_simulate wrote).
//
//   cosmo_cache [--cache scan|sim]                       list: entries (size, last use, what), totals, limits
//   cosmo_cache [--cache scan|sim] --clear [--entry ID]  remove every entry, or one
//   cosmo_cache [--cache scan|sim] --max-size SIZE       remove least recently used entries down to SIZE
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "cosmo/cache/cache.hpp"
#include "cosmo/common/command_line.hpp"

using namespace cosmo;
namespace fs = std::filesystem;

namespace {

const char* rootVariable(cache::Kind kind) {
  return kind == cache::Kind::Scan ? "COSMO_SCAN_CACHE" : "COSMO_SIM_CACHE";
}

void list(cache::Kind kind) {
  const fs::path root = cache::cacheRoot(kind);
  const char* name = cache::kindName(kind);
  if (root.empty()) {
    std::printf("%s cache: off (%s=off)\n\n", name, rootVariable(kind));
    return;
  }
  const std::uint64_t limit = cache::maxSize(kind);
  const std::vector<cache::Entry> entries = cache::listEntries(root);
  const std::uint64_t pending = cache::pendingBytes(root);
  std::uint64_t total = pending;
  for (const auto& e : entries) total += e.bytes;
  std::printf("%s cache: %s (%s; limit %s, %s)\n", name, root.string().c_str(),
              fs::exists(root) ? "exists" : "empty, not created yet", cache::formatSize(limit).c_str(),
              cache::maxSizeVariable(kind));
  if (!entries.empty()) std::printf("  %-32s %8s %10s  %s\n", "entry", "size", "last used", "what");
  for (auto it = entries.rbegin(); it != entries.rend(); ++it)  // most recently used first
    std::printf("  %-32s %8s %10s  %s\n", it->id.c_str(), cache::formatSize(it->bytes).c_str(),
                (cache::formatAge(it->last_used) + " ago").c_str(),
                it->info.empty() ? "(no description: being written, or from an earlier cosmo)" : it->info.c_str());
  std::printf("  total: %zu %s, %s", entries.size(), entries.size() == 1 ? "entry" : "entries",
              cache::formatSize(total).c_str());
  if (pending) std::printf(" (%s being written or removed)", cache::formatSize(pending).c_str());
  std::printf("\n\n");
}

void report(cache::Kind kind, const std::vector<cache::Entry>& removed, const std::vector<cache::Entry>& kept) {
  for (const auto& e : removed)
    std::printf("%s cache: removed %s (%s)\n", cache::kindName(kind), e.id.c_str(), cache::formatSize(e.bytes).c_str());
  for (const auto& e : kept)
    std::printf("%s cache: kept %s (in use by a running process)\n", cache::kindName(kind), e.id.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  std::string which, entry, max_size;
  bool clear = false;
  CommandLine app("cosmo_cache",
                  "Lists cosmo's caches (sizes per entry: a bag's decoded scans, a simulated sequence; last use; "
                  "totals; limits) or removes entries from them. The scan cache is $COSMO_SCAN_CACHE (default "
                  "~/.cache/cosmo/scans, limit $COSMO_SCAN_CACHE_MAX_SIZE, default 100G); the simulation cache "
                  "$COSMO_SIM_CACHE (default ~/.cache/cosmo/sim, limit $COSMO_SIM_CACHE_MAX_SIZE, default 20G). "
                  "Writers keep their cache under its limit by removing the least recently used whole entries.");
  app.add_option("--cache", which, "scan or sim (default: both)")->type_name("scan|sim");
  app.add_flag("--clear", clear, "remove every entry (of --cache; of both without it), or only --entry's");
  app.add_option("--entry", entry, "with --clear: the entry to remove (its id as listed)")->type_name("ID");
  app.add_option("--max-size", max_size,
                 "remove least recently used entries until the cache holds at most SIZE (bytes, or K, M, G, T)")
      ->type_name("SIZE");
  if (const std::optional<int> code = app.parseOrExit(argc, argv)) return *code;
  try {
    if (!entry.empty() && !clear) throw std::invalid_argument("--entry goes with --clear");
    if (clear && !max_size.empty()) throw std::invalid_argument("--clear and --max-size: give one");
    std::vector<cache::Kind> kinds = {cache::Kind::Scan, cache::Kind::Sim};
    if (!which.empty()) kinds = {cache::parseKind(which)};
    if (!max_size.empty()) {
      const std::uint64_t limit = cache::parseSize(max_size, "--max-size");
      for (cache::Kind kind : kinds) {
        const cache::Eviction ev = cache::enforceLimit(cache::cacheRoot(kind), limit);
        report(kind, ev.removed, {});
        std::printf("%s cache: %s -> %s\n", cache::kindName(kind), cache::formatSize(ev.bytes_before).c_str(),
                    cache::formatSize(ev.bytes_after).c_str());
      }
      return 0;
    }
    if (clear) {
      bool found = false;
      for (cache::Kind kind : kinds) {
        const fs::path root = cache::cacheRoot(kind);
        if (root.empty()) continue;
        if (!entry.empty()) {
          bool here = false;
          for (const auto& e : cache::listEntries(root)) here = here || e.id == entry;
          if (!here) continue;
        }
        found = true;
        const cache::Cleared c = cache::clear(root, entry);
        report(kind, c.removed, c.kept);
        std::printf("%s cache: %s freed\n", cache::kindName(kind), cache::formatSize(c.bytes).c_str());
      }
      if (!entry.empty() && !found)
        throw std::invalid_argument("no entry '" + entry + "' in the " +
                                    (which.empty() ? std::string("scan or sim") : which) +
                                    " cache (`cosmo_cache` lists them)");
      return 0;
    }
    for (cache::Kind kind : kinds) list(kind);
  } catch (const std::invalid_argument& e) {
    std::cerr << "cosmo_cache: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "cosmo_cache: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
