#include "cosmo/pipeline/generate_request.hpp"

#include <charconv>
#include <stdexcept>

#include "cosmo/common/text_list.hpp"
#include "cosmo/dataset/outlier_rule.hpp"
#include "cosmo/sequence/gate_threshold.hpp"

namespace cosmo::pipeline {

void GenerateRequest::validate() const {
  if (comms.empty()) throw std::runtime_error("--comm: no comm model given");
  if (!dataset::parseOutlierRule(outlier_rule))
    throw std::runtime_error("--outlier-rule: expected fidelity or squared, got '" + outlier_rule + "'");
  if (odometry != "loam" && odometry != "reference")
    throw std::runtime_error("--odometry: expected loam or reference, got '" + odometry + "'");
  if (!(estimation.max_translation_error > 0) || !(estimation.max_rotation_error > 0))
    throw std::runtime_error("--good-translation / --good-rotation: expected positive numbers");
  if (!estimate_trial.empty() && !noise_models.empty())
    throw std::runtime_error("--estimate-noise-models and --noise-models: give one of them");
  if (estimate_only && estimate_trial.empty())
    throw std::runtime_error("--estimate-only: give the trial with --estimate-noise-models TRIAL");
  if (gate_threshold) {
    try {
      sequence::gateThresholdKeys(*gate_threshold);
    } catch (const std::invalid_argument& e) { throw std::runtime_error(std::string("--gate-threshold: ") + e.what()); }
  }
}

void addGenerateOptions(CLI::App& app, GenerateRequest& r) {
  addSequence(app, r.sequence, r.data_root);
  app.add_flag_callback("--no-check", [&r] { r.check = false; },
                        "skip the pre-flight check (cosmo_check) that stops a run that would be unlabelled");
  app.add_option_function<std::string>(
         "--comm", [&r](const std::string& list) { r.comms = splitList(list); },
         "comm models, comma separated (wifi, proradio, a config/comm/*.yaml, or a radio trace .csv replayed "
         "with Wi-Fi's phi(d) outside its windows); the robots' odometry and keyframes are computed once for "
         "all of them (default: wifi)")
      ->type_name("LIST");
  app.add_option_function<unsigned long long>(
      "--seed", [&r](unsigned long long seed) { r.seed = seed; }, "overrides the sequence config's seed");
  app.add_option("--out", r.out_dir, "output folder")->capture_default_str()->type_name("DIR");
  app.add_option("--config-dir", r.config_dir,
                 "frontend/odometry/place_recognition/registration/comm/noise_models configs (default: the source "
                 "tree's config/)")
      ->type_name("DIR");
  addNoiseModels(app, r.noise_models,
                 "default: the sequence's noise_models, else <config-dir>/noise_models/<environment>.yaml; none: the "
                 "run stops");
  app.add_option("--outlier-rule", r.outlier_rule, "fidelity or squared")->capture_default_str();
  app.add_option("--estimate-noise-models", r.estimate_trial,
                 "first make the noise models as the paper does: run TRIAL (robot id or trial name) alone through "
                 "the front-end, compare with its reference, keep the good loop closures, write the sample "
                 "covariances, then generate the sequence with them")
      ->type_name("TRIAL");
  app.add_option("--noise-models-out", r.noise_models_out,
                 "where the estimate goes (default: beside the outputs, <out>/<environment, else the sequence's "
                 "name>.noise_models.yaml)")
      ->type_name("FILE");
  app.add_flag("--estimate-only", r.estimate_only, "with --estimate-noise-models: write the estimate and stop");
  addClosureThresholds(app, "good", r.estimation.max_translation_error, r.estimation.max_rotation_error);
  app.add_option("--odometry", r.odometry,
                 "loam, or reference: each robot's odometry from its reference trajectory (held at its ends; robots "
                 "without one use LOAM)")
      ->capture_default_str()
      ->check(CLI::IsMember({"loam", "reference"}));
  app.add_flag_callback("--reference-odometry", [&r] { r.odometry = "reference"; }, "the same as --odometry reference")
      ->group("");
  app.add_flag("--serial-odometry", r.serial_odometry,
               "everything in the main thread (default: one thread per robot reads its own bag and runs its LOAM "
               "and keyframes ahead of the team; the output is the same byte for byte)");
  app.add_option_function<unsigned>(
         "--registration-threads", [&r](unsigned n) { r.registration_threads = n; },
         "threads running the loop-closure registrations while the team's thread goes on (0: on the team's "
         "thread; default: the machine's cores; 0 with --serial-odometry); the output is the same byte for byte")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--max-seconds", r.max_seconds, "stop after S seconds of sequence time (quick looks)")
      ->type_name("S");
  app.add_option_function<double>(
         "--gate-threshold", [&r](double x) { r.gate_threshold = x; },
         "the registration gate's acceptance threshold (gate: strict, min_structure_overlap: X in [0, 1], on top of "
         "the sequence's registration: keys; a sweep 0.40-0.70)")
      ->type_name("X");
  app.add_flag("--quiet", r.quiet, "less output: the pre-flight report only when it fails, no progress line");
}

std::vector<std::string> generateArgs(const GenerateRequest& r) {
  const GenerateRequest d;
  std::vector<std::string> a{r.sequence};
  const auto number = [](double x) {  // the shortest text that reads back as x
    char buf[32];
    const auto end = std::to_chars(buf, buf + sizeof buf, x).ptr;
    return std::string(buf, end);
  };
  if (!r.data_root.empty()) a.insert(a.end(), {"--data-root", r.data_root});
  if (r.comms != d.comms) {
    std::string list;
    for (const auto& c : r.comms) list += (list.empty() ? "" : ",") + c;
    a.insert(a.end(), {"--comm", list});
  }
  if (r.seed) a.insert(a.end(), {"--seed", std::to_string(*r.seed)});
  if (r.max_seconds > 0) a.insert(a.end(), {"--max-seconds", number(r.max_seconds)});
  if (r.odometry != d.odometry) a.insert(a.end(), {"--odometry", r.odometry});
  if (r.gate_threshold) a.insert(a.end(), {"--gate-threshold", number(*r.gate_threshold)});
  if (!r.config_dir.empty()) a.insert(a.end(), {"--config-dir", r.config_dir});
  if (!r.noise_models.empty()) a.insert(a.end(), {"--noise-models", r.noise_models});
  if (r.outlier_rule != d.outlier_rule) a.insert(a.end(), {"--outlier-rule", r.outlier_rule});
  if (!r.estimate_trial.empty()) a.insert(a.end(), {"--estimate-noise-models", r.estimate_trial});
  if (!r.noise_models_out.empty()) a.insert(a.end(), {"--noise-models-out", r.noise_models_out});
  if (r.estimate_only) a.push_back("--estimate-only");
  if (r.estimation.max_translation_error != d.estimation.max_translation_error)
    a.insert(a.end(), {"--good-translation", number(r.estimation.max_translation_error)});
  if (r.estimation.max_rotation_error != d.estimation.max_rotation_error)
    a.insert(a.end(), {"--good-rotation", number(r.estimation.max_rotation_error)});
  if (r.serial_odometry) a.push_back("--serial-odometry");
  if (r.registration_threads) a.insert(a.end(), {"--registration-threads", std::to_string(*r.registration_threads)});
  if (!r.check) a.push_back("--no-check");
  if (r.out_dir != d.out_dir) a.insert(a.end(), {"--out", r.out_dir});
  if (r.quiet) a.push_back("--quiet");
  return a;
}

GenerateRequest generateRequestFromArgs(const std::vector<std::string>& args) {
  CLI::App app("cosmo_generate");
  GenerateRequest request;
  addGenerateOptions(app, request);
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes the arguments last first
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    std::string text;
    for (const auto& a : args) text += (text.empty() ? "" : " ") + a;
    throw std::runtime_error("cosmo_generate " + text + ": " + e.what());
  }
  return request;
}

}  // namespace cosmo::pipeline
