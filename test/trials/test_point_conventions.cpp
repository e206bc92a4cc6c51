// Per-point time and ring of the LiDARs robots carry, decoded to the same Scan: the same sweep of points with
// known times written in Ouster's layout (`t` ns from the sweep start, `ring`), a split-time automotive layout
// (`time_sec` + `time_nsec` uint32, `laser_id`, point_step 32), Livox's PointCloud2 (`timestamp` float64 absolute
// ns, `line` uint8) and Hesai's (`timestamp` float64 absolute s), and a cloud with no time (named, not dewarped).
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "cosmo/trials/point_cloud_decode.hpp"

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
  EXPECT_EQ(pointConventions(w.layout).describe(), "time t (ns from the sweep start), ring ring");
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
  EXPECT_EQ(c.describe(), "time time_sec + time_nsec (absolute), no ring");
  expectKnownTimesAndRings(w.decode(), false);
}

TEST(PointConventions, LivoxAbsoluteNanosecondsInAFloat64AndItsLine) {
  Writer w(26);
  w.field("intensity", 12, PointType::Float32), w.field("tag", 16, PointType::UInt8);
  w.field("line", 17, PointType::UInt8), w.field("timestamp", 18, PointType::Float64);
  for (int i = 0; i < kPoints; ++i) {
    w.put(i, 17, static_cast<std::uint8_t>(i % 4));
    w.put(i, 18, static_cast<double>(pointStamp(i)));
  }
  EXPECT_EQ(pointConventions(w.layout).describe(), "time timestamp (s; absolute ns above 1e15), ring line");
  expectKnownTimesAndRings(w.decode());
}

TEST(PointConventions, HesaiAbsoluteSecondsInAFloat64) {
  Writer w(24);
  w.field("timestamp", 12, PointType::Float64), w.field("ring", 20, PointType::UInt16);
  for (int i = 0; i < kPoints; ++i) {
    w.put(i, 12, static_cast<double>(pointStamp(i) / 1000000000ULL) + (pointStamp(i) % 1000000000ULL) * 1e-9);
    w.put(i, 20, static_cast<std::uint16_t>(i % 4));
  }
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
