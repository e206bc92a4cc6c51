#pragma once
// The JRL (JSON Robot Log) data model: a multi-robot factor-graph dataset as ../shared/docs/jrl.md specifies
// (format v1.1.x of DanMcGann/jrl, the COSMO-Bench file format). Plain data, no GTSAM.
//
// Reading and writing live in jrl/io.hpp, checks in jrl/validate.hpp, Fig. 1 metadata in jrl/stats.hpp.
//
// Pose3 values keep the quaternion exactly as stored in the file ([w,x,y,z], sign and every bit), so that a
// read/write round trip reproduces the input bytes. Convert with toPose()/fromPose() (cosmo::Pose3 =
// Eigen::Isometry3d) or use the helpers at the bottom (pose3At, insertPose3, Factor::priorPose3, ...).
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "cosmo/common/pose.hpp"
#include "cosmo/common/time.hpp"

namespace cosmo::jrl {

// ---------------------------------------------------------------------------------------------------------
// Keys: a gtsam Symbol(robot, index) flattened to uint64: (uint64(robot) << 56) | index, index < 2^56.
// ---------------------------------------------------------------------------------------------------------
using Key = std::uint64_t;
constexpr int kIndexBits = 56;
constexpr std::uint64_t kIndexMask = (std::uint64_t{1} << kIndexBits) - 1;

/// Key of pose `index` of robot `robot` (e.g. symbol('a', 0) == 6989586621679009792).
inline Key symbol(char robot, std::uint64_t index) {
  return (static_cast<std::uint64_t>(static_cast<unsigned char>(robot)) << kIndexBits) | (index & kIndexMask);
}
/// Owner robot of a key (its top byte).
inline char robotOf(Key key) { return static_cast<char>(key >> kIndexBits); }
/// Index part of a key (its low 56 bits).
inline std::uint64_t indexOf(Key key) { return key & kIndexMask; }
/// Human-readable "a12".
std::string keyName(Key key);

// ---------------------------------------------------------------------------------------------------------
// Value types (top-level Values and measured values of factors).
// ---------------------------------------------------------------------------------------------------------

/// Pose3 as stored: translation [x,y,z] (m) and unit quaternion. The quaternion is kept bit-exact (including
/// its sign); fromPose() normalises it.
struct Pose3Value {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();

  cosmo::Pose3 toPose() const;                        ///< rotation normalised
  static Pose3Value fromPose(const cosmo::Pose3& T);  ///< quaternion from the rotation matrix, normalised
};

struct Pose2 {
  double x = 0.0, y = 0.0, theta = 0.0;
};
struct Point2 {
  double x = 0.0, y = 0.0;
};
struct Point3 {
  double x = 0.0, y = 0.0, z = 0.0;
};
struct VectorValue {  ///< JRL "Vector" {"data":[...]}
  std::vector<double> data;
};
struct Scalar {
  double value = 0.0;
};
struct Rot2 {  ///< nested only (bearing of 2-D BearingRange)
  double theta = 0.0;
};
struct Unit3 {  ///< nested only (bearing of 3-D BearingRange)
  double i = 1.0, j = 0.0, k = 0.0;
};
struct BearingRange2 {  ///< JRL "BearingRange" with a Rot2 bearing
  Rot2 bearing;
  Scalar range;
};
struct BearingRange3 {  ///< JRL "BearingRange" with a Unit3 bearing
  Unit3 bearing;
  Scalar range;
};

/// A top-level value (groundtruth / initialization). COSMO uses only Pose3Value.
using Value = std::variant<Pose3Value, Pose2, Point2, Point3, VectorValue, Scalar>;
/// Key-sorted values of one robot (duplicates impossible by construction, rejected by the reader).
using Values = std::map<Key, Value>;
/// What a factor measures; the alternative is fixed by the factor type (see measuredKind()).
using Measured = std::variant<Pose3Value, Pose2, Point2, Point3, Scalar, BearingRange2, BearingRange3>;

// ---------------------------------------------------------------------------------------------------------
// Factors.
// ---------------------------------------------------------------------------------------------------------

/// The 16 factor tags the reference parser knows (jrl.md §5.1). COSMO uses only the first two.
enum class FactorType {
  PriorFactorPose3,
  BetweenFactorPose3,
  PriorFactorPose2,
  BetweenFactorPose2,
  PriorFactorPoint2,
  BetweenFactorPoint2,
  PriorFactorPoint3,
  BetweenFactorPoint3,
  RangeFactorPose2,
  RangeFactorPose3,
  RangeFactor2D,
  RangeFactor3D,
  BearingRangeFactorPose2,
  BearingRangeFactor2D,
  BearingRangeFactorPose3,
  BearingRangeFactor3D,
};
constexpr int kFactorTypeCount = 16;

/// The JSON "type" string of a factor type, e.g. "BetweenFactorPose3".
const char* factorTag(FactorType type);
/// Factor type of a JSON tag, nullopt when unknown.
std::optional<FactorType> factorTypeFromTag(std::string_view tag);
/// Covariance dimension d (the file holds d*d numbers): Pose3 6, Pose2 3, Point2 2, Point3 3, Range 1,
/// BearingRange 2-D 2, 3-D 3.
int factorDim(FactorType type);
/// True for the Prior* tags (one key "key", measured field "prior"); others have "key1","key2","measurement".
bool isPrior(FactorType type);
/// Index into Measured of the alternative this factor type carries.
std::size_t measuredKind(FactorType type);

struct Factor {
  FactorType type = FactorType::PriorFactorPose3;
  /// 1 key for priors, 2 (key1, key2) otherwise. BetweenFactor: measured = T_key1^-1 * T_key2.
  std::vector<Key> keys;
  Measured measured;
  /// Covariance (not information), d*d numbers row by row, GTSAM tangent order (Pose3: [rx,ry,rz,tx,ty,tz]).
  std::vector<double> covariance;

  /// PriorFactorPose3 on `key` (covariance 6x6, rotation first).
  static Factor priorPose3(Key key, const cosmo::Pose3& prior, const Matrix6& covariance);
  /// BetweenFactorPose3 key1 -> key2 measuring T_key1^-1 * T_key2 (covariance 6x6, rotation first).
  static Factor betweenPose3(Key key1, Key key2, const cosmo::Pose3& measured, const Matrix6& covariance);

  bool isBetweenPose3() const { return type == FactorType::BetweenFactorPose3; }
  bool isPriorPose3() const { return type == FactorType::PriorFactorPose3; }
  /// The measured Pose3 of a PriorFactorPose3 / BetweenFactorPose3; throws std::logic_error otherwise.
  cosmo::Pose3 pose3() const;
  /// Covariance as a d x d matrix (row by row).
  Eigen::MatrixXd covarianceMatrix() const;
};

// ---------------------------------------------------------------------------------------------------------
// Dataset.
// ---------------------------------------------------------------------------------------------------------

/// One time step of a robot: its factors, in order.
struct Entry {
  StampNs stamp = 0;  ///< UNIX-epoch nanoseconds in COSMO
  std::vector<Factor> factors;
};

/// Position of a factor in one robot's measurements: [entry index, factor index in that entry].
struct FactorId {
  std::size_t entry = 0;
  std::size_t measurement = 0;
  bool operator<(const FactorId& o) const { return entry != o.entry ? entry < o.entry : measurement < o.measurement; }
  bool operator==(const FactorId& o) const { return entry == o.entry && measurement == o.measurement; }
};

struct Dataset {
  std::string name;
  std::vector<char> robots;                         ///< e.g. {'a','b','c'}
  std::map<char, std::vector<Entry>> measurements;  ///< per robot, in time order
  std::optional<std::map<char, Values>> groundtruth;
  std::optional<std::map<char, Values>> initialization;
  std::optional<std::map<char, std::set<FactorId>>> potential_outliers;  ///< "potential_outlier_factors"
  std::optional<std::map<char, std::set<FactorId>>> outliers;            ///< "outlier_factors"

  /// The factor at `id` of robot `robot`; throws std::out_of_range when absent.
  const Factor& factor(char robot, const FactorId& id) const;
};

// ---------------------------------------------------------------------------------------------------------
// Value helpers.
// ---------------------------------------------------------------------------------------------------------

/// The Pose3 stored under `key`; throws std::out_of_range (missing) or std::logic_error (not a Pose3).
cosmo::Pose3 pose3At(const Values& values, Key key);
/// Insert or overwrite a Pose3 value.
void insertPose3(Values& values, Key key, const cosmo::Pose3& pose);
/// JRL "type" string of a value ("Pose3", "Pose2", "Point2", "Point3", "Vector", "Scalar").
const char* valueTag(const Value& value);

}  // namespace cosmo::jrl
