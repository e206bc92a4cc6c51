#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "cosmo/comm/transfer_log.hpp"

using namespace cosmo;

TEST(TransferLog, CsvAndSummaryFiles) {
  comm::RadioParams p = comm::RadioParams::wifi();
  p.size_model = comm::RadioParams::SizeModel::RealCompressed;
  comm::RadioSimulator sim(p, {'a', 'b'}, 1);
  sim.setRobotState('a', {0, 0, 0}, true);
  sim.setRobotState('b', {2, 0, 0}, true);
  sim.offerKeyframe('a', 3, 1000);
  sim.offerKeyframe('b', 4, 100000000);  // 50 s at full bandwidth: b's transfer will not finish
  for (int i = 0; i < 50; ++i) sim.step(sim.nextStepTime());
  sim.setRobotState('b', {500, 0, 0}, true);
  for (int i = 0; i < 50; ++i) sim.step(sim.nextStepTime());
  ASSERT_GE(sim.transferLog().size(), 2u);

  const auto dir = std::filesystem::temp_directory_path() / ("cosmo_transfer_log_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string csv = (dir / "transfers.csv").string();
  writeTransferLog(csv, sim.transferLog(), sim.stats(), sim.params());
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "sender,receiver,keyframe,start,end,bytes,outcome,received,bytes_sent,link");
  int delivered = 0, timed_out = 0, rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    if (line.back() == ',') cells.emplace_back();
    ASSERT_EQ(cells.size(), 10u) << line;
    EXPECT_EQ(cells[9], "distance");
    if (cells[6] == "delivered") {
      ++delivered;
      EXPECT_EQ(cells[7], cells[4]);  // received in the step it completed: no latency without a trace
      EXPECT_EQ(cells[8], cells[5]);  // every byte sent
    } else {
      ++timed_out;
      EXPECT_EQ(cells[7], "");
      EXPECT_LT(std::stoull(cells[8]), std::stoull(cells[5]));
    }
  }
  EXPECT_EQ(rows, static_cast<int>(sim.transferLog().size()));
  EXPECT_EQ(delivered, static_cast<int>(sim.stats().delivered));
  EXPECT_EQ(timed_out, static_cast<int>(sim.stats().timed_out));
  EXPECT_GE(timed_out, 1);
  std::ifstream js((dir / "transfers.summary.json").string());
  const auto j = nlohmann::json::parse(js);
  EXPECT_EQ(j["delivered"].get<int>(), delivered);
  EXPECT_EQ(j["params"]["timeout_mode"], "no_progress");
  EXPECT_FALSE(std::filesystem::exists(csv + ".tmp"));
  EXPECT_THROW(writeTransferLog((dir / "missing" / "x.csv").string(), {}, sim.stats(), p), std::runtime_error);
  sim.setTimeOrigin(1700000000000000000ULL);
  writeTransferLog(csv, sim);
  std::ifstream js2((dir / "transfers.summary.json").string());
  const auto j2 = nlohmann::json::parse(js2);
  EXPECT_EQ(j2["time_origin_ns"].get<std::uint64_t>(), 1700000000000000000ULL);
  EXPECT_EQ(j2["in_flight"], 0);
  EXPECT_FALSE(j2.contains("trace"));
  std::filesystem::remove_all(dir);
}
