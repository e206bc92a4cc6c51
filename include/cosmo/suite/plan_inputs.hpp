#pragma once
// The files a job reads (plan.hpp: their identities decide whether its outputs are current) and the sequence
// time it processes.
#include <string>

#include "cosmo/pipeline/sequence_config.hpp"
#include "cosmo/suite/plan.hpp"

namespace cosmo::suite {

/// A group's inputs: the program, the sequence config, each trial's bag and reference, the config files the
/// front-end and its comm models read, and the noise models (`estimate_file`, or the sequence's own). Sets the
/// job's robots and seconds.
void addGroupInputs(const Plan& plan, Job& job, const pipeline::SequenceConfig& config,
                    const std::string& estimate_file);
/// An estimate's inputs: the program, the sequence config, that trial's bag and reference, the front-end's
/// config files.
void addEstimateInputs(const Plan& plan, Job& job, const pipeline::SequenceConfig& config, const std::string& trial);

/// Throws one std::runtime_error listing every input of every job that does not exist (with the suite file),
/// estimates' outputs aside.
void checkInputsExist(const Plan& plan);

/// The synchronised sequence's length, estimated without reading the bags: the longest trial reference's span
/// (0 when no trial has a reference).
double estimatedSequenceSeconds(const pipeline::SequenceConfig& config);

/// Seconds as an option value ("20", "12.5").
std::string formatSeconds(double seconds);

}  // namespace cosmo::suite
