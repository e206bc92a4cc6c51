#pragma once
// A trial's reference trajectory file, its format told by content (a trial's `reference:`):
//  - MCD `pose_inW.csv`: header `num,t,x,y,z,qx,qy,qz,qw` (or none), 9 comma-separated columns, UNIX seconds;
//  - CU-Multi ground truth: `#` comment lines, then 8 comma-separated columns `timestamp,x,y,z,qx,qy,qz,qw`
//    (seconds; a value above 1e12 is taken as nanoseconds), positions as recorded (UTM);
//  - TUM: `t x y z qx qy qz qw`, whitespace-separated, `#` comments;
//  - KITTI: 12 numbers per line (row-major 3 x 4), no stamps: `times.txt` beside it gives one stamp (seconds)
//    per pose, as in KITTI's odometry sequences.
// The poses are the file's own (body poses for MCD and CU-Multi), in recorded time. Errors throw
// std::runtime_error naming the file and line.
#include <string>

#include "cosmo/common/trajectory.hpp"

namespace cosmo::trials {

enum class ReferenceFormat { McdPoseCsv, CuMultiCsv, Tum, Kitti };

std::string referenceFormatName(ReferenceFormat format);
/// The format of `path` from its first lines; throws naming the file and the first line that fits none.
ReferenceFormat detectReferenceFormat(const std::string& path);
/// Reads `path` in the format detectReferenceFormat finds.
Trajectory readReference(const std::string& path);

/// One format each (also what readReference calls).
Trajectory readCuMultiGroundTruth(const std::string& path);
Trajectory readKittiReference(const std::string& path);

}  // namespace cosmo::trials
