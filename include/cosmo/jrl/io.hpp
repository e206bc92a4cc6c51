#pragma once
// Reading and writing JRL files (../shared/docs/jrl.md). The writer reproduces the reference library's bytes:
// one compact JSON object, keys sorted, doubles in nlohmann's spelling, no trailing newline.
#include <stdexcept>
#include <string>

#include "cosmo/jrl/dataset.hpp"

namespace cosmo::jrl {

/// Tolerance of the reader (and validate()) on |‖q‖ - 1| for Pose3 quaternions and Unit3 bearings. COSMO files
/// are unit to within 3e-10; the reference parser does not normalise, so anything further off is rejected.
constexpr double kUnitNormTolerance = 1e-6;

/// A malformed JRL document. what() = "<source>: <json path>: <problem>", e.g.
/// "x.jrl: measurements.b[12].measurements[1].covariance: expected 36 numbers, got 35".
class JrlError : public std::runtime_error {
 public:
  JrlError(const std::string& source, const std::string& path, const std::string& problem);
  const std::string& source() const { return source_; }
  const std::string& path() const { return path_; }  ///< JSON path, empty for document-level problems
  const std::string& problem() const { return problem_; }

 private:
  std::string source_, path_, problem_;
};

/// Parse a JRL document; `source` names it in errors (a file name). Throws JrlError.
/// Rejected: invalid/truncated JSON, missing or mistyped fields, string robot ids, non-integer or negative
/// keys/stamps/indices, NaN/Inf/null numbers, non-unit quaternions (kUnitNormTolerance), covariances with
/// a wrong element count, unknown factor/value tags, duplicate keys within one robot's values, duplicate robots.
/// Accepted like the reference parser: integers where doubles are expected, entries without "measurements",
/// null for an empty entry list or Values, object keys not listed in "robots" (ignored), any outlier-id order.
Dataset parseJrl(const std::string& text, const std::string& source = "<string>");

/// Read a JRL file. Throws JrlError (also when the file cannot be read).
Dataset readJrl(const std::string& path);

/// The JRL document of `dataset` (the exact bytes writeJrl writes). Throws JrlError ("<dump>") on NaN/Inf,
/// a wrong covariance size, a wrong key count or measured type, or per-robot maps naming unknown robots.
std::string dumpJrl(const Dataset& dataset);

/// Write `dataset` to `path` atomically (temporary file in the same folder, then rename). Throws
/// std::runtime_error naming the path on I/O failure.
void writeJrl(const std::string& path, const Dataset& dataset);

}  // namespace cosmo::jrl
