#pragma once
// A database of ScanContext descriptors with the paper's two-phase search: the ring keys' nearest neighbours
// (a nanoflann k-d tree, L2 distance) give candidates, the full descriptor distance ranks them.
//
// Insertion is cheap: the k-d tree covers the entries present at its last rebuild and is rebuilt periodically
// (see ScanContextDatabaseParams::rebuild_every); the newer entries are searched linearly, so every query sees every
// inserted entry. Entries keep their insertion order ("position"); a query may be limited to the first N positions,
// which is how a robot excludes its most recent keyframes.
#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

#include "cosmo/common/time.hpp"
#include "cosmo/place_recognition/scan_context.hpp"

namespace cosmo::place_recognition {

struct ScanContextDatabaseParams {
  /// Ring-key nearest neighbours that get the full distance (paper / Kim's code: 10).
  int num_candidates = 10;
  /// Rebuild the k-d tree once max(rebuild_every, rebuild_fraction * entries in the tree) entries wait outside
  /// it; those newest entries are scanned linearly. The fraction keeps the rebuild cost per insertion constant
  /// for large databases (a 50k rebuild takes ~0.1 s), while the linear part stays a small share of a query.
  int rebuild_every = 50;
  double rebuild_fraction = 0.1;
  /// Full-distance options (empty columns, shift search) taken from the descriptor parameters.
  EmptyColumnPolicy empty_columns = EmptyColumnPolicy::kPenalizeOneSided;
  int coarse_search_radius = -1;
};

struct DatabaseEntry {
  std::size_t id = 0;  ///< caller's id (keyframe index)
  StampNs stamp = 0;   ///< stamp of the scan (used for time-based exclusion)
  ScanContext descriptor;
};

struct DatabaseMatch {
  std::size_t position = 0;  ///< insertion position in the database
  std::size_t id = 0;        ///< the entry's id
  DescriptorMatch match;
};

class ScanContextDatabase {
 public:
  explicit ScanContextDatabase(const ScanContextDatabaseParams& params = {});
  ~ScanContextDatabase();
  ScanContextDatabase(ScanContextDatabase&&) noexcept;
  ScanContextDatabase& operator=(ScanContextDatabase&&) noexcept;
  ScanContextDatabase(const ScanContextDatabase&) = delete;
  ScanContextDatabase& operator=(const ScanContextDatabase&) = delete;

  /// Appends an entry (its descriptor must have the size of the earlier ones; throws std::invalid_argument).
  void insert(std::size_t id, ScanContext descriptor, StampNs stamp = 0);
  std::size_t size() const;
  bool empty() const { return size() == 0; }
  const DatabaseEntry& entry(std::size_t position) const;
  /// Entries in the k-d tree (the rest are the linearly searched newest ones).
  std::size_t indexedSize() const;

  /// Two-phase search among the entries at positions [0, searchable): the num_candidates nearest ring keys,
  /// each scored with the full distance; returned sorted by distance (ties: lower position first).
  std::vector<DatabaseMatch> query(const ScanContext& query,
                                   std::size_t searchable = std::numeric_limits<std::size_t>::max()) const;
  /// The ring-key phase alone: positions of the k nearest ring keys among [0, searchable), nearest first.
  std::vector<std::size_t> nearestRingKeys(const Eigen::VectorXf& ring_key, std::size_t k,
                                           std::size_t searchable = std::numeric_limits<std::size_t>::max()) const;

 private:
  void rebuild();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cosmo::place_recognition
