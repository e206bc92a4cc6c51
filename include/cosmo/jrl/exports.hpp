#pragma once
// Exports of a dataset to the formats back-end users load (`cosmo_jrl export`). Each throws std::runtime_error
// naming the file it cannot write, or the dataset's problem (a non-Pose3 factor, missing values).
//
// g2o: one global graph. Vertices `VERTEX_SE3:QUAT id x y z qx qy qz qw` at the initialization (the owner's
//   value of each key), numbered 0..n-1 in JRL key order (robot, then pose index); a first comment line names
//   each robot's first id (`# ... first ids a 0 b 351 c 886`). Edges `EDGE_SE3:QUAT id1 id2 x y z qx qy qz qw`
//   followed by the 21 upper-triangular entries (row by row) of the information matrix in g2o's own convention
//   (g2oInformation): every BetweenFactorPose3 (odometry and every loop closure, outliers included). Priors
//   are not written (g2o has no prior edge its readers share); they equal the ground truth of each robot's first
//   pose, which the vertices hold.
//   Beside OUT.g2o (its path without ".g2o", plus): OUT.blocks.csv, header robot,first_id,count, one row per robot
//   in id order: its vertices are ids first_id .. first_id + count - 1 (contiguous blocks, as DPGO-style
//   distributed solvers split a global graph; odometry edges are i -> i+1 within a block, loop closures may cross
//   blocks); OUT.ids.csv, header g2o_id,robot,jrl_key,stamp, one row per vertex in id order: its robot, its JRL key
//   (the integer of the file, e.g. 6989586621679009792 = a0) and the stamp (ns) of its owner's first entry that
//   refers to it (empty when none does).
// TUM: per robot <dir>/<name>_<r>_groundtruth.tum and <name>_<r>_initialization.tum, own poses in index order,
//   `t x y z qx qy qz qw`, t = the stamp (s) of the entry that creates the pose.
// labels CSV: one row per loop closure (intra and inter robot), header line
//   robot,entry,measurement,kind,key1,key2,pose1,pose2,stamp_ns,trans_err_m,rot_err_deg,d2,label
//   errors of the measurement against the ground truth (jrl/closure_error.hpp), label inlier / outlier
//   (outlier_factors) or unlabelled (no outlier lists in the file).
#include <string>
#include <vector>

#include "cosmo/common/pose.hpp"
#include "cosmo/jrl/dataset.hpp"

namespace cosmo::jrl {

/// The information matrix of g2o's EDGE_SE3:QUAT for a JRL covariance Σ (GTSAM's order [w, v], rotation
/// first). g2o's error of an edge is e = [t; qx, qy, qz] of m^-1 T1^-1 T2 (translation first, the vector part of
/// the unit quaternion with w >= 0, i.e. half the rotation vector to first order), while GTSAM's is
/// r = Log(m^-1 T1^-1 T2) = [w; v]; so e = D P r to first order with P the block swap and
/// D = diag(1, 1, 1, 1/2, 1/2, 1/2), and the matrix that gives g2o the same chi² as GTSAM is
/// Ω = D^-1 P Σ^-1 P^T D^-1: Σ^-1 with the blocks swapped, the rotation block times 4, the cross blocks times 2.
Matrix6 g2oInformation(const Matrix6& covariance);

/// Writes `path` and the two files beside it (g2oBlocksPath, g2oIdsPath); returns the three paths.
std::vector<std::string> exportG2o(const Dataset& dataset, const std::string& path);
/// "OUT.g2o" -> "OUT.blocks.csv", "OUT.ids.csv" (a path not ending in ".g2o": the whole path, plus).
std::string g2oBlocksPath(const std::string& g2o_path);
std::string g2oIdsPath(const std::string& g2o_path);
/// Returns the paths written.
std::vector<std::string> exportTum(const Dataset& dataset, const std::string& dir);
void exportLabelsCsv(const Dataset& dataset, const std::string& path);

}  // namespace cosmo::jrl
