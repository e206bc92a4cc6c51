// CDR sensor_msgs/msg/PointCloud2 (trials/cdr_point_cloud.hpp) and the shared cloud decode
// (trials/point_cloud_decode.hpp): layout, per-point times, invalid returns dropped, malformed messages.
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>

#include "cosmo/trials/cdr_point_cloud.hpp"
#include "cosmo/trials/ouster_cloud.hpp"

using namespace cosmo;
using namespace cosmo::trials;

namespace {

/// A 4 x 8 sweep: every third pixel has no return; ring = beam, time = column time before the last column.
Scan simulatedSweep(const OusterSweep& sw, StampNs stamp) {
  Scan s;
  s.stamp = stamp;
  for (int b = 0; b < sw.beams; ++b)
    for (int c = 0; c < sw.columns; ++c) {
      if ((b * sw.columns + c) % 3 == 0) continue;
      s.points.emplace_back(1.0f + b, 0.5f * c, -0.25f * b);
      s.intensity.push_back(static_cast<float>(10 * b + c));
      s.ring.push_back(static_cast<std::uint16_t>(b));
      s.time.push_back(static_cast<float>(-(sw.columns - 1 - c) / (sw.columns * sw.rate_hz)));
    }
  return s;
}

OusterSweep smallSweep(bool at_end) {
  OusterSweep sw;
  sw.beams = 4;
  sw.columns = 8;
  sw.rate_hz = 10.0;
  sw.stamp_at_end = at_end;
  sw.ring_uint16 = !at_end;
  return sw;
}

std::string errorOf(const std::vector<std::uint8_t>& m) {
  try {
    Scan s;
    decodeCdrPointCloud2(m.data(), m.size(), true, "bag robot1/ouster/points", s);
  } catch (const std::runtime_error& e) { return e.what(); }
  return "";
}

}  // namespace

TEST(CdrPointCloud, EncodeParseRoundTripKeepsTheLayout) {
  const OusterSweep sw = smallSweep(false);
  const RawCloud cloud = organisedOusterCloud(simulatedSweep(sw, 1700000000500000000ULL), sw);
  const auto cdr = encodeCdrPointCloud2(cloud);
  ASSERT_GE(cdr.size(), 4u);
  EXPECT_EQ(cdr[0], 0x00);
  EXPECT_EQ(cdr[1], 0x01);
  const CloudView v = parseCdrPointCloud2(cdr.data(), cdr.size(), "test");
  EXPECT_EQ(v.layout.stamp, cloud.layout.stamp);
  EXPECT_EQ(v.layout.frame_id, "os_sensor");
  EXPECT_EQ(v.layout.height, 4u);
  EXPECT_EQ(v.layout.width, 8u);
  EXPECT_EQ(v.layout.point_step, 48u);
  EXPECT_EQ(v.layout.row_step, 48u * 8u);
  ASSERT_EQ(v.layout.fields.size(), cloud.layout.fields.size());
  for (std::size_t k = 0; k < v.layout.fields.size(); ++k) {
    EXPECT_EQ(v.layout.fields[k].name, cloud.layout.fields[k].name);
    EXPECT_EQ(v.layout.fields[k].offset, cloud.layout.fields[k].offset);
    EXPECT_EQ(v.layout.fields[k].datatype, cloud.layout.fields[k].datatype);
  }
  EXPECT_EQ(describeFields(v.layout),
            "x:float32@0 y:float32@4 z:float32@8 intensity:float32@16 t:uint32@20 reflectivity:uint16@24 "
            "ring:uint16@26 ambient:uint16@28 range:uint32@32");
  ASSERT_EQ(v.bytes, cloud.data.size());
  EXPECT_EQ(std::memcmp(v.data, cloud.data.data(), v.bytes), 0);
}

TEST(CdrPointCloud, HandEncodedMessageHasTheDocumentedAlignment) {
  // header: sec 7, nanosec 9, frame "ab" (len 3 incl. NUL), then height at offset 4+4+4+4+3 -> aligned to 16
  RawCloud c;
  c.layout.stamp = 7000000009ULL;
  c.layout.frame_id = "ab";
  c.layout.height = 1;
  c.layout.width = 0;
  c.layout.fields = {{"x", 0, 7, 1}};
  c.layout.point_step = 4;
  const auto m = encodeCdrPointCloud2(c);
  const std::vector<std::uint8_t> expected = {0, 1, 0, 0,                  // encapsulation
                                              7, 0, 0, 0, 9,   0,   0, 0,  // stamp
                                              3, 0, 0, 0, 'a', 'b', 0, 0,  // frame_id + 1 pad byte
                                              1, 0, 0, 0, 0,   0,   0, 0,  // height, width
                                              1, 0, 0, 0,                  // 1 field
                                              2, 0, 0, 0, 'x', 0,   0, 0,  // name "x" + 2 pad
                                              0, 0, 0, 0, 7,   0,   0, 0,  // offset 0, datatype 7 + 3 pad
                                              1, 0, 0, 0,                  // count
                                              0, 0, 0, 0,                  // is_bigendian + 3 pad
                                              4, 0, 0, 0, 0,   0,   0, 0,  // point_step, row_step
                                              0, 0, 0, 0,                  // data length 0
                                              0};                          // is_dense
  EXPECT_EQ(m, expected);
}

TEST(CdrPointCloud, StartStampedOusterCloudDecodesToItsTruth) {
  const OusterSweep sw = smallSweep(false);
  const StampNs sim_stamp = 1700000000500000000ULL;
  const Scan truth = simulatedSweep(sw, sim_stamp);
  const auto cdr = encodeCdrPointCloud2(organisedOusterCloud(truth, sw));
  Scan s;
  const DecodeCounts n = decodeCdrPointCloud2(cdr.data(), cdr.size(), false, "test", s);
  EXPECT_EQ(n.points, 32u);
  EXPECT_EQ(n.invalid, 32u - truth.size());
  ASSERT_EQ(s.size(), truth.size());
  // Header at the sweep start (the first column's time); the scan is stamped at the sweep end, one column past
  // the last: start + period.
  const double column = 1.0 / (sw.columns * sw.rate_hz);
  EXPECT_NEAR(static_cast<double>(s.stamp), static_cast<double>(sim_stamp + toStampNs(column)), 2.0);
  for (std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_EQ(s.points[i], truth.points[i]);
    EXPECT_EQ(s.ring[i], truth.ring[i]);
    EXPECT_EQ(s.intensity[i], truth.intensity[i]);
    const double abs_decoded = toSeconds(s.stamp - 1700000000000000000ULL) + s.time[i];
    const double abs_truth = toSeconds(sim_stamp - 1700000000000000000ULL) + truth.time[i];
    EXPECT_NEAR(abs_decoded, abs_truth, 1e-8) << i;
    EXPECT_LE(s.time[i], 0.0f);
  }
}

TEST(CdrPointCloud, EndStampedOrganisedCloudPutsPointsAtStampMinusPeriodPlusT) {
  const OusterSweep sw = smallSweep(true);
  const StampNs sim_stamp = 1700000000500000000ULL;
  const Scan truth = simulatedSweep(sw, sim_stamp);
  const RawCloud cloud = organisedOusterCloud(truth, sw);
  Scan s;
  decodeCloud(cloud.layout, cloud.data.data(), cloud.data.size(), true, "test", s);
  ASSERT_EQ(s.size(), truth.size());
  // The header is the sweep end, one column after the last column's time.
  const double column = 1.0 / (sw.columns * sw.rate_hz);
  EXPECT_EQ(s.stamp, sim_stamp + toStampNs(column));
  for (std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_LT(s.time[i], 0.0f);
    EXPECT_NEAR(s.time[i], truth.time[i] - column, 1e-7) << i;
  }
}

TEST(CdrPointCloud, InvalidReturnsAreDroppedByRangeOrZeroPoint) {
  const OusterSweep sw = smallSweep(true);
  RawCloud cloud = organisedOusterCloud(simulatedSweep(sw, 1700000000000000000ULL), sw);
  // Pixel 1 is a return: zero its range only (a return the driver flagged as invalid).
  const std::uint32_t zero = 0;
  std::memcpy(cloud.data.data() + 1 * 48 + 32, &zero, 4);
  Scan s;
  const DecodeCounts n = decodeCloud(cloud.layout, cloud.data.data(), cloud.data.size(), true, "t", s);
  EXPECT_EQ(n.invalid, 11u + 1u);  // 11 pixels without a return, one with range 0
  EXPECT_EQ(s.size(), 32u - 12u);
  for (const auto& p : s.points) EXPECT_FALSE(p.isZero());
  EXPECT_TRUE(s.hasTime() && s.hasRing() && s.hasIntensity());
}

TEST(CdrPointCloud, EveryTruncationIsAClearErrorNeverACrash) {
  const OusterSweep sw = smallSweep(false);
  const auto cdr = encodeCdrPointCloud2(organisedOusterCloud(simulatedSweep(sw, 1700000000000000000ULL), sw));
  for (std::size_t len = 0; len < cdr.size(); ++len) {
    const std::vector<std::uint8_t> cut(cdr.begin(), cdr.begin() + static_cast<long>(len));
    const std::string e = errorOf(cut);
    ASSERT_FALSE(e.empty()) << "length " << len;
    EXPECT_NE(e.find("bag robot1/ouster/points"), std::string::npos) << e;
  }
  const std::string cut = errorOf(std::vector<std::uint8_t>(cdr.begin(), cdr.end() - 10));  // inside the point data
  EXPECT_NE(cut.find("truncated"), std::string::npos) << cut;
}

TEST(CdrPointCloud, MalformedMessagesNameWhatIsWrong) {
  const OusterSweep sw = smallSweep(false);
  const auto good = encodeCdrPointCloud2(organisedOusterCloud(simulatedSweep(sw, 1700000000000000000ULL), sw));
  auto big_endian = good;
  big_endian[1] = 0x00;
  EXPECT_NE(errorOf(big_endian).find("not little-endian CDR"), std::string::npos);
  auto frame_len = good;  // frame_id length far beyond the message
  frame_len[12] = 0xff;
  frame_len[13] = 0xff;
  EXPECT_NE(errorOf(frame_len).find("header.frame_id"), std::string::npos);
  auto no_nul = good;  // "os_sensor\0": overwrite the NUL
  no_nul[16 + 9] = 'x';
  EXPECT_NE(errorOf(no_nul).find("NUL"), std::string::npos);
  auto many_fields = good;  // field count: after frame (16 + 10 -> 28), height, width
  many_fields[36] = 0xff;
  many_fields[37] = 0xff;
  many_fields[38] = 0xff;
  EXPECT_NE(errorOf(many_fields).find("fields"), std::string::npos);

  // Well-formed CDR whose cloud is inconsistent: short data, a field outside the point, no x.
  RawCloud c = organisedOusterCloud(simulatedSweep(sw, 1700000000000000000ULL), sw);
  RawCloud short_data = c;
  short_data.data.resize(c.data.size() - 48);
  EXPECT_NE(errorOf(encodeCdrPointCloud2(short_data)).find("width*height*point_step"), std::string::npos);
  RawCloud outside = c;
  outside.layout.fields.back().offset = 46;  // range (uint32) beyond point_step 48
  EXPECT_NE(errorOf(encodeCdrPointCloud2(outside)).find("'range' lies outside"), std::string::npos);
  RawCloud no_x = c;
  no_x.layout.fields.erase(no_x.layout.fields.begin());
  EXPECT_NE(errorOf(encodeCdrPointCloud2(no_x)).find("no x/y/z"), std::string::npos);
  RawCloud bad_type = c;
  bad_type.layout.fields[4].datatype = 42;  // t
  EXPECT_NE(errorOf(encodeCdrPointCloud2(bad_type)).find("unknown datatype 42"), std::string::npos);
}
