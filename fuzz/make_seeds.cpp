// cosmo_fuzz_seeds OUT_DIR: the seed inputs of the fuzz targets, cut from the real-layout fixtures the simulator
// writes (a tiny trial of test/trials/tiny_trial.hpp, 2 beams x 16 columns, in the MCD layout: bz2 ROS 1 bag; the
// cosmo layout: ROS 1 bag, plain and lz4; the CU-Multi layout: ROS 2 sqlite3 bag) and from a synthetic Nebula
// team (pose-graph bag, messages, g2o). Writes OUT_DIR/<target>/<seed>; the small seeds in fuzz/seeds are its
// output. Deterministic (the simulator's and the team's seeds are fixed), except for sqlite's page contents.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include "../test/trials/tiny_trial.hpp"
#include "cosmo/dataset/measurement_journal.hpp"
#include "cosmo/nebula/g2o_io.hpp"
#include "cosmo/nebula/ros1_serialization.hpp"
#include "cosmo/nebula/synthetic_team.hpp"
#include "cosmo/ros/bag_io.hpp"
#include "cosmo/ros/nebula_synthetic_folder.hpp"
#include "cosmo/ros/trial_layout_writer.hpp"
#include "cosmo/sim/scan_simulator.hpp"
#include "cosmo/trials/ros1_bag.hpp"
#include "cosmo/trials/ros1_message_stream.hpp"
#include "cosmo/trials/ros2_bag.hpp"
#include "cosmo/trials/scan_cache.hpp"
#include "cosmo/trials/trial_scans.hpp"
#include "cosmo/common/whole_file.hpp"

using namespace cosmo;
namespace fs = std::filesystem;

namespace {

constexpr int kBeams = 2, kColumns = 16, kSweeps = 3;
constexpr int kMcdSweeps = 20;  ///< MCD's reference starts 1 s after the first scan and ends 0.5 s before the last

void put(const fs::path& out, const std::string& target, const std::string& name, const std::string& bytes) {
  fs::create_directories(out / target);
  std::ofstream(out / target / name, std::ios::binary) << bytes;
}

std::string firstLines(const fs::path& path, int n) {
  std::ifstream in(path);
  std::string line, text;
  for (int i = 0; i < n && std::getline(in, line); ++i) text += line + "\n";
  return text;
}

std::string firstMessage(const fs::path& bag_path) {
  auto bag = std::make_shared<const trials::Ros1Bag>(bag_path.string());
  trials::Ros1MessageStream stream(bag, bag->messages(bag->topicConnections("/os_cloud_node/points")), 0);
  trials::Ros1MessageRef m;
  trials::Ros1Bag::Bytes bytes;
  stream.next(m, bytes);
  return std::string(reinterpret_cast<const char*>(bytes.data), bytes.size);
}

/// A one-trial sequence config of a written layout, as cosmo_simulate writes it.
std::string sequenceConfig(const std::string& layout, const ros_glue::WrittenTrial& w) {
  std::ostringstream out;
  out.precision(17);
  out << "# Synthetic sequence in the " << layout << " layout\nname: tiny_" << layout
      << "\nsource: synthetic\nseed: 3\nanchor: a\nenvironment: synthetic\n";
  if (layout == "cu-multi") out << "reference_offset: anchor\n";
  out << "trials:\n  - robot: a\n    name: walk_a\n    bag: " << w.bag << "\n    topic: " << w.topic
      << "\n    stamp: " << (w.stamp_at_end ? "end" : "start") << "\n    reference: " << w.reference
      << "\n    extrinsic: [";
  const Eigen::Quaterniond q(w.extrinsic.linear());
  out << w.extrinsic.translation().x() << ", " << w.extrinsic.translation().y() << ", " << w.extrinsic.translation().z()
      << ", " << q.x() << ", " << q.y() << ", " << q.z() << ", " << q.w() << "]\n";
  return out.str();
}

/// The tiny trial in the cosmo (none, lz4), MCD and CU-Multi layouts, and the seeds cut from them.
void trialSeeds(const fs::path& work, const fs::path& out) {
  const sim::LidarModel lidar = test::smallLidar(kBeams, kColumns, 10.0);
  const sim::PlannedSequence plan = test::tinyPlan(lidar);
  const auto& t = plan.trials.at(0);
  const Pose3 T_body_lidar = t.params.extrinsicPose();
  sim::ScanSimulator simulator(*plan.world, lidar);
  std::vector<Scan> scans;
  for (int k = 0; k < kMcdSweeps; ++k)
    scans.push_back(simulator.simulate(t.body, T_body_lidar, t.scan_stamps[k], t.noise_seed));

  ros_glue::LayoutTrialInfo info;
  info.name = t.params.name;
  info.platform = t.params.platform;
  info.beams = kBeams;
  info.columns = kColumns;
  info.rate_hz = 10.0;
  std::map<std::string, ros_glue::WrittenTrial> written;
  for (auto layout : {ros_glue::TrialLayout::Mcd, ros_glue::TrialLayout::CuMulti}) {
    const std::string name = ros_glue::trialLayoutName(layout);
    auto writer = ros_glue::makeTrialLayoutWriter(layout, (work / name).string(), info);
    const int sweeps = layout == ros_glue::TrialLayout::Mcd ? kMcdSweeps : kSweeps;
    for (int k = 0; k < sweeps; ++k) writer->write(scans[k]);
    written[name] = writer->finish(t.body, T_body_lidar);
  }
  for (auto [name, compression] :
       {std::pair{"none", ros_glue::BagCompression::None}, std::pair{"lz4", ros_glue::BagCompression::Lz4}}) {
    ros_glue::ScanBagWriter bag((work / (std::string("cosmo_") + name + ".bag")).string(), compression);
    for (int k = 0; k < kSweeps; ++k) bag.write("/os_cloud_node/points", scans[k], "os_sensor");
  }

  const fs::path mcd_bag = work / "mcd" / written["mcd"].bag;
  put(out, "ros1_bag", "mcd_bz2.bag", cosmo::readWholeFileOrEmpty(mcd_bag));
  put(out, "ros1_bag", "cosmo_none.bag", cosmo::readWholeFileOrEmpty(work / "cosmo_none.bag"));
  put(out, "ros1_bag", "cosmo_lz4.bag", cosmo::readWholeFileOrEmpty(work / "cosmo_lz4.bag"));
  for (const char* target : {"ros1_point_cloud", "ros_point_cloud"}) {
    put(out, target, "mcd_ouster.msg", firstMessage(mcd_bag));
    put(out, target, "cosmo_scan.msg", firstMessage(work / "cosmo_none.bag"));
  }

  const fs::path cu_bag = work / "cu-multi" / written["cu-multi"].bag;
  trials::Ros2BagReader reader(cu_bag.string(), written["cu-multi"].topic);
  trials::Ros2BagReader::Message m;
  reader.next(m);
  put(out, "cdr_point_cloud", "cu_multi_ouster.cdr", std::string(reinterpret_cast<const char*>(m.data), m.size));
  const auto db3 = trials::ros2BagFiles(cu_bag.string()).at(0);
  put(out, "ros2_bag", "cu_multi.bin",
      cosmo::readWholeFileOrEmpty(cu_bag / "metadata.yaml") + cosmo::readWholeFileOrEmpty(db3));

  put(out, "reference", "mcd_pose_inW.csv", firstLines(work / "mcd" / written["mcd"].reference, 8));
  put(out, "reference", "cu_multi_gt.csv", firstLines(work / "cu-multi" / written["cu-multi"].reference, 8));
  std::ostringstream tum, kitti, times;
  tum.precision(17);
  kitti.precision(9);
  for (std::size_t i = 0; i < 5; ++i) {
    const StampedPose& p = t.body.poses().at(i * 10);
    const Eigen::Quaterniond q(p.pose.linear());
    tum << toSeconds(p.stamp) << " " << p.pose.translation().transpose() << " " << q.x() << " " << q.y() << " " << q.z()
        << " " << q.w() << "\n";
    const Eigen::Matrix<double, 3, 4> m34 = p.pose.matrix().topRows<3>();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) kitti << m34(r, c) << (r == 2 && c == 3 ? "\n" : " ");
    times << toSeconds(p.stamp - t.body.startStamp()) << "\n";
  }
  put(out, "reference", "tum.txt", "# timestamp tx ty tz qx qy qz qw\n" + tum.str());
  put(out, "reference", "kitti.txt", kitti.str() + "#times.txt\n" + times.str());

  for (const auto& [layout, w] : written) put(out, "sequence_yaml", layout + ".yaml", sequenceConfig(layout, w));

  const fs::path cache = work / "cache.scans";
  {
    trials::CachingScanSource caching(
        std::make_unique<trials::Ros1ScanSource>((work / "cosmo_none.bag").string(), "/os_cloud_node/points"),
        cache.string());
    Scan s;
    while (caching.next(s)) {}
  }
  put(out, "scan_cache", "tiny.scans", cosmo::readWholeFileOrEmpty(cache));
  trials::writeCachedSpan((work / "tiny.span").string(), scans.front().stamp, scans[kSweeps - 1].stamp);
  put(out, "scan_cache", "tiny.span", cosmo::readWholeFileOrEmpty(work / "tiny.span"));
}

/// A synthetic Nebula team of one robot: its pose-graph bag, its first messages, its g2o graphs.
void nebulaSeeds(const fs::path& work, const fs::path& out) {
  nebula::SyntheticTeamParams p;
  p.robots = {{"husky1", 'a'}};
  p.poses_per_robot = 8;
  p.poses_per_message = 3;
  std::mt19937_64 rng(7);
  const nebula::SyntheticTeam team = nebula::makeSyntheticTeam(p, rng);
  ros_glue::writeNebulaFolder((work / "nebula").string(), team);
  put(out, "ros1_bag", "nebula_husky1.bag", cosmo::readWholeFileOrEmpty(work / "nebula" / "rosbag" / "husky1.bag"));
  const auto& messages = team.messages.at("husky1");
  std::string framed;  // the messages, each preceded by its uint32 length
  for (std::size_t i = 0; i < messages.size() && i < 3; ++i) {
    const auto bytes = nebula::encodePoseGraph(messages[i]);
    const auto n = static_cast<std::uint32_t>(bytes.size());
    framed += std::string(reinterpret_cast<const char*>(&n), 4) + std::string(bytes.begin(), bytes.end());
    put(out, "nebula_pose_graph", "husky1_first_" + std::to_string(i + 1) + ".msgs", framed);
  }
  put(out, "g2o", "husky1.g2o", cosmo::readWholeFileOrEmpty(work / "nebula" / "g2o_pcd" / "husky1.g2o"));
  put(out, "g2o", "result.g2o", firstLines(work / "nebula" / "ground_truth" / "result.g2o", 6));
}

/// A recorder journal of two robots: keyframes (one with a reference, one bridged), a loop closure, the marks.
void journalSeeds(const fs::path& out) {
  dataset::JournalHeader h{"run-1", "demo", {'a', 'b'}, true};
  std::string bytes = dataset::encodeJournalHeader(h);
  std::uint64_t seq = 0;
  for (char robot : {'a', 'b'})
    for (std::uint32_t i = 0; i < 3; ++i) {
      dataset::KeyframeMeasurement k;
      k.robot = robot;
      k.index = i;
      k.stamp = 1000000000ull * (i + 1);
      k.odometry =
          makePose({1.0 * i, 0.5, 0.0}, Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * i, Eigen::Vector3d::UnitZ())));
      if (i == 0) k.reference = Pose3::Identity();
      if (robot == 'b' && i == 2) k.bridge_from = 0;
      k.scans_skipped = i;
      bytes += dataset::encodeJournalRecord({robot, ++seq, k});
    }
  dataset::LoopClosureMeasurement lc;
  lc.owner = 'a';
  lc.computed_at = 2500000000ull;
  lc.key1 = 1;
  lc.key2 = 2;
  bytes += dataset::encodeJournalRecord({'a', ++seq, lc});
  put(out, "journal", "two_robots.journal", bytes);
  put(out, "journal", "torn_tail.journal", bytes.substr(0, bytes.size() - 7));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: cosmo_fuzz_seeds OUT_DIR\n";
    return 2;
  }
  const fs::path out = argv[1];
  const fs::path work = out / "_fixtures";
  try {
    fs::create_directories(work);
    trialSeeds(work, out);
    nebulaSeeds(work, out);
    journalSeeds(out);
    fs::remove_all(work);
  } catch (const std::exception& e) {
    std::cerr << "cosmo_fuzz_seeds: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
