#pragma once
// One fuzz target: `COSMO_FUZZ_TARGET(name) { ... }` defines a function of the input (`data`, `size`) that hands
// it to one reader of outside data. A reader may end an input with std::runtime_error (its message naming the
// file, field or offset): that is the expected outcome for a bad input. A crash, a sanitizer report, a hang, an
// unbounded allocation or any other exception is a finding.
//
// The same target sources build twice: with clang, libFuzzer, ASan and UBSan as one program per target
// (fuzz/CMakeLists.txt, COSMO_LIBFUZZER defined: the target is the program's LLVMFuzzerTestOneInput), and into
// the gtest that replays every committed seed and regression input in the normal build (test/fuzz).
#include <cstddef>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>

namespace cosmo::fuzz {

using Target = void (*)(const std::uint8_t* data, std::size_t size);

/// Every target linked into this program, by name.
inline std::map<std::string, Target>& targets() {
  static std::map<std::string, Target> all;
  return all;
}

struct Registration {
  Registration(const char* name, Target target) { targets()[name] = target; }
};

/// Runs `target` on one input; true when the reader accepted it, false when it ended it with std::runtime_error
/// (`message` receives what()). Anything else propagates.
inline bool runInput(Target target, const std::uint8_t* data, std::size_t size, std::string* message = nullptr) {
  try {
    target(data, size);
    return true;
  } catch (const std::runtime_error& e) {
    if (message) *message = e.what();
    return false;
  }
}

}  // namespace cosmo::fuzz

#ifdef COSMO_LIBFUZZER
#define COSMO_FUZZ_ENTRY(NAME)                                                       \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) { \
    cosmo::fuzz::runInput(&cosmo_fuzz_##NAME, data, size);                           \
    return 0;                                                                        \
  }
#else
#define COSMO_FUZZ_ENTRY(NAME)
#endif

#define COSMO_FUZZ_TARGET(NAME)                                                                        \
  static void cosmo_fuzz_##NAME(const std::uint8_t* data, std::size_t size);                          \
  static const cosmo::fuzz::Registration cosmo_fuzz_registration_##NAME(#NAME, &cosmo_fuzz_##NAME); \
  COSMO_FUZZ_ENTRY(NAME)                                                                               \
  static void cosmo_fuzz_##NAME(const std::uint8_t* data, std::size_t size)
