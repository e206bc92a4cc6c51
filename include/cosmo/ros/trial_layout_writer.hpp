#pragma once
// Writes a simulated trial in a real dataset's layout (cosmo_simulate --layout, fixtures of the readers'
// tests), so that reading it back can be checked against the known truth:
//  - mcd: trials/mcd_layout.hpp (bz2 ROS 1 bag of organised Ouster clouds stamped at the sweep end, body
//    pose_inW.csv at the cloud stamps from 1 s after the first cloud to 0.5 s before the last, calibration.yaml,
//    MCD's T_body_lidar: handheld, or ATV for an `atv` platform);
//  - cu-multi: trials/cu_multi_layout.hpp (ROS 2 sqlite3 bag folder, clouds stamped at the sweep start,
//    ground truth at every cloud stamp in a UTM-like frame: kSimulatedUtmOffset added to x/y, imu_T_lidar).
// The written body poses are chosen so that body * extrinsic is the simulator's true LiDAR pose: the scans are
// the same as in the cosmo layout, only their container, stamps and reference frame differ.
#include <memory>
#include <string>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/scan.hpp"
#include "cosmo/common/trajectory.hpp"

namespace cosmo::ros_glue {

enum class TrialLayout { Cosmo, Mcd, CuMulti };
/// "cosmo" | "mcd" | "cu-multi"; throws otherwise.
TrialLayout parseTrialLayout(const std::string& name);
std::string trialLayoutName(TrialLayout layout);

/// Added to the x/y of every CU-Multi-layout ground-truth position (UTM-sized values).
inline const Eigen::Vector3d kSimulatedUtmOffset(4.8e5, 4.43e6, 0.0);

struct LayoutTrialInfo {
  std::string name;      ///< trial name
  int robot_number = 1;  ///< CU-Multi's robotN (1-based)
  std::string platform;  ///< handheld | atv | car (MCD: which extrinsic)
  int beams = 64, columns = 1024;
  double rate_hz = 10.0;
};

/// A written trial as a sequence config entry (paths relative to the output folder).
struct WrittenTrial {
  std::string bag, topic, reference;
  Pose3 extrinsic = Pose3::Identity();  ///< T_body_lidar of the written reference
  bool stamp_at_end = true;
};

class TrialLayoutWriter {
 public:
  virtual ~TrialLayoutWriter() = default;
  /// One simulated sweep (sim::ScanSimulator: stamped at its last column, ring and time per point).
  virtual void write(const Scan& scan) = 0;
  /// Closes the bag and writes the reference: `body` and `T_body_lidar` are the simulator's (the true LiDAR
  /// pose is body * T_body_lidar).
  virtual WrittenTrial finish(const Trajectory& body, const Pose3& T_body_lidar) = 0;
};

/// Mcd or CuMulti (the cosmo layout is the simulator's own writer).
std::unique_ptr<TrialLayoutWriter> makeTrialLayoutWriter(TrialLayout layout, const std::string& dir,
                                                         const LayoutTrialInfo& info);

}  // namespace cosmo::ros_glue
