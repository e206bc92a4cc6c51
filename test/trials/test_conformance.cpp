// Bags that other tools wrote, read by cosmo's ROS 1 bag reader (trials/ros1_bag.hpp) and by Debian's librosbag
// (the reference): the same messages in the same order — topic, connection (type, md5sum, definition), receive
// time and bytes — for the bags of ../shared/data/conformance (embag's and rosbag.js's fixtures, see its README) and
// the bags Python's rosbag wrote in test/trials/data/conformance (scripts/conformance_bags.py: every compression with
// tiny chunks, writes out of time order, an empty `latching=` value, connection records repeated per chunk, a
// definition that does not match its md5sum, messages at time 0, Livox's CustomMsg and its older definition). The
// CustomMsg bag also decodes to the sweeps it holds; the older definition is refused, named.
#include <gtest/gtest.h>
#include <ros/serialization.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cosmo/common/shared_data.hpp"
#include "cosmo/trials/ros1_bag.hpp"
#include "cosmo/trials/trial_scans.hpp"

using namespace cosmo;
namespace fs = std::filesystem;

namespace {

struct Message {
  std::string topic;
  std::string connection;  ///< its connection: type, md5sum and message definition
  StampNs received = 0;
  std::vector<std::uint8_t> bytes;
  bool operator==(const Message& o) const {
    return topic == o.topic && connection == o.connection && received == o.received && bytes == o.bytes;
  }
};

std::vector<Message> readByLibrosbag(const std::string& path) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  rosbag::View view(bag);
  std::vector<Message> out;
  for (const rosbag::MessageInstance& m : view) {
    Message msg;
    msg.topic = m.getTopic();
    const auto header = m.getConnectionHeader();
    msg.connection = header->at("type") + " " + header->at("md5sum") + "\n" + m.getMessageDefinition();
    msg.received = m.getTime().toNSec();
    msg.bytes.resize(m.size());
    ros::serialization::OStream stream(msg.bytes.data(), static_cast<std::uint32_t>(msg.bytes.size()));
    m.write(stream);
    out.push_back(std::move(msg));
  }
  return out;
}

std::vector<Message> readByCosmo(const std::string& path) {
  const trials::Ros1Bag bag(path);
  std::vector<std::uint32_t> ids;
  for (const auto& c : bag.connections()) ids.push_back(c.id);
  std::vector<Message> out;
  std::map<std::uint32_t, std::vector<std::uint8_t>> chunks;
  for (const trials::Ros1MessageRef& ref : bag.messages(ids)) {
    auto& chunk = chunks[ref.chunk];
    if (chunk.empty()) bag.readChunk(ref.chunk, chunk);
    const auto data = bag.messageData(ref, chunk);
    Message msg;
    msg.topic = bag.connection(ref.connection).topic;
    const trials::Ros1Connection& c = bag.connection(ref.connection);
    msg.connection = c.type + " " + c.md5sum + "\n" + c.definition;
    msg.received = ref.received;
    msg.bytes.assign(data.data, data.data + data.size);
    out.push_back(std::move(msg));
  }
  return out;
}

std::vector<std::string> bagsIn(const std::string& dir) {
  std::vector<std::string> out;
  if (!fs::is_directory(dir)) return out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".bag") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

/// Both readers on `path`: the same messages; returns how many.
std::size_t expectSameMessages(const std::string& path) {
  const std::vector<Message> reference = readByLibrosbag(path);
  std::vector<Message> ours;
  try {
    ours = readByCosmo(path);
  } catch (const std::exception& e) {
    ADD_FAILURE() << path << ": cosmo's reader refused what librosbag reads: " << e.what();
    return 0;
  }
  EXPECT_EQ(ours.size(), reference.size()) << path;
  for (std::size_t i = 0; i < std::min(ours.size(), reference.size()); ++i) {
    if (ours[i] == reference[i]) continue;
    ADD_FAILURE() << path << ": message " << i << " differs: ours " << ours[i].topic << " at " << ours[i].received
                  << " ns, " << ours[i].bytes.size() << " bytes, connection " << ours[i].connection.substr(0, 60)
                  << "; librosbag " << reference[i].topic << " at " << reference[i].received << " ns, "
                  << reference[i].bytes.size() << " bytes, connection " << reference[i].connection.substr(0, 60);
    break;
  }
  return reference.size();
}

}  // namespace

TEST(TrialsConformance, BagsOtherToolsWroteReadAsLibrosbagReadsThem) {
  const auto dir = sharedPath("data/conformance");
  if (!dir) GTEST_SKIP() << "no ../shared/data/conformance (COSMO_SHARED_DIR)";
  const auto bags = bagsIn(*dir);
  ASSERT_GE(bags.size(), 6u) << *dir;
  std::size_t messages = 0;
  for (const auto& bag : bags) {
    const std::size_t n = expectSameMessages(bag);
    std::printf("[conformance] %s: %zu messages, same in both readers\n", fs::path(bag).filename().c_str(), n);
    messages += n;
  }
  EXPECT_GT(messages, 8000u);  // rosbag.js's example alone holds 8,647
}

TEST(TrialsConformance, BagsPythonsRosbagWroteReadAsLibrosbagReadsThem) {
  const auto bags = bagsIn(std::string(COSMO_SOURCE_DIR) + "/test/trials/data/conformance");
  ASSERT_GE(bags.size(), 11u);
  for (const auto& bag : bags) {
    const std::size_t n = expectSameMessages(bag);
    std::printf("[conformance] %s: %zu messages, same in both readers\n", fs::path(bag).filename().c_str(), n);
    EXPECT_GT(n, 0u) << bag;
  }
}

TEST(TrialsConformance, ARecordingOfNothingIsReadAsOne) {
  const auto bag = sharedPath("data/conformance/rosbagjs_no-messages.bag");
  if (!bag) GTEST_SKIP() << "no ../shared/data/conformance (COSMO_SHARED_DIR)";
  const trials::Ros1Bag ours(*bag);
  EXPECT_TRUE(ours.connections().empty());
  EXPECT_TRUE(ours.chunks().empty());
  EXPECT_TRUE(readByLibrosbag(*bag).empty());
}

TEST(TrialsConformance, ALivoxCustomMsgBagDecodesToItsSweeps) {
  const std::string dir = std::string(COSMO_SOURCE_DIR) + "/test/trials/data/conformance/";
  trials::Ros1ScanSource source(dir + "py_livox_custom.bag", "livox/lidar", false);
  ASSERT_EQ(source.size(), 5u);
  Scan scan;
  for (int k = 0; k < 5; ++k) {
    ASSERT_TRUE(source.next(scan));
    // stamped at timebase (the sweep start), kept: point i at +25 ms * i
    EXPECT_EQ(scan.stamp, 1700000000'000000000ULL + 100000000ULL * k);
    ASSERT_EQ(scan.size(), 4u);
    for (int i = 0; i < 4; ++i) {
      EXPECT_EQ(scan.points[i], Eigen::Vector3f(1.0f + k + i, -i, 0.5f * i));
      EXPECT_NEAR(scan.time[i], 0.025 * i, 1e-7);
      EXPECT_EQ(scan.ring[i], i % 4);
    }
    EXPECT_EQ(trials::pointConventions(source.lastLayout()).layout, "Livox CustomMsg");
  }
  EXPECT_FALSE(source.next(scan));
  try {
    trials::Ros1ScanSource old(dir + "py_livox_custom_old.bag", "/livox/lidar");
    ADD_FAILURE() << "the older definition was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("py_livox_custom_old.bag /livox/lidar: message type "
                                         "livox_ros_driver/CustomMsg with md5sum a3e5532e86bb82ac2085ba9c8e7e4e45 is "
                                         "another definition"),
              std::string::npos)
        << e.what();
  }
}
