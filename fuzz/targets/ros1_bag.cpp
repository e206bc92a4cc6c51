// ROS 1 bags (records, chunks none/bz2/lz4, indexes, connections) through cosmo's own reader, as the trials and
// the Nebula import read them: every connection's messages, clouds (PointCloud2, Livox CustomMsg) and pose graphs
// decoded, the trial span of a cloud topic, and the scan source with a decompression worker.
#include <memory>
#include <optional>

#include "../fuzz_target.hpp"
#include "../input_file.hpp"
#include "cosmo/nebula/ros1_serialization.hpp"
#include "cosmo/trials/ros1_bag.hpp"
#include "cosmo/trials/ros1_message_stream.hpp"
#include "cosmo/trials/ros1_point_cloud.hpp"
#include "cosmo/trials/trial_scans.hpp"

using namespace cosmo;

namespace {

/// The connection's cloud type, none for other types.
std::optional<trials::Ros1CloudType> cloudType(const trials::Ros1Connection& c) {
  try {
    return trials::ros1CloudType(c, "input");
  } catch (const std::runtime_error&) { return std::nullopt; }
}

void readConnection(const std::shared_ptr<const trials::Ros1Bag>& bag, const trials::Ros1Connection& c) {
  trials::Ros1MessageStream stream(bag, bag->messages({c.id}), 0);
  trials::Ros1MessageRef m;
  trials::Ros1Bag::Bytes bytes;
  Scan scan;
  trials::CloudLayout layout;
  const std::optional<trials::Ros1CloudType> type = cloudType(c);
  while (stream.next(m, bytes)) {
    try {
      if (type)
        trials::decodeRos1Cloud(*type, bytes.data, bytes.size, true, bag->path(), scan, layout);
      else if (c.type == "pose_graph_msgs/PoseGraph")
        nebula::decodePoseGraph(bytes.data, bytes.size);
    } catch (const std::runtime_error&) {  // a bad message; the container's next ones still read
    }
  }
}

}  // namespace

COSMO_FUZZ_TARGET(ros1_bag) {
  const std::string path = fuzz::inputFile(data, size, "input.bag");
  auto bag = std::make_shared<const trials::Ros1Bag>(path);
  bag->describeTopics();
  for (const auto& c : bag->connections()) readConnection(bag, c);
  for (const auto& c : bag->connections())
    if (cloudType(c)) {
      trials::readRos1TrialSpan(path, c.topic, 'a');
      trials::Ros1ScanSource source(path, c.topic, false, 1);
      Scan scan;
      while (source.next(scan)) {}
      break;
    }
}
