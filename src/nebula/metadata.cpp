#include "cosmo/nebula/metadata.hpp"

#include <yaml-cpp/yaml.h>

#include <cctype>

namespace cosmo::nebula {

namespace {

void emitMatrix(YAML::Emitter& out, const Matrix6& m) {
  out << YAML::BeginSeq;
  for (int r = 0; r < 6; ++r) {
    out << YAML::Flow << YAML::BeginSeq;
    for (int c = 0; c < 6; ++c) out << m(r, c);
    out << YAML::EndSeq;
  }
  out << YAML::EndSeq;
}

const char* noiseSourceName(NoiseSource s) {
  switch (s) {
    case NoiseSource::Recorded: return "recorded";
    case NoiseSource::Given: return "given";
    case NoiseSource::Estimated: return "estimated";
  }
  return "?";
}

}  // namespace

std::string metadataYaml(const NebulaGraph& graph, const ConversionReport& report, const ConversionParams& params,
                         const MetadataInputs& inputs) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << params.name;
  out << YAML::Key << "source" << YAML::Value << inputs.source_dir;
  out << YAML::Key << "read_from" << YAML::Value
      << (inputs.from_g2o ? "g2o_pcd (stamps: pose index i -> i s)" : "rosbag");
  out << YAML::Key << "inputs" << YAML::Value << YAML::BeginSeq;
  for (const auto& f : inputs.files) out << f;
  out << YAML::EndSeq;
  out << YAML::Key << "robots" << YAML::Value << YAML::BeginMap;  // key character -> robot name
  for (const auto& [c, r] : graph.robots)
    out << YAML::Key << std::string(1, c) << YAML::Value << (r.name.empty() ? std::string("?") : r.name);
  out << YAML::EndMap;
  out << YAML::Key << "poses" << YAML::Value << YAML::BeginMap;
  for (const auto& [c, r] : graph.robots) out << YAML::Key << std::string(1, c) << YAML::Value << r.stamps.size();
  out << YAML::EndMap;
  out << YAML::Key << "odometry_factors" << YAML::Value << report.odometry;
  out << YAML::Key << "intra_robot_loop_closures" << YAML::Value << report.intra;
  out << YAML::Key << "inter_robot_loop_closures" << YAML::Value << report.inter;
  out << YAML::Key << "intra_robot_outliers" << YAML::Value << report.intra_outliers;
  out << YAML::Key << "inter_robot_outliers" << YAML::Value << report.inter_outliers;
  out << YAML::Key << "loop_closures_inverted" << YAML::Value << report.inverted;  // stored with key1 = later pose
  out << YAML::Key << "ignored_edges" << YAML::Value << YAML::BeginMap;
  for (const auto& [type, n] : graph.ignored_edges) out << YAML::Key << type << YAML::Value << n;
  out << YAML::EndMap;
  out << YAML::Key << "other_nodes" << YAML::Value << YAML::BeginMap;  // artifacts, UWB anchors, base station
  for (const auto& [c, n] : graph.other_nodes)
    out << YAML::Key << (std::isprint(static_cast<unsigned char>(c)) ? std::string(1, c) : std::to_string(int(c)))
        << YAML::Value << n;
  out << YAML::EndMap;
  out << YAML::Key << "warnings" << YAML::Value << YAML::BeginMap;
  for (const auto& [kind, n] : graph.warnings.counts) out << YAML::Key << kind << YAML::Value << n;
  out << YAML::EndMap;
  out << YAML::Key << "messages" << YAML::Value << graph.messages;
  out << YAML::Key << "repeated_nodes" << YAML::Value << graph.repeated_nodes;
  out << YAML::Key << "repeated_edges" << YAML::Value << graph.repeated_edges;
  out << YAML::Key << "recorded_covariance_order" << YAML::Value
      << (inputs.covariance_order == CovarianceOrder::TranslationFirst ? "translation-first" : "rotation-first");
  out << YAML::Key << "noise_models" << YAML::Value << noiseSourceName(params.noise);
  if (report.models) {
    out << YAML::Key << "noise_models_environment" << YAML::Value << report.models->environment;
    out << YAML::Key << "odometry_covariance" << YAML::Value;
    emitMatrix(out, report.models->odometry);
    out << YAML::Key << "loop_closure_covariance" << YAML::Value;
    emitMatrix(out, report.models->loop_closure);
  }
  out << YAML::Key << "outlier_rule" << YAML::Value << outlierRuleName(params.rule);
  out << YAML::Key << "critical_value" << YAML::Value << params.critical_value;
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace cosmo::nebula
