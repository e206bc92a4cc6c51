#include "cosmo/comm/payload_store.hpp"

#include <stdexcept>
#include <string>

#include "cosmo/comm/scan_compression.hpp"

namespace cosmo::comm {

PayloadStore::PayloadStore(bool compress, std::uint32_t xz_preset) : compress_(compress), xz_preset_(xz_preset) {
  if (xz_preset > 9)
    throw std::invalid_argument("payload store: xz preset must be in 0..9, got " + std::to_string(xz_preset));
}

PayloadStore::Payload PayloadStore::pack(std::shared_ptr<const Scan> scan) const {
  if (!scan) throw std::invalid_argument("payload store: an offered keyframe has no scan");
  Payload p;
  p.sizes.raw = rawPayloadBytes(*scan);
  if (compress_) {
    p.xz = compressScan(*scan, xz_preset_);
    p.stamp = scan->stamp;
    p.sizes.payload = p.xz.size();
  } else {
    p.scan = std::move(scan);
    p.sizes.payload = p.sizes.raw;
  }
  return p;
}

PayloadStore::Sizes PayloadStore::store(char robot, std::size_t index, Payload payload) {
  const Sizes sizes = payload.sizes;
  items_[{robot, index}] = std::move(payload);
  return sizes;
}

std::shared_ptr<const Scan> PayloadStore::deliver(char sender, std::size_t index) const {
  const auto it = items_.find({sender, index});
  if (it == items_.end()) return nullptr;
  const Payload& item = it->second;
  if (!compress_) return item.scan;
  Scan received = decompressScan(item.xz);
  received.stamp = item.stamp;
  return std::make_shared<const Scan>(std::move(received));
}

}  // namespace cosmo::comm
