// sensor_msgs/PointCloud2 <-> Scan (src/ros/point_cloud.cpp): field types, per-point time conventions, errors.
#include <gtest/gtest.h>

#include <cstring>

#include "cosmo/ros/point_cloud.hpp"

namespace {

using cosmo::Scan;
using cosmo::ros_glue::fromPointCloud2;
using cosmo::ros_glue::PointTimeEncoding;
using cosmo::ros_glue::toPointCloud2;

Scan sweep(std::size_t n) {
  Scan s;
  s.stamp = 1700000000123456789ULL;
  for (std::size_t i = 0; i < n; ++i) {
    s.points.emplace_back(0.5f * i, -0.25f * i, 0.125f * i - 3.0f);
    s.intensity.push_back(static_cast<float>(i % 7));
    s.ring.push_back(static_cast<uint16_t>(i % 64));
    s.time.push_back(-0.1f + 0.1f * static_cast<float>(i) / static_cast<float>(n - 1));  // latest point at 0
  }
  return s;
}

/// A cloud with the given fields (name, datatype, size), packed in that order, filled by `fill(point, field)`.
struct FieldSpec {
  const char* name;
  uint8_t type;
  uint32_t size;
};
template <typename Fill>
sensor_msgs::PointCloud2 packed(std::size_t n, std::vector<FieldSpec> specs, Fill fill) {
  sensor_msgs::PointCloud2 m;
  m.header.stamp.sec = 1700000000;
  m.header.stamp.nsec = 500000000;
  m.height = 1;
  m.width = static_cast<uint32_t>(n);
  for (const auto& f : specs) {
    sensor_msgs::PointField pf;
    pf.name = f.name;
    pf.offset = m.point_step;
    pf.datatype = f.type;
    pf.count = 1;
    m.fields.push_back(pf);
    m.point_step += f.size;
  }
  m.row_step = m.point_step * m.width;
  m.data.resize(m.row_step);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < specs.size(); ++k) fill(m.data.data() + i * m.point_step + m.fields[k].offset, i, k);
  return m;
}

TEST(PointCloud, RelativeSecondsRoundTripIsBitExact) {
  const Scan s = sweep(500);
  const Scan r = fromPointCloud2(toPointCloud2(s, "lidar", PointTimeEncoding::RelativeSeconds));
  ASSERT_EQ(r.size(), s.size());
  EXPECT_EQ(r.stamp, s.stamp);
  for (std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_EQ(r.points[i], s.points[i]);
    EXPECT_EQ(r.time[i], s.time[i]);
    EXPECT_EQ(r.ring[i], s.ring[i]);
    EXPECT_EQ(r.intensity[i], s.intensity[i]);
  }
}

TEST(PointCloud, OusterNanosecondsAreSecondsBeforeTheStamp) {
  const Scan s = sweep(300);
  const Scan r = fromPointCloud2(toPointCloud2(s, "lidar", PointTimeEncoding::OusterNs));
  ASSERT_TRUE(r.hasTime());
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_NEAR(r.time[i], s.time[i], 2e-8);
  EXPECT_EQ(r.time.back(), 0.0f);
  // stamped at the sweep start: the decode moves the scan's stamp to the sweep end (header + one sweep), so the
  // points keep their times before it, exactly as the end-stamped decode gives them
  const Scan start = fromPointCloud2(toPointCloud2(s, "lidar", PointTimeEncoding::OusterNs), false);
  ASSERT_EQ(start.size(), r.size());
  EXPECT_NEAR(start.time.front(), r.time.front(), 1e-6);
  EXPECT_NEAR(start.time.back(), 0.0f, 1e-6);
  EXPECT_NEAR(static_cast<double>(start.stamp - r.stamp), 0.1e9, 1e3);
}

TEST(PointCloud, AbsoluteEpochTimesKeepMicroseconds) {
  // Velodyne-style float64 `time` in epoch seconds, 0.1 s sweep ending 1 ms after the stamp.
  const std::size_t n = 1000;
  const double stamp = 1700000000.5;
  auto m = packed(n,
                  {{"x", sensor_msgs::PointField::FLOAT64, 8},
                   {"y", sensor_msgs::PointField::FLOAT64, 8},
                   {"z", sensor_msgs::PointField::FLOAT64, 8},
                   {"time", sensor_msgs::PointField::FLOAT64, 8}},
                  [&](uint8_t* p, std::size_t i, std::size_t k) {
                    const double v = k < 3 ? 1.0 + k + 0.001 * i : stamp - 0.099 + 0.1 * i / (n - 1);
                    std::memcpy(p, &v, 8);
                  });
  const Scan r = fromPointCloud2(m);
  ASSERT_TRUE(r.hasTime());
  for (std::size_t i = 0; i < n; i += 97) {
    EXPECT_NEAR(r.time[i], -0.099 + 0.1 * i / (n - 1), 1e-6) << i;
    EXPECT_NEAR(r.points[i].y(), 2.0 + 0.001 * i, 1e-5);
  }
  EXPECT_FALSE(r.hasRing());
  EXPECT_FALSE(r.hasIntensity());
}

TEST(PointCloud, IntegerAndNarrowFieldsConvert) {
  auto m = packed(4,
                  {{"x", sensor_msgs::PointField::FLOAT32, 4},
                   {"y", sensor_msgs::PointField::FLOAT32, 4},
                   {"z", sensor_msgs::PointField::FLOAT32, 4},
                   {"intensity", sensor_msgs::PointField::UINT8, 1},
                   {"ring", sensor_msgs::PointField::INT16, 2}},
                  [](uint8_t* p, std::size_t i, std::size_t k) {
                    if (k < 3) {
                      const float v = -1.5f * (i + 1);
                      std::memcpy(p, &v, 4);
                    }
                    if (k == 3) *p = static_cast<uint8_t>(200 + i);
                    if (k == 4) {
                      const int16_t v = static_cast<int16_t>(i == 3 ? -2 : 30 + i);
                      std::memcpy(p, &v, 2);
                    }
                  });
  const Scan r = fromPointCloud2(m);
  ASSERT_EQ(r.size(), 4u);
  EXPECT_EQ(r.points[2].z(), -4.5f);
  EXPECT_EQ(r.intensity[3], 203.0f);
  EXPECT_EQ(r.ring[1], 31);
  EXPECT_EQ(r.ring[3], 0);  // negative ring clamped, not wrapped
  EXPECT_FALSE(r.hasTime());
}

TEST(PointCloud, DecodingIntoAUsedScanReplacesEveryField) {
  // The bag reader (trials::Ros1ScanSource) decodes each message into the caller's Scan: a cloud without intensity, ring and time must
  // not leave the previous scan's fields behind.
  Scan s = fromPointCloud2(toPointCloud2(sweep(50), "lidar"));
  ASSERT_TRUE(s.hasTime() && s.hasRing() && s.hasIntensity());
  auto m = packed(3,
                  {{"x", sensor_msgs::PointField::FLOAT32, 4},
                   {"y", sensor_msgs::PointField::FLOAT32, 4},
                   {"z", sensor_msgs::PointField::FLOAT32, 4}},
                  [](uint8_t* p, std::size_t i, std::size_t k) {
                    const float v = 1.0f * i + k;
                    std::memcpy(p, &v, 4);
                  });
  cosmo::ros_glue::decodePointCloud2(m, m.data.data(), m.data.size(), true, "test", s);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s.points[2], Eigen::Vector3f(2.0f, 3.0f, 4.0f));
  EXPECT_EQ(s.stamp, 1700000000500000000ULL);
  EXPECT_TRUE(s.time.empty());
  EXPECT_TRUE(s.ring.empty());
  EXPECT_TRUE(s.intensity.empty());
  // The point bytes are read from `data`, not from the message's own (empty) vector.
  sensor_msgs::PointCloud2 meta = m;
  meta.data.clear();
  cosmo::ros_glue::decodePointCloud2(meta, m.data.data(), m.data.size(), true, "test", s);
  EXPECT_EQ(s.points[1], Eigen::Vector3f(1.0f, 2.0f, 3.0f));
  EXPECT_THROW(cosmo::ros_glue::decodePointCloud2(meta, m.data.data(), m.data.size() - 1, true, "test", s),
               std::runtime_error);
}

TEST(PointCloud, BadCloudsNameTheSourceAndField) {
  auto no_z = packed(2, {{"x", sensor_msgs::PointField::FLOAT32, 4}, {"y", sensor_msgs::PointField::FLOAT32, 4}},
                     [](uint8_t*, std::size_t, std::size_t) {});
  try {
    fromPointCloud2(no_z, true, "/a/points");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/a/points"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("x/y/z"), std::string::npos) << e.what();
  }
  auto short_data = toPointCloud2(sweep(10), "lidar");
  short_data.data.resize(short_data.data.size() - 1);
  EXPECT_THROW(fromPointCloud2(short_data, true, "/b/points"), std::runtime_error);
  auto outside = toPointCloud2(sweep(10), "lidar");
  outside.fields.back().offset = outside.point_step;  // ring beyond the point
  try {
    fromPointCloud2(outside, true, "/c/points");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'ring'"), std::string::npos) << e.what();
  }
}

}  // namespace
