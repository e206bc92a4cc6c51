#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "cosmo/comm/radio_params.hpp"

using namespace cosmo;

TEST(RadioParams, PaperValues) {
  const comm::RadioParams w = comm::RadioParams::wifi();
  EXPECT_DOUBLE_EQ(w.bandwidth_kBps, 2000);
  EXPECT_DOUBLE_EQ(w.d_init, 30);
  EXPECT_DOUBLE_EQ(w.d_intf, 40);
  EXPECT_DOUBLE_EQ(w.p_max, 0.7);
  EXPECT_DOUBLE_EQ(w.alpha, 1.1);
  EXPECT_DOUBLE_EQ(w.beta, 0.1);
  EXPECT_DOUBLE_EQ(w.r_max, 70);
  EXPECT_DOUBLE_EQ(w.step, 0.1);
  EXPECT_DOUBLE_EQ(w.timeout, 2.0);
  const comm::RadioParams p = comm::RadioParams::proRadio();
  EXPECT_DOUBLE_EQ(p.bandwidth_kBps, 1000);
  EXPECT_DOUBLE_EQ(p.d_init, 150);
  EXPECT_DOUBLE_EQ(p.d_intf, 150);
  EXPECT_DOUBLE_EQ(p.p_max, 0.8);
  EXPECT_DOUBLE_EQ(p.alpha, 1.8);
  EXPECT_DOUBLE_EQ(p.beta, 0.3);
  EXPECT_DOUBLE_EQ(p.r_max, 200);
}

TEST(RadioParams, PhiShape) {
  const comm::RadioParams w = comm::RadioParams::wifi();
  EXPECT_DOUBLE_EQ(w.phi(0.0), 0.7);  // capped at P_max near the robot
  EXPECT_NEAR(w.phi(30.0), 1.1 * (std::pow(0.1, 30.0 / 70.0) - 0.1), 1e-12);
  EXPECT_NEAR(w.phi(70.0), 0.0, 1e-12);                                       // zero at r_max
  EXPECT_DOUBLE_EQ(w.phi(500.0), 0.0);                                        // clamped, never negative
  for (double d = 0; d < 100; d += 0.5) EXPECT_GE(w.phi(d), w.phi(d + 0.5));  // non-increasing
  const comm::RadioParams p = comm::RadioParams::proRadio();
  EXPECT_DOUBLE_EQ(p.phi(10.0), 0.8);
  EXPECT_NEAR(p.phi(150.0), 1.8 * (std::pow(0.3, 0.75) - 0.3), 1e-12);
  EXPECT_DOUBLE_EQ(p.phi(250.0), 0.0);
}

TEST(RadioParams, ShippedConfigsMatchPresets) {
  const std::string dir = std::string(COSMO_SOURCE_DIR) + "/config/comm/";
  const comm::RadioParams w = comm::RadioParams::fromConfig(ConfigNode::load(dir + "wifi.yaml"));
  const comm::RadioParams p = comm::RadioParams::fromConfig(ConfigNode::load(dir + "proradio.yaml"));
  for (const auto& [got, want] :
       {std::pair{w, comm::RadioParams::wifi()}, std::pair{p, comm::RadioParams::proRadio()}}) {
    EXPECT_DOUBLE_EQ(got.bandwidth_kBps, want.bandwidth_kBps);
    EXPECT_DOUBLE_EQ(got.d_init, want.d_init);
    EXPECT_DOUBLE_EQ(got.d_intf, want.d_intf);
    EXPECT_DOUBLE_EQ(got.p_max, want.p_max);
    EXPECT_DOUBLE_EQ(got.alpha, want.alpha);
    EXPECT_DOUBLE_EQ(got.beta, want.beta);
    EXPECT_DOUBLE_EQ(got.r_max, want.r_max);
    EXPECT_EQ(got.timeout_mode, comm::RadioParams::TimeoutMode::NoProgress);
    EXPECT_EQ(got.size_model, comm::RadioParams::SizeModel::PaperFactor);
  }
}

TEST(RadioParams, BadConfigNamesFileAndKey) {
  const auto path = std::filesystem::temp_directory_path() / ("cosmo_comm_bad_" + std::to_string(::getpid()) + ".yaml");
  { std::ofstream(path) << "comm:\n  timeout_mode: sometimes\n"; }
  try {
    comm::RadioParams::fromConfig(ConfigNode::load(path.string()));
    FAIL() << "no exception";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("timeout_mode"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path.filename().string()), std::string::npos) << e.what();
  }
  { std::ofstream(path) << "comm:\n  p_max: 1.5\n"; }
  EXPECT_THROW(comm::RadioParams::fromConfig(ConfigNode::load(path.string())), std::runtime_error);
  { std::ofstream(path) << "comm:\n  bandwidth_kBps: fast\n"; }
  EXPECT_THROW(comm::RadioParams::fromConfig(ConfigNode::load(path.string())), std::runtime_error);
  std::filesystem::remove(path);
  EXPECT_THROW(comm::RadioParams::byName("carrier-pigeon"), std::runtime_error);
}
