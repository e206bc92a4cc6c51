#pragma once
// The radio's payload store: the keyframe scans robots offered, kept until the radio delivers them. Both drivers
// hold one (TeamRun offline, the comm_broker node), so what a receiver gets is decided in one place:
// - compressing (the real size model, or a broker asked to send real xz payloads): the scan's x y z travel as an
//   xz stream (scan_compression.hpp), its compressed size is the payload size, and the receiver gets the
//   decompressed points stamped with the keyframe's stamp;
// - not compressing (the paper's size model f * S): the offered scan itself is delivered (xz is lossless, so its
//   decompressed copy would hold the same x y z), its payload size is the raw 12 bytes per point.
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "cosmo/common/scan.hpp"

namespace cosmo::comm {

class PayloadStore {
 public:
  explicit PayloadStore(bool compress, std::uint32_t xz_preset = 6);

  /// Sizes of an offered scan's payload: what the radio transfers, and the raw 12 bytes per point.
  struct Sizes {
    std::size_t payload = 0;
    std::size_t raw = 0;
  };
  /// An offered scan made ready to store: its xz payload when compressing (the costly part: pack() changes
  /// nothing, so a caller may run it outside its lock), else the scan itself.
  struct Payload {
    std::shared_ptr<const Scan> scan;  ///< not compressing: the offered scan
    std::vector<std::uint8_t> xz;      ///< compressing: the xz payload ...
    StampNs stamp = 0;                 ///< ... and the keyframe's stamp
    Sizes sizes;
  };
  /// Throws std::invalid_argument without a scan, std::runtime_error when it cannot be compressed.
  Payload pack(std::shared_ptr<const Scan> scan) const;
  /// Keeps `robot`'s keyframe `index` (replacing an earlier offer of it); returns its sizes.
  Sizes store(char robot, std::size_t index, Payload payload);
  /// pack() then store().
  Sizes offer(char robot, std::size_t index, std::shared_ptr<const Scan> scan) {
    return store(robot, index, pack(std::move(scan)));
  }
  /// The scan a receiver gets for `sender`'s keyframe `index`; nullptr when it was never offered. Throws
  /// std::runtime_error when a stored payload does not decompress.
  std::shared_ptr<const Scan> deliver(char sender, std::size_t index) const;

  bool compresses() const { return compress_; }
  std::size_t size() const { return items_.size(); }

 private:
  bool compress_;
  std::uint32_t xz_preset_;
  std::map<std::pair<char, std::size_t>, Payload> items_;
};

}  // namespace cosmo::comm
