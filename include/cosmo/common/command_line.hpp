#pragma once
// Command lines of the tools and benchmarks: options declared once with CLI11, `--help` generated from the same
// declarations, usage errors (an unknown option, a missing or bad value, named in the message) exit with 2.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace cosmo {

/// A program's command line. An option given twice takes its last value.
class CommandLine : public CLI::App {
 public:
  CommandLine(const std::string& program, const std::string& description);
  /// Parses argv into the declarations. Returns the exit code when the program ends here: 0 after --help (the
  /// help on stdout), 2 after a usage error (the message and a pointer to --help on stderr).
  std::optional<int> parseOrExit(int argc, char** argv);
};

/// A value above zero; the message names the value ("--tail: expected a positive number, got '-1'").
extern const CLI::Validator Positive;

/// Options several programs share, declared once.
/// --noise-models FILE: a noise-model YAML; `what` says what it overrides.
CLI::Option* addNoiseModels(CLI::App& app, std::string& file, const std::string& what);
/// --<prefix>-translation M, --<prefix>-rotation RAD: the errors under which a loop closure is good (positive).
void addClosureThresholds(CLI::App& app, const std::string& prefix, double& translation, double& rotation);
/// SEQUENCE.yaml (required) and --data-root DIR: a sequence config and where its trials' files are.
void addSequence(CLI::App& app, std::string& sequence, std::string& data_root);
/// --config FILE: a module's parameter YAML (default: the built-in defaults, which config/*.yaml repeat).
CLI::Option* addModuleConfig(CLI::App& app, std::string& file, const std::string& module);

}  // namespace cosmo
