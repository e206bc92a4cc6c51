// Per-point time and ring of the LiDARs robots carry, decoded to the same Scan: the same sweep of points with
// known times written in Ouster's layout (`t` ns from the sweep start, `ring`), a split-time automotive layout
// (`time_sec` + `time_nsec` uint32, `laser_id`, point_step 32), Livox's PointCloud2 (`timestamp` float64 absolute
// ns, `line` uint8) and Hesai's (`timestamp` float64 absolute s), Livox's CustomMsg (`timebase` + `offset_time` ns,
// `line`; its definition told by its md5sum), and a cloud with no time (named, not dewarped); the simulator's
// writer of each layout (trials/point_layouts.hpp) decodes to the scan it was given.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "cosmo/trials/point_cloud_decode.hpp"
#include "cosmo/trials/point_layouts.hpp"
#include "cosmo/trials/ros1_bag.hpp"
#include "cosmo/trials/ros1_point_cloud.hpp"

using namespace cosmo;
using namespace cosmo::trials;

namespace {

constexpr StampNs kStamp = 1700000000'100000000ULL;  // the sweep end
constexpr int kPoints = 8;

/// Point i is measured at kStamp - (kPoints - 1 - i) * 10 ms, on ring i % 4.
StampNs pointStamp(int i) { return kStamp - static_cast<StampNs>(kPoints - 1 - i) * 10'000'000ULL; }

struct Writer {
  CloudLayout layout;
  std::vector<std::uint8_t> data;
  /// Points with x y z (float32 at 0/4/8) already written; the test adds its time and ring fields.
  explicit Writer(std::uint32_t point_step) {
    layout.stamp = kStamp;
    layout.width = kPoints;
    layout.point_step = point_step;
    layout.row_step = point_step * kPoints;
    data.assign(static_cast<std::size_t>(point_step) * kPoints, 0);
    field("x", 0, PointType::Float32), field("y", 4, PointType::Float32), field("z", 8, PointType::Float32);
    for (int i = 0; i < kPoints; ++i) put(i, 0, 1.0f + i), put(i, 4, 2.0f), put(i, 8, 0.5f);
  }
  void field(const std::string& name, std::uint32_t offset, PointType type) {
    layout.fields.push_back({name, offset, static_cast<std::uint8_t>(type), 1});
  }
  template <typename T>
  void put(int i, std::uint32_t offset, T v) {
    std::memcpy(&data[static_cast<std::size_t>(i) * layout.point_step + offset], &v, sizeof v);
  }
  Scan decode() const {
    Scan scan;
    decodeCloud(layout, data.data(), data.size(), true, "test", scan);
    return scan;
  }
};

void expectKnownTimesAndRings(const Scan& scan, bool rings = true) {
  ASSERT_EQ(scan.points.size(), static_cast<std::size_t>(kPoints));
  EXPECT_EQ(scan.stamp, kStamp);
  ASSERT_EQ(scan.time.size(), static_cast<std::size_t>(kPoints));
  for (int i = 0; i < kPoints; ++i) EXPECT_NEAR(scan.time[i], -(kPoints - 1 - i) * 0.01, 1e-6) << i;
  if (!rings) return;
  ASSERT_EQ(scan.ring.size(), static_cast<std::size_t>(kPoints));
  for (int i = 0; i < kPoints; ++i) EXPECT_EQ(scan.ring[i], i % 4) << i;
}

}  // namespace

TEST(PointConventions, OusterNanosecondsFromTheSweepStart) {
  Writer w(24);
  w.field("t", 12, PointType::UInt32), w.field("ring", 16, PointType::UInt16);
  for (int i = 0; i < kPoints; ++i) {
    w.put(i, 12, static_cast<std::uint32_t>(pointStamp(i) - pointStamp(0)));
    w.put(i, 16, static_cast<std::uint16_t>(i % 4));
  }
  expectKnownTimesAndRings(w.decode());
  EXPECT_EQ(pointConventions(w.layout).describe(), "Ouster layout: time t (ns from the sweep start), ring ring");
}

TEST(PointConventions, SplitSecondsAndNanosecondsOfAnAutomotiveLidar) {
  Writer w(32);
  w.field("intensity", 16, PointType::Float32), w.field("time_sec", 20, PointType::UInt32);
  w.field("time_nsec", 24, PointType::UInt32), w.field("laser_id", 28, PointType::UInt16);
  for (int i = 0; i < kPoints; ++i) {
    w.put(i, 20, static_cast<std::uint32_t>(pointStamp(i) / 1000000000ULL));
    w.put(i, 24, static_cast<std::uint32_t>(pointStamp(i) % 1000000000ULL));
  }
  const PointConventions c = pointConventions(w.layout);
  EXPECT_EQ(c.time_kind, PointConventions::Time::SplitAbsolute);
  EXPECT_EQ(c.describe(), "split-time layout: time time_sec + time_nsec (absolute), ring laser_id");
  for (int i = 0; i < kPoints; ++i) w.put(i, 28, static_cast<std::uint16_t>(i % 4));
  expectKnownTimesAndRings(w.decode());
}

TEST(PointConventions, LivoxAbsoluteNanosecondsInAFloat64AndItsLine) {
  Writer w(26);
  w.field("intensity", 12, PointType::Float32), w.field("tag", 16, PointType::UInt8);
  w.field("line", 17, PointType::UInt8), w.field("timestamp", 18, PointType::Float64);
  for (int i = 0; i < kPoints; ++i) {
    w.put(i, 17, static_cast<std::uint8_t>(i % 4));
    w.put(i, 18, static_cast<double>(pointStamp(i)));
  }
  EXPECT_EQ(pointConventions(w.layout).describe(),
            "Livox PointCloud2 layout: time timestamp (s; absolute ns above 1e15), ring line");
  expectKnownTimesAndRings(w.decode());
}

TEST(PointConventions, HesaiAbsoluteSecondsInAFloat64) {
  Writer w(24);
  w.field("timestamp", 12, PointType::Float64), w.field("ring", 20, PointType::UInt16);
  for (int i = 0; i < kPoints; ++i) {
    w.put(i, 12, static_cast<double>(pointStamp(i) / 1000000000ULL) + (pointStamp(i) % 1000000000ULL) * 1e-9);
    w.put(i, 20, static_cast<std::uint16_t>(i % 4));
  }
  EXPECT_EQ(pointConventions(w.layout).layout, "Hesai / Robosense");
  expectKnownTimesAndRings(w.decode());
}

TEST(PointConventions, ACloudWithoutTimesIsNamedAsNotDewarped) {
  Writer w(12);
  EXPECT_EQ(pointConventions(w.layout).describe(), "no per-point time (not dewarped), no ring");
  EXPECT_TRUE(w.decode().time.empty());
  // Half of a split time is no time.
  w.field("time_sec", 8, PointType::UInt32);
  EXPECT_EQ(pointConventions(w.layout).time_kind, PointConventions::Time::None);
}

namespace {

/// The sweep of the tests above as a Scan: stamped at its end, point i at -(kPoints - 1 - i) * 10 ms on ring i % 4.
Scan knownScan() {
  Scan s;
  s.stamp = kStamp;
  for (int i = 0; i < kPoints; ++i) {
    s.points.emplace_back(1.0f + i, 2.0f, 0.5f);
    s.intensity.push_back(10.0f * i);
    s.time.push_back(static_cast<float>(-(kPoints - 1 - i) * 0.01));
    s.ring.push_back(static_cast<std::uint16_t>(i % 4));
  }
  return s;
}

}  // namespace

TEST(PointConventions, LivoxCustomMsgTimebasePlusOffsetTime) {
  const std::vector<std::uint8_t> msg = serializeLivoxCustomMsg(knownScan(), "livox_frame");
  // header (4 + 8 + 4 + 11), timebase 8, point_num 4, lidar_id 1, rsvd 3, count 4, 8 points of 19 bytes
  EXPECT_EQ(msg.size(), 27u + 8 + 4 + 1 + 3 + 4 + 8 * 19);
  const CloudView view = parseLivoxCustomMsg(msg.data(), msg.size(), "test");
  EXPECT_EQ(view.layout.time_base, pointStamp(0));  // the first point's time
  EXPECT_EQ(view.layout.frame_id, "livox_frame");
  const PointConventions c = pointConventions(view.layout);
  EXPECT_EQ(c.time_kind, PointConventions::Time::BaseOffset);
  EXPECT_EQ(c.describe(), "Livox CustomMsg layout: time timebase + offset_time (ns, absolute), ring line");
  Scan scan;
  CloudLayout layout;
  decodeRos1Cloud(Ros1CloudType::LivoxCustomMsg, msg.data(), msg.size(), true, "test", scan, layout);
  expectKnownTimesAndRings(scan);
  EXPECT_EQ(scan.points[3], Eigen::Vector3f(4.0f, 2.0f, 0.5f));
  // Real drivers stamp the header at timebase (the sweep start): the stamp is kept, the times follow it.
  std::vector<std::uint8_t> start_stamped = msg;
  const auto sec = static_cast<std::uint32_t>(pointStamp(0) / 1000000000ULL);
  const auto nsec = static_cast<std::uint32_t>(pointStamp(0) % 1000000000ULL);
  std::memcpy(&start_stamped[4], &sec, 4);
  std::memcpy(&start_stamped[8], &nsec, 4);
  decodeRos1Cloud(Ros1CloudType::LivoxCustomMsg, start_stamped.data(), start_stamped.size(), false, "test", scan,
                  layout);
  EXPECT_EQ(scan.stamp, pointStamp(0));
  for (int i = 0; i < kPoints; ++i) EXPECT_NEAR(scan.time[i], i * 0.01, 1e-6) << i;
}

TEST(PointConventions, AMalformedLivoxCustomMsgIsNamed) {
  std::vector<std::uint8_t> msg = serializeLivoxCustomMsg(knownScan(), "f");
  const std::size_t count_at = 4 + 8 + 4 + 1 + 8 + 4 + 1 + 3;
  auto fails = [](const std::vector<std::uint8_t>& m) -> std::string {
    try {
      parseLivoxCustomMsg(m.data(), m.size(), "bag.bag /livox/lidar");
    } catch (const std::runtime_error& e) { return e.what(); }
    return "";
  };
  std::vector<std::uint8_t> cut(msg.begin(), msg.end() - 5);
  EXPECT_NE(fails(cut).find("bag.bag /livox/lidar: malformed livox_ros_driver/CustomMsg at points"), std::string::npos)
      << fails(cut);
  msg[count_at - 8] = 7;  // point_num says 7
  EXPECT_NE(fails(msg).find("holds 8 points, point_num says 7"), std::string::npos) << fails(msg);
}

TEST(PointConventions, LivoxCustomMsgIsToldByItsTypeAndMd5sum) {
  Ros1Connection c;
  c.type = "sensor_msgs/PointCloud2";
  EXPECT_EQ(ros1CloudType(c, "b /t"), Ros1CloudType::PointCloud2);
  for (const char* type : {"livox_ros_driver/CustomMsg", "livox_ros_driver2/CustomMsg"}) {
    c.type = type;
    c.md5sum = kLivoxCustomMsgMd5;
    EXPECT_EQ(ros1CloudType(c, "b /t"), Ros1CloudType::LivoxCustomMsg);
  }
  // The first driver's definition (timestep, points without offset_time and tag): refused, named.
  c.type = "livox_ros_driver/CustomMsg";
  c.md5sum = "a3e5532e86bb82ac2085ba9c8e7e4e45";
  try {
    ros1CloudType(c, "old.bag /livox/lidar");
    ADD_FAILURE() << "an older definition was accepted";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("old.bag /livox/lidar: message type livox_ros_driver/CustomMsg with md5sum "
                        "a3e5532e86bb82ac2085ba9c8e7e4e45 is another definition"),
              std::string::npos)
        << what;
  }
  c.type = "sensor_msgs/Image";
  EXPECT_THROW(ros1CloudType(c, "b /t"), std::runtime_error);
}

// Each layout the simulator writes decodes to the scan it was given: the same points, rings and times (to the
// rounding of each layout's time type).
TEST(PointConventions, EachSimulatedLayoutDecodesToTheScanWritten) {
  const Scan truth = knownScan();
  for (PointLayout layout : {PointLayout::Velodyne, PointLayout::Hesai, PointLayout::Livox, PointLayout::SplitTime}) {
    SCOPED_TRACE(pointLayoutName(layout));
    EXPECT_EQ(parsePointLayout(pointLayoutName(layout)), layout);
    const RawCloud cloud = pointLayoutCloud(truth, layout, "lidar");
    Scan scan;
    decodeCloud(cloud.layout, cloud.data.data(), cloud.data.size(), true, "test", scan);
    expectKnownTimesAndRings(scan);
    EXPECT_EQ(scan.points, truth.points);
  }
  EXPECT_EQ(pointLayoutNames(), "ouster|velodyne|hesai|livox|livox-custom|split-time");
  EXPECT_FALSE(parsePointLayout("pandar"));
  EXPECT_THROW(pointLayoutCloud(truth, PointLayout::Ouster, "lidar"), std::invalid_argument);
}
