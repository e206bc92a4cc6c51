#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "cosmo/jrl/closure_error.hpp"
#include "cosmo/jrl/exports.hpp"
#include "cosmo/jrl/pose_graph.hpp"

namespace cosmo::jrl {

void exportLabelsCsv(const Dataset& dataset, const std::string& path) {
  const PoseGraph g = poseGraph(dataset);
  if (g.groundtruth.empty()) throw std::runtime_error(dataset.name + ": no ground truth to measure the closures");
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  out << "robot,entry,measurement,kind,key1,key2,pose1,pose2,stamp_ns,trans_err_m,rot_err_deg,d2,label\n";
  char buf[128];
  for (const PoseFactor& f : g.factors) {
    if (!f.isLoopClosure()) continue;
    const ClosureError e = closureError(f, g.groundtruth);
    std::snprintf(buf, sizeof buf, "%.6f,%.6f,%.6f", e.trans_m, e.rot_rad * 180.0 / M_PI, e.d2);
    out << f.robot << ',' << f.id.entry << ',' << f.id.measurement << ',' << factorKindName(f.kind) << ',' << f.key1
        << ',' << f.key2 << ',' << keyName(f.key1) << ',' << keyName(f.key2) << ',' << f.stamp << ',' << buf << ','
        << (!g.has_outlier_labels ? "unlabelled"
            : f.outlier           ? "outlier"
                                  : "inlier")
        << "\n";
  }
  out.close();
  if (!out) throw std::runtime_error(path + ": cannot write");
}

}  // namespace cosmo::jrl
