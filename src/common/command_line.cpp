#include "cosmo/common/command_line.hpp"

#include <iostream>

namespace cosmo {

const CLI::Validator Positive(
    [](std::string& text) {
      double value = 0.0;
      if (!CLI::detail::lexical_cast(text, value) || !(value > 0.0))
        return "expected a positive number, got '" + text + "'";
      return std::string();
    },
    "POSITIVE");

CommandLine::CommandLine(const std::string& program, const std::string& description) : App(description, program) {
  option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
}

std::optional<int> CommandLine::parseOrExit(int argc, char** argv) {
  try {
    parse(argc, argv);
  } catch (const CLI::CallForHelp& e) { return exit(e); } catch (const CLI::ParseError& e) {
    std::cerr << get_name() << ": " << e.what() << "\nRun with --help for more information.\n";
    return 2;
  }
  return std::nullopt;
}

CLI::Option* addNoiseModels(CLI::App& app, std::string& file, const std::string& what) {
  return app.add_option("--noise-models", file, "noise-model YAML (" + what + ")");
}

void addClosureThresholds(CLI::App& app, const std::string& prefix, double& translation, double& rotation) {
  app.add_option("--" + prefix + "-translation", translation,
                 "loop closures with a larger translation error are left out, m")
      ->capture_default_str()
      ->check(Positive);
  app.add_option("--" + prefix + "-rotation", rotation, "loop closures with a larger rotation error are left out, rad")
      ->capture_default_str()
      ->check(Positive);
}

void addSequence(CLI::App& app, std::string& sequence, std::string& data_root) {
  app.add_option("SEQUENCE.yaml", sequence, "the sequence config")->required();
  app.add_option("--data-root", data_root,
                 "the folder the trials' bags and references are below (default: the config's data_root key, else "
                 "$COSMO_DATA_ROOT, else the config's folder)")
      ->type_name("DIR");
}

CLI::Option* addModuleConfig(CLI::App& app, std::string& file, const std::string& module) {
  return app.add_option("--config", file, module + " parameters, YAML (default: the built-in defaults)");
}

}  // namespace cosmo
