// A scan cache file (trials/scan_cache.hpp: decoded scans kept on disk) and a cached span, which a full disk or a
// killed run can leave damaged: read back scan by scan.
#include <cstring>

#include "../fuzz_target.hpp"
#include "../input_file.hpp"
#include "cosmo/trials/scan_cache.hpp"

using namespace cosmo;

COSMO_FUZZ_TARGET(scan_cache) {
  const std::string path = fuzz::inputFile(data, size, "input.scans");
  if (size >= 10 && std::memcmp(data, "cosmo-span", 10) == 0) {
    StampNs first = 0, last = 0;
    trials::readCachedSpan(path, first, last);
    return;
  }
  trials::CachedScanSource source(path);
  Scan scan;
  while (source.next(scan)) {
  }
}
