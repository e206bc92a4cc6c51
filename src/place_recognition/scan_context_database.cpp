// ScanContext database: nanoflann k-d tree over ring keys, periodic rebuild, linear scan of the newest entries.
#include "cosmo/place_recognition/scan_context_database.hpp"

#include <algorithm>
#include <nanoflann.hpp>
#include <stdexcept>
#include <string>
#include <utility>

namespace cosmo::place_recognition {
namespace {

/// nanoflann's dataset interface over the first `count` ring keys of a flat array.
struct RingKeyCloud {
  const std::vector<float>* keys = nullptr;
  std::size_t dims = 0;
  std::size_t count = 0;
  std::size_t kdtree_get_point_count() const { return count; }
  float kdtree_get_pt(std::size_t idx, std::size_t dim) const { return (*keys)[idx * dims + dim]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using RingKeyTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, RingKeyCloud>, RingKeyCloud,
                                                        -1, std::size_t>;

}  // namespace

struct ScanContextDatabase::Impl {
  ScanContextDatabaseParams params;
  std::vector<DatabaseEntry> entries;
  std::vector<float> keys;  // ring keys, row after row
  std::size_t dims = 0;
  RingKeyCloud cloud;
  std::unique_ptr<RingKeyTree> tree;
};

ScanContextDatabase::ScanContextDatabase(const ScanContextDatabaseParams& params) : impl_(std::make_unique<Impl>()) {
  if (params.num_candidates < 1) throw std::invalid_argument("ScanContextDatabase: num_candidates must be >= 1");
  if (params.rebuild_every < 1) throw std::invalid_argument("ScanContextDatabase: rebuild_every must be >= 1");
  if (!(params.rebuild_fraction >= 0.0))
    throw std::invalid_argument("ScanContextDatabase: rebuild_fraction must be >= 0");
  impl_->params = params;
  impl_->cloud.keys = &impl_->keys;
}
ScanContextDatabase::~ScanContextDatabase() = default;
ScanContextDatabase::ScanContextDatabase(ScanContextDatabase&&) noexcept = default;
ScanContextDatabase& ScanContextDatabase::operator=(ScanContextDatabase&&) noexcept = default;

std::size_t ScanContextDatabase::size() const { return impl_->entries.size(); }
std::size_t ScanContextDatabase::indexedSize() const { return impl_->tree ? impl_->cloud.count : 0; }
const DatabaseEntry& ScanContextDatabase::entry(std::size_t position) const { return impl_->entries.at(position); }

void ScanContextDatabase::insert(std::size_t id, ScanContext descriptor, StampNs stamp) {
  Impl& m = *impl_;
  const auto dims = static_cast<std::size_t>(descriptor.ring_key.size());
  if (dims == 0) throw std::invalid_argument("ScanContextDatabase::insert: descriptor without ring key");
  if (!m.entries.empty()) {
    const ScanContext& first = m.entries.front().descriptor;
    if (dims != m.dims || descriptor.descriptor.rows() != first.descriptor.rows() ||
        descriptor.descriptor.cols() != first.descriptor.cols()) {
      throw std::invalid_argument("ScanContextDatabase::insert: descriptor of id " + std::to_string(id) +
                                  " has another size than the database's");
    }
  }
  m.dims = dims;
  m.keys.insert(m.keys.end(), descriptor.ring_key.data(), descriptor.ring_key.data() + dims);
  m.entries.push_back(DatabaseEntry{id, stamp, std::move(descriptor)});
  const double pending = static_cast<double>(m.entries.size() - indexedSize());
  if (pending >= std::max(static_cast<double>(m.params.rebuild_every),
                          m.params.rebuild_fraction * static_cast<double>(indexedSize())))
    rebuild();
}

void ScanContextDatabase::rebuild() {
  Impl& m = *impl_;
  m.tree.reset();
  m.cloud.dims = m.dims;
  m.cloud.count = m.entries.size();
  if (m.cloud.count == 0) return;
  m.tree = std::make_unique<RingKeyTree>(m.dims, m.cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
}

std::vector<std::size_t> ScanContextDatabase::nearestRingKeys(const Eigen::VectorXf& ring_key, std::size_t k,
                                                              std::size_t searchable) const {
  const Impl& m = *impl_;
  const std::size_t limit = std::min(searchable, m.entries.size());
  if (limit == 0 || k == 0) return {};
  if (static_cast<std::size_t>(ring_key.size()) != m.dims) {
    throw std::invalid_argument("ScanContextDatabase: query ring key has " + std::to_string(ring_key.size()) +
                                " rings, the database " + std::to_string(m.dims));
  }
  std::vector<std::pair<float, std::size_t>> found;  // (squared distance, position)
  const std::size_t indexed = indexedSize();
  if (indexed > 0) {
    // Entries at positions >= limit inside the tree are filtered out afterwards: ask for that many more.
    const std::size_t hidden = indexed > limit ? indexed - limit : 0;
    const std::size_t want = std::min(indexed, k + hidden);
    std::vector<std::size_t> idx(want);
    std::vector<float> d2(want);
    const std::size_t n = m.tree->knnSearch(ring_key.data(), want, idx.data(), d2.data());
    for (std::size_t i = 0; i < n; ++i)
      if (idx[i] < limit) found.emplace_back(d2[i], idx[i]);
  }
  for (std::size_t pos = indexed; pos < limit; ++pos) {  // newest entries, not yet in the tree
    const Eigen::Map<const Eigen::VectorXf> key(&m.keys[pos * m.dims], static_cast<Eigen::Index>(m.dims));
    found.emplace_back((key - ring_key).squaredNorm(), pos);
  }
  std::sort(found.begin(), found.end());
  if (found.size() > k) found.resize(k);
  std::vector<std::size_t> positions;
  positions.reserve(found.size());
  for (const auto& f : found) positions.push_back(f.second);
  return positions;
}

std::vector<DatabaseMatch> ScanContextDatabase::query(const ScanContext& query, std::size_t searchable) const {
  const Impl& m = *impl_;
  std::vector<DatabaseMatch> matches;
  for (const std::size_t pos :
       nearestRingKeys(query.ring_key, static_cast<std::size_t>(m.params.num_candidates), searchable)) {
    const DatabaseEntry& e = m.entries[pos];
    matches.push_back(DatabaseMatch{
        pos, e.id, scanContextDistance(query, e.descriptor, m.params.empty_columns, m.params.coarse_search_radius)});
  }
  std::sort(matches.begin(), matches.end(), [](const DatabaseMatch& a, const DatabaseMatch& b) {
    return a.match.distance != b.match.distance ? a.match.distance < b.match.distance : a.position < b.position;
  });
  return matches;
}

}  // namespace cosmo::place_recognition
