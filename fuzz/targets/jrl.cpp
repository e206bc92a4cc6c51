// A JRL dataset (COSMO-Bench's JSON format, jrl/io.hpp): parsed, checked (jrl/validate.hpp) and, when it parses,
// written again and re-read.
#include "../fuzz_target.hpp"
#include "cosmo/jrl/io.hpp"
#include "cosmo/jrl/validate.hpp"

using namespace cosmo;

COSMO_FUZZ_TARGET(jrl) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const jrl::Dataset dataset = jrl::parseJrl(text, "input");
  jrl::validate(dataset);
  jrl::parseJrl(jrl::dumpJrl(dataset), "dumped input");
}
