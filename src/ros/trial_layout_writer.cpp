#include "cosmo/ros/trial_layout_writer.hpp"

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "cosmo/ros/bag_io.hpp"
#include "cosmo/trials/cu_multi_layout.hpp"
#include "cosmo/trials/mcd_layout.hpp"

namespace fs = std::filesystem;

namespace cosmo::ros_glue {

TrialLayout parseTrialLayout(const std::string& name) {
  if (name == "cosmo") return TrialLayout::Cosmo;
  if (name == "mcd") return TrialLayout::Mcd;
  if (name == "cu-multi") return TrialLayout::CuMulti;
  throw std::runtime_error("unknown layout '" + name + "' (expected mcd, cu-multi or cosmo)");
}

std::string trialLayoutName(TrialLayout layout) {
  switch (layout) {
    case TrialLayout::Cosmo: return "cosmo";
    case TrialLayout::Mcd: return "mcd";
    case TrialLayout::CuMulti: return "cu-multi";
  }
  return "?";
}

namespace {

/// Body poses written so that body * `written_extrinsic` is the true LiDAR pose at each stamp.
std::vector<StampedPose> writtenBody(const Trajectory& body, const Pose3& T_body_lidar, const Pose3& written_extrinsic,
                                     const std::vector<StampNs>& stamps, const Eigen::Vector3d& offset) {
  std::vector<StampedPose> out;
  out.reserve(stamps.size());
  const Pose3 to_written = written_extrinsic.inverse();
  for (StampNs s : stamps) {
    Pose3 p = body.atClamped(s) * T_body_lidar * to_written;
    p.translation() += offset;
    out.push_back({s, p});
  }
  return out;
}

class McdWriter : public TrialLayoutWriter {
 public:
  McdWriter(const std::string& dir, const LayoutTrialInfo& info)
      : dir_(fs::path(dir) / info.name),
        info_(info),
        sweep_(trials::mcdSweep(info.beams, info.columns, info.rate_hz)),
        extrinsic_(info.platform == "atv" ? trials::mcdAtvExtrinsic() : trials::mcdHandheldExtrinsic()),
        bag_name_(info.name + "_os1_" + std::to_string(info.beams) + ".bag") {
    fs::create_directories(dir_);
    bag_ = std::make_unique<ScanBagWriter>((dir_ / bag_name_).string(), BagCompression::Bz2);
  }
  void write(const Scan& scan) override {
    const trials::RawCloud cloud = trials::organisedOusterCloud(scan, sweep_);
    stamps_.push_back(cloud.layout.stamp);
    bag_->write(trials::kMcdTopic, cloud);
  }
  WrittenTrial finish(const Trajectory& body, const Pose3& T_body_lidar) override {
    bag_->close();
    // MCD's ground truth: row `num` N at cloud N-1, from about 1 s after the first cloud to 0.5 s before the last.
    const auto first = static_cast<std::size_t>(std::lround(1.0 * info_.rate_hz));
    const auto tail = static_cast<std::size_t>(std::lround(0.5 * info_.rate_hz));
    if (stamps_.size() < first + tail + 2)
      throw std::runtime_error(info_.name + ": " + std::to_string(stamps_.size()) +
                               " scans are too few for MCD's ground-truth span (needs > 1.5 s)");
    const std::vector<StampNs> gt(stamps_.begin() + static_cast<long>(first), stamps_.end() - static_cast<long>(tail));
    trials::writeMcdPoseCsv((dir_ / "pose_inW.csv").string(),
                            writtenBody(body, T_body_lidar, extrinsic_, gt, Eigen::Vector3d::Zero()),
                            static_cast<int>(first) + 1);
    trials::writeMcdCalibration((dir_ / "calibration.yaml").string(), extrinsic_);
    WrittenTrial w;
    w.bag = info_.name + "/" + bag_name_;
    w.topic = trials::kMcdTopic;
    w.reference = info_.name + "/pose_inW.csv";
    w.extrinsic = extrinsic_;
    w.stamp_at_end = true;
    return w;
  }

 private:
  fs::path dir_;
  LayoutTrialInfo info_;
  trials::OusterSweep sweep_;
  Pose3 extrinsic_;
  std::string bag_name_;
  std::unique_ptr<ScanBagWriter> bag_;
  std::vector<StampNs> stamps_;
};

class CuMultiWriter : public TrialLayoutWriter {
 public:
  CuMultiWriter(const std::string& dir, const LayoutTrialInfo& info)
      : dir_(dir),
        info_(info),
        sweep_(trials::cuMultiSweep(info.beams, info.columns, info.rate_hz)),
        folder_("robot" + std::to_string(info.robot_number) + "_" + info.name + "_lidar"),
        bag_((dir_ / folder_).string(), info.robot_number) {}
  void write(const Scan& scan) override {
    const trials::RawCloud cloud = trials::organisedOusterCloud(scan, sweep_);
    stamps_.push_back(cloud.layout.stamp);
    bag_.write(cloud);
  }
  WrittenTrial finish(const Trajectory& body, const Pose3& T_body_lidar) override {
    bag_.close();
    // CU-Multi's name for a site's robot: <site>_robotN_ref.csv beside robotN_<site>_lidar/ (evalio's files).
    const std::string gt = info_.name + "_robot" + std::to_string(info_.robot_number) + "_ref.csv";
    trials::writeCuMultiGroundTruth((dir_ / gt).string(), writtenBody(body, T_body_lidar, trials::cuMultiImuTLidar(),
                                                                      stamps_, kSimulatedUtmOffset));
    WrittenTrial w;
    w.bag = folder_;
    w.topic = trials::cuMultiTopic(info_.robot_number);
    w.reference = gt;
    w.extrinsic = trials::cuMultiImuTLidar();
    w.stamp_at_end = false;
    return w;
  }

 private:
  fs::path dir_;
  LayoutTrialInfo info_;
  trials::OusterSweep sweep_;
  std::string folder_;
  trials::CuMultiBagWriter bag_;
  std::vector<StampNs> stamps_;
};

}  // namespace

std::unique_ptr<TrialLayoutWriter> makeTrialLayoutWriter(TrialLayout layout, const std::string& dir,
                                                         const LayoutTrialInfo& info) {
  switch (layout) {
    case TrialLayout::Mcd: return std::make_unique<McdWriter>(dir, info);
    case TrialLayout::CuMulti: return std::make_unique<CuMultiWriter>(dir, info);
    case TrialLayout::Cosmo: break;
  }
  throw std::invalid_argument("makeTrialLayoutWriter: the cosmo layout is written by the simulator's own writer");
}

}  // namespace cosmo::ros_glue
