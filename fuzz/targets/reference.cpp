// A trial's reference file (MCD pose_inW.csv, CU-Multi ground truth, TUM, KITTI poses + times.txt), its format
// told by content, then what the pipeline does with it: the sequence offset of an anchor and the sensor
// reference in sequence time. A KITTI input is the poses, a line "#times.txt" and the times.txt text.
#include <algorithm>
#include <cstring>
#include <filesystem>

#include "../fuzz_target.hpp"
#include "../input_file.hpp"
#include "cosmo/sequence/sequence_references.hpp"
#include "cosmo/trials/reference_file.hpp"

using namespace cosmo;

COSMO_FUZZ_TARGET(reference) {
  static const char kTimes[] = "\n#times.txt\n";
  const std::uint8_t* split = std::search(data, data + size, kTimes, kTimes + std::strlen(kTimes));
  std::filesystem::create_directories(fuzz::scratchDir() / "reference");
  std::filesystem::remove(fuzz::scratchDir() / "reference" / "times.txt");
  const std::string path = fuzz::inputFile(data, static_cast<std::size_t>(split - data), "reference/poses.txt");
  if (split != data + size) {
    const std::uint8_t* times = split + std::strlen(kTimes);
    fuzz::inputFile(times, static_cast<std::size_t>(data + size - times), "reference/times.txt");
  }
  const Trajectory body = trials::readReference(path);
  if (body.empty()) return;
  const Eigen::Vector3d offset = sequence::roundedFirstPosition(body);
  sequence::TrialTiming timing;
  timing.first = body.startStamp();
  timing.last = body.endStamp();
  timing.offset_ns = -static_cast<std::int64_t>(timing.first / 2);
  sequence::toSensorReference(body, Pose3::Identity(), timing, offset);
}
