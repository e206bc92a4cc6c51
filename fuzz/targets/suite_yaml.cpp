// A suite file (config/suites/*.yaml), read and checked as cosmo_suite reads it: every key, every variant value.
#include "../fuzz_target.hpp"
#include "../input_file.hpp"
#include "cosmo/suite/suite_file.hpp"

using namespace cosmo;

COSMO_FUZZ_TARGET(suite_yaml) {
  const std::string path = fuzz::inputFile(data, size, "suite.yaml");
  suite::SuiteFile::load(path);
}
