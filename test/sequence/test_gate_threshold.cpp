// The gate threshold a sweep varies (sequence/gate_threshold.hpp): the strict gate's min_structure_overlap on top of
// the sequence's own registration keys.
#include <gtest/gtest.h>

#include "cosmo/frontend/frontend_params.hpp"
#include "cosmo/sequence/gate_threshold.hpp"

using namespace cosmo;
using namespace cosmo::frontend;
using namespace cosmo::sequence;

TEST(GateThreshold, SetsTheStrictGatesStructureOverlapOnTopOfTheSequencesKeys) {
  SequenceConfig demo;  // the demo's registration: KISS-Matcher alone, the paper's gate
  demo.registration = {{"refine", "false"}, {"gate", "paper"}};
  for (double threshold : {0.0, 0.45, 0.62, 0.7}) {
    SequenceConfig variant = demo;
    applyGateThreshold(variant, threshold);
    const registration::RegistrationParams p = registrationParamsWith(defaultConfigDir(), variant.registration, "variant");
    EXPECT_EQ(p.gate, "strict");
    EXPECT_DOUBLE_EQ(p.min_structure_overlap, threshold);
    EXPECT_FALSE(p.refine);                                                             // the sequence's key stays
    EXPECT_DOUBLE_EQ(p.min_overlap, frontend::FrontendParams::loadDir(defaultConfigDir()).registration.min_overlap);
  }
  EXPECT_THROW(gateThresholdKeys(-0.1), std::invalid_argument);
  EXPECT_THROW(gateThresholdKeys(1.5), std::invalid_argument);
  EXPECT_EQ(gateThresholdKeys(0.58).at("min_structure_overlap"), "0.58");
}
