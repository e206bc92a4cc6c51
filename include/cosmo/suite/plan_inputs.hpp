#pragma once
// The files a job reads (plan.hpp: their identities decide whether its outputs are current) and the sequence
// time it processes.
#include <map>
#include <string>
#include <vector>

#include "cosmo/sequence/sequence_config.hpp"
#include "cosmo/suite/plan.hpp"

namespace cosmo::suite {

/// A group's inputs: the program, the sequence config, each trial's bag and reference, the config files the
/// front-end and its comm models read, and the noise models (`estimate_file`, or the sequence's own). Sets the
/// job's robots and seconds.
void addGroupInputs(const Plan& plan, Job& job, const sequence::SequenceConfig& config,
                    const std::string& estimate_file);
/// An estimate's inputs: the program, the sequence config, that trial's bag and reference, the front-end's
/// config files.
void addEstimateInputs(const Plan& plan, Job& job, const sequence::SequenceConfig& config, const std::string& trial);

/// The trial bags of `config` that a run would decompress first: ROS 1 bags with compressed chunks whose scan cache
/// (trials/scan_cache.hpp) is not there yet.
std::vector<std::string> coldCompressedBags(const sequence::SequenceConfig& config);

/// Sets each group's `after`: the earlier group (in the plan's order) that first reads a bag of `cold` it reads.
void orderFirstPasses(Plan& plan, const std::map<std::string, std::vector<std::string>>& cold);

/// Throws one std::runtime_error listing every input of every job that does not exist (with the suite file),
/// estimates' outputs aside.
void checkInputsExist(const Plan& plan);

/// The synchronised sequence's length, estimated without reading the bags: the longest trial reference's span
/// (0 when no trial has a reference).
double estimatedSequenceSeconds(const sequence::SequenceConfig& config);

}  // namespace cosmo::suite
