#pragma once
// The offline driver's policy, of which cosmo_generate is the command line: a GenerateRequest
// (generate_request.hpp) -> the sequence resolved (trials::resolveSequence) -> its noise models
// (the sequence's, or estimated first from one trial run alone) -> per comm model a TeamRun fed (feed.hpp) and its
// dataset written: <out>/<name>_<comm>.jrl (+ .recorder.yaml, .stats.txt) and <out>/<name>_<comm>_transfers.csv
// (+ .summary.json) and <out>/<name>_<comm>_connectivity.json. Deterministic: the same request gives the same bytes,
// whatever the threads.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cosmo/pipeline/feed.hpp"
#include "cosmo/pipeline/generate_request.hpp"
#include "cosmo/pipeline/team_run.hpp"
#include "cosmo/trials/sequence_resolution.hpp"

namespace cosmo::pipeline {

/// One comm model's dataset.
struct GeneratedDataset {
  std::string label;           ///< the comm model's (comm/comm_model.hpp)
  std::string jrl, transfers;  ///< the files written
  dataset::BuildReport report;
  FeedFigures feed;
};

/// What a person sees of a run, told as it happens (all optional).
struct GenerateLog {
  std::function<void(const std::string&)> preflight;              ///< the pre-flight check's report (it passed)
  std::function<void(const trials::ResolvedSequence&)> resolved;  ///< the sequence, resolved
  std::function<void(const std::string&)> line;  ///< the sequence's summary, the estimate (lines end with '\n')
  std::function<void(const std::string& label)> run_starts;     ///< a comm model's run starts
  std::function<void(const TeamRun&, StampNs stamp)> progress;  ///< after each scan fed (progress lines)
  /// A dataset was written; `run` holds its team (summaries, figures).
  std::function<void(const TeamRun& run, const GeneratedDataset& dataset)> written;
  /// The wall clock for FeedFigures (the core reads none).
  std::function<double()> wall_clock;
};

struct GenerateResult {
  trials::ResolvedSequence sequence;
  dataset::NoiseModels noise;
  std::vector<GeneratedDataset> datasets;  ///< none with estimate_only
};

/// Runs the request. Throws std::runtime_error with the reason (a failed pre-flight check: its report first, on
/// log.line).
GenerateResult generate(const GenerateRequest& request, const GenerateLog& log = {});

}  // namespace cosmo::pipeline
