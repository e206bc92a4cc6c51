// A g2o graph of a Nebula dataset (ground_truth/result.g2o, g2o_pcd/*.g2o; nebula/g2o_io.hpp): parsed and merged
// into a team graph as the Nebula import does with the g2o-only folders.
#include <sstream>

#include "../fuzz_target.hpp"
#include "cosmo/nebula/g2o_io.hpp"
#include "cosmo/nebula/graph_builder.hpp"

using namespace cosmo;

COSMO_FUZZ_TARGET(g2o) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  const nebula::G2oGraph graph = nebula::parseG2o(in, "input.g2o");
  nebula::GraphBuilder builder;
  builder.addG2o(graph, "input.g2o");
  builder.build();
}
