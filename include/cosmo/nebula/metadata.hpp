#pragma once
// The metadata written next to a converted Nebula JRL (<name>.nebula.yaml): the robots' names and key
// characters (the JRL itself has no place for them), the inputs, what was counted and ignored, the noise
// models and the outlier rule.
#include <string>
#include <vector>

#include "cosmo/nebula/graph_builder.hpp"
#include "cosmo/nebula/jrl_assembly.hpp"

namespace cosmo::nebula {

struct MetadataInputs {
  std::string source_dir;
  std::vector<std::string> files;
  bool from_g2o = false;
  CovarianceOrder covariance_order = CovarianceOrder::TranslationFirst;
};

std::string metadataYaml(const NebulaGraph& graph, const ConversionReport& report, const ConversionParams& params,
                         const MetadataInputs& inputs);

}  // namespace cosmo::nebula
