// cosmo::cache (cache/cache.hpp): sizes, entries, the least-recently-used limit, clearing, content identities.
// Every test works in a folder of its own under the temporary directory (never the user's ~/.cache), removed at
// its end; the files are a few KB.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "cosmo/cache/cache.hpp"

namespace fs = std::filesystem;
using namespace cosmo;

namespace {

struct TempRoot {
  fs::path path = fs::temp_directory_path() / ("cosmo_cache_test_" + std::to_string(::getpid()) + "_" +
                                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
  TempRoot() {
    fs::remove_all(path);
    fs::create_directories(path);
    // Whatever the code under test resolves, it is below this folder.
    ::setenv("COSMO_SCAN_CACHE", (path / "scans").c_str(), 1);
    ::setenv("COSMO_SIM_CACHE", (path / "sim").c_str(), 1);
  }
  ~TempRoot() { fs::remove_all(path); }
};

void writeBytes(const fs::path& p, std::size_t n, char fill = 'x') {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << std::string(n, fill);
}

/// Sets an item's last use to `minutes` ago.
void usedAgo(const fs::path& p, int minutes) {
  fs::last_write_time(p, fs::file_time_type::clock::now() - std::chrono::minutes(minutes));
}

std::vector<std::string> ids(const std::vector<cache::Entry>& entries) {
  std::vector<std::string> out;
  for (const auto& e : entries) out.push_back(e.id);
  return out;
}

}  // namespace

TEST(CacheSize, ParsesSuffixesAndRefusesTheRest) {
  EXPECT_EQ(cache::parseSize("0", "X"), 0u);
  EXPECT_EQ(cache::parseSize("123", "X"), 123u);
  EXPECT_EQ(cache::parseSize("4K", "X"), 4096u);
  EXPECT_EQ(cache::parseSize("1.5M", "X"), 1572864u);
  EXPECT_EQ(cache::parseSize("100G", "X"), 100ULL << 30);
  EXPECT_EQ(cache::parseSize("100GB", "X"), 100ULL << 30);
  EXPECT_EQ(cache::parseSize("2t", "X"), 2ULL << 40);
  for (const char* bad : {"", "G", "12X", "-1G", "1..2G", "ten", "1e3", "5 G"}) {
    try {
      cache::parseSize(bad, "COSMO_SCAN_CACHE_MAX_SIZE");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("COSMO_SCAN_CACHE_MAX_SIZE"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("'" + std::string(bad) + "'"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(cache::formatSize(1536), "1.5K");
  EXPECT_EQ(cache::formatSize(100ULL << 30), "100G");
  EXPECT_EQ(cache::formatSize(20ULL << 30), "20G");
}

TEST(CacheSize, LimitsFromTheEnvironment) {
  TempRoot t;
  ::unsetenv("COSMO_SCAN_CACHE_MAX_SIZE");
  ::unsetenv("COSMO_SIM_CACHE_MAX_SIZE");
  EXPECT_EQ(cache::maxSize(cache::Kind::Scan), 100ULL << 30);
  EXPECT_EQ(cache::maxSize(cache::Kind::Sim), 20ULL << 30);
  ::setenv("COSMO_SIM_CACHE_MAX_SIZE", "3M", 1);
  EXPECT_EQ(cache::maxSize(cache::Kind::Sim), 3ULL << 20);
  ::setenv("COSMO_SCAN_CACHE_MAX_SIZE", "lots", 1);
  EXPECT_THROW(cache::maxSize(cache::Kind::Scan), std::invalid_argument);
  ::unsetenv("COSMO_SCAN_CACHE_MAX_SIZE");
  ::unsetenv("COSMO_SIM_CACHE_MAX_SIZE");
  EXPECT_EQ(cache::cacheRoot(cache::Kind::Scan), t.path / "scans");
  EXPECT_EQ(cache::cacheRoot(cache::Kind::Sim), t.path / "sim");
  ::setenv("COSMO_SCAN_CACHE", "off", 1);
  EXPECT_TRUE(cache::cacheRoot(cache::Kind::Scan).empty());
}

TEST(CacheEntries, ListsFileGroupsAndFoldersLeastRecentlyUsedFirst) {
  TempRoot t;
  const fs::path root = t.path / "scans";
  writeBytes(root / "aaaa.scans", 1000);
  writeBytes(root / "aaaa.span", 10);
  cache::writeInfo(root / "aaaa.info", "trial one");
  writeBytes(root / "seq-1" / "a.bag", 500);
  cache::writeInfo(root / "seq-1" / cache::kFolderInfoName, "sequence one");
  writeBytes(root / "bbbb.scans.tmp-999999999-0", 300);  // a writer's temporary: not an entry
  usedAgo(root / "aaaa.scans", 30);
  usedAgo(root / "aaaa.span", 30);
  usedAgo(root / "aaaa.info", 30);
  usedAgo(root / "seq-1", 60);
  const auto entries = cache::listEntries(root);
  ASSERT_EQ(ids(entries), (std::vector<std::string>{"seq-1", "aaaa"}));
  EXPECT_TRUE(entries[0].folder);
  EXPECT_EQ(entries[0].info, "sequence one");
  EXPECT_EQ(entries[0].bytes, 500u + std::string("sequence one\n").size());
  EXPECT_EQ(entries[1].paths.size(), 3u);
  EXPECT_EQ(entries[1].info, "trial one");
  EXPECT_EQ(cache::pendingBytes(root), 300u);
  cache::touch(root / "seq-1");
  EXPECT_EQ(ids(cache::listEntries(root)), (std::vector<std::string>{"aaaa", "seq-1"}));
  EXPECT_TRUE(cache::listEntries(t.path / "missing").empty());
}

TEST(CacheLimit, EvictsLeastRecentlyUsedWholeEntriesUntilUnderTheLimit) {
  TempRoot t;
  const fs::path root = t.path / "sim";
  // Five entries of 1000 bytes (folders and file groups), used 50, 40, ... 10 minutes ago.
  const std::vector<std::string> names = {"e0", "e1", "e2", "e3", "e4"};
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i % 2) {
      writeBytes(root / (names[i] + ".scans"), 900);
      writeBytes(root / (names[i] + ".span"), 100);
      usedAgo(root / (names[i] + ".scans"), 50 - 10 * static_cast<int>(i));
      usedAgo(root / (names[i] + ".span"), 50 - 10 * static_cast<int>(i));
    } else {
      writeBytes(root / names[i] / "x.bag", 600);
      writeBytes(root / names[i] / "y.bag", 400);
      usedAgo(root / names[i], 50 - 10 * static_cast<int>(i));
    }
  }
  // Under the limit: nothing goes.
  EXPECT_TRUE(cache::enforceLimit(root, 5000).removed.empty());
  // 2500: the three oldest go, e0 first; the limit is honoured.
  cache::Eviction ev = cache::enforceLimit(root, 2500);
  EXPECT_EQ(ids(ev.removed), (std::vector<std::string>{"e0", "e1", "e2"}));
  EXPECT_EQ(ev.bytes_before, 5000u);
  EXPECT_EQ(ev.bytes_after, 2000u);
  EXPECT_EQ(ids(cache::listEntries(root)), (std::vector<std::string>{"e3", "e4"}));
  EXPECT_FALSE(fs::exists(root / "e1.span"));  // whole entries
  // Nothing half-removed is left behind.
  for (const auto& item : fs::directory_iterator(root))
    EXPECT_EQ(item.path().filename().string().rfind(".removing", 0), std::string::npos) << item.path();
  // The entry just written is kept even alone above the limit; an entry in use is skipped.
  ev = cache::enforceLimit(root, 0, "e3");
  EXPECT_EQ(ids(ev.removed), (std::vector<std::string>{"e4"}));
  EXPECT_EQ(ids(cache::listEntries(root)), (std::vector<std::string>{"e3"}));
  {
    cache::EntryUse use(root / "e3.scans");
    EXPECT_TRUE(cache::enforceLimit(root, 0).removed.empty());
    const cache::Cleared c = cache::clear(root);
    EXPECT_TRUE(c.removed.empty());
    EXPECT_EQ(ids(c.kept), (std::vector<std::string>{"e3"}));
  }
  EXPECT_EQ(ids(cache::enforceLimit(root, 0).removed), (std::vector<std::string>{"e3"}));
}

TEST(CacheLimit, ApplyLimitUsesTheVariableAndRefusesABadOne) {
  TempRoot t;
  const fs::path root = t.path / "scans";
  writeBytes(root / "old.scans", 4000);
  usedAgo(root / "old.scans", 10);
  writeBytes(root / "new.scans", 4000);
  ::setenv("COSMO_SCAN_CACHE_MAX_SIZE", "5K", 1);
  testing::internal::CaptureStderr();
  const cache::Eviction ev = cache::applyLimit(cache::Kind::Scan, root, "new");
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(ids(ev.removed), (std::vector<std::string>{"old"}));
  EXPECT_NE(err.find("removed old"), std::string::npos) << err;
  EXPECT_NE(err.find("COSMO_SCAN_CACHE_MAX_SIZE=5K"), std::string::npos) << err;
  ::setenv("COSMO_SCAN_CACHE_MAX_SIZE", "5X", 1);
  EXPECT_THROW(cache::applyLimit(cache::Kind::Scan, root, "new"), std::invalid_argument);
  ::unsetenv("COSMO_SCAN_CACHE_MAX_SIZE");
}

TEST(CacheClear, OneEntryOrAllAndStaleTemporaries) {
  TempRoot t;
  const fs::path root = t.path / "sim";
  writeBytes(root / "a" / "f", 10);
  writeBytes(root / "b.scans", 10);
  writeBytes(root / "c.scans.tmp-999999999-0", 10);                             // its process is gone
  writeBytes(root / ("d.scans.tmp-" + std::to_string(::getpid()) + "-0"), 10);  // still being written
  EXPECT_THROW(cache::clear(root, "zzz"), std::invalid_argument);
  cache::Cleared c = cache::clear(root, "b");
  EXPECT_EQ(ids(c.removed), (std::vector<std::string>{"b"}));
  EXPECT_TRUE(fs::exists(root / "a"));
  c = cache::clear(root);
  EXPECT_EQ(ids(c.removed), (std::vector<std::string>{"a"}));
  EXPECT_FALSE(fs::exists(root / "c.scans.tmp-999999999-0"));
  EXPECT_TRUE(fs::exists(root / ("d.scans.tmp-" + std::to_string(::getpid()) + "-0")));
}

TEST(CacheIdentity, SameThroughASymlinkDifferentForAChangedFile) {
  TempRoot t;
  // 4 MiB: first and last MiB, and samples between.
  std::string bytes(4 << 20, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>((i * 2654435761u) >> 13);
  const fs::path data = t.path / "data";
  writeBytes(data / "bag.bag", 0);
  std::ofstream(data / "bag.bag", std::ios::binary) << bytes;
  fs::create_directory_symlink(data, t.path / "linked");
  const std::uint64_t id = cache::fileIdentity(data / "bag.bag");
  EXPECT_EQ(cache::fileIdentity(t.path / "linked" / "bag.bag"), id);
  fs::copy_file(data / "bag.bag", t.path / "copy.bag");
  EXPECT_EQ(cache::fileIdentity(t.path / "copy.bag"), id);
  // A changed byte in the first MiB, the last MiB, or one more byte: another identity.
  for (std::size_t at : {std::size_t{100}, bytes.size() - 100}) {
    std::string changed = bytes;
    changed[at] ^= 1;
    std::ofstream(t.path / "changed.bag", std::ios::binary | std::ios::trunc) << changed;
    EXPECT_NE(cache::fileIdentity(t.path / "changed.bag"), id) << at;
  }
  std::ofstream(t.path / "longer.bag", std::ios::binary) << bytes << 'x';
  EXPECT_NE(cache::fileIdentity(t.path / "longer.bag"), id);
  EXPECT_THROW(cache::fileIdentity(t.path / "missing.bag"), std::runtime_error);
  EXPECT_NE(cache::hashBytes("abc", 3), cache::hashBytes("abd", 3));
  EXPECT_EQ(cache::hashBytes(bytes.data(), bytes.size()), cache::hashBytes(bytes.data(), bytes.size()));
}
