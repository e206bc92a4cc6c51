// Each module's parameter list (common/param_list.hpp) checked against the struct's defaults, the shipped config
// file and the reader: every parameter is in its file with the default's value, the file holds no key nobody
// reads, each key reaches its own member, and a misspelt key stops the run naming the file and the key.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "cosmo/comm/radio_params.hpp"
#include "cosmo/common/param_list.hpp"
#include "cosmo/odometry/loam_params.hpp"
#include "cosmo/frontend/frontend_params.hpp"
#include "cosmo/place_recognition/place_recognizer.hpp"
#include "cosmo/place_recognition/scan_context.hpp"
#include "cosmo/registration/registration_params.hpp"

namespace {

using namespace cosmo;
using namespace cosmo::place_recognition;

ConfigNode shippedSection(const std::string& file, const std::vector<std::string>& path) {
  ConfigNode node = ConfigNode::load(std::string(COSMO_SOURCE_DIR) + "/config/" + file);
  for (const std::string& key : path) {
    EXPECT_TRUE(node.has(key)) << file << " has no section " << key;
    node = node[key];
  }
  return node;
}

ConfigNode parse(const std::string& text) { return ConfigNode{YAML::Load(text), "test.yaml: "}; }

std::set<std::string> keysOf(const ConfigNode& section) {
  std::set<std::string> keys;
  for (const auto& entry : section.node) keys.insert(entry.first.as<std::string>());
  return keys;
}

/// Each listed member's value as YAML text, by key.
template <class Params>
std::map<std::string, std::string> listedValues(Params params) {
  std::map<std::string, std::string> values;
  params.visit([&](const char* key, auto& value) { values[key] = YAML::Dump(YAML::Node(value)); });
  return values;
}

/// Another value of the same type, which a reader must carry over unchanged.
template <class T>
T changed(const T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    return !value;
  } else if constexpr (std::is_integral_v<T>) {
    return value + 1;
  } else if constexpr (std::is_floating_point_v<T>) {
    return value * 2.0 + 0.25;
  } else {
    return value + "_changed";
  }
}

/// The file's section names every listed key and nothing else but `other_keys`.
template <class Params>
void expectSectionListsEveryParameter(const ConfigNode& section, const std::vector<std::string>& other_keys) {
  const std::set<std::string> in_file = keysOf(section);
  std::set<std::string> known(other_keys.begin(), other_keys.end());
  for (const std::string& key : paramKeys<Params>()) {
    EXPECT_TRUE(in_file.count(key)) << section.where << " lacks the parameter " << key;
    known.insert(key);
  }
  for (const std::string& key : in_file)
    EXPECT_TRUE(known.count(key)) << section.where << "." << key << " is read by nobody";
}

/// Every listed key of the file's section holds the struct's default.
template <class Params>
void expectSectionHoldsTheDefaults(const ConfigNode& section, Params defaults) {
  defaults.visit([&](const char* key, auto& value) {
    if (!section.has(key)) return;
    using T = std::decay_t<decltype(value)>;
    EXPECT_EQ(section.node[key].template as<T>(), value) << section.where << "." << key << " differs from the default";
  });
}

/// Reading a section with one key changed changes that key's member and no other.
template <class Params>
void expectEachKeyReachesItsOwnMember(const Params& defaults) {
  const std::map<std::string, std::string> before = listedValues(defaults);
  Params probe = defaults;
  probe.visit([&](const char* key, auto& value) {
    YAML::Node section;
    section[key] = changed(value);
    Params read = defaults;
    readParams(ConfigNode{section, "test.yaml: "}, read);
    const std::map<std::string, std::string> after = listedValues(read);
    for (const auto& [other, text] : after) {
      if (other == key) {
        EXPECT_EQ(text, YAML::Dump(section[key])) << key << " was not read into its member";
      } else {
        EXPECT_EQ(text, before.at(other)) << "reading " << key << " changed " << other;
      }
    }
  });
}

/// The three checks above on one section, and the module's own reader on it gives the defaults.
template <class Params>
void expectFileStructAndReaderAgree(const ConfigNode& section, const Params& defaults,
                                    const std::vector<std::string>& other_keys = {}) {
  expectSectionListsEveryParameter<Params>(section, other_keys);
  expectSectionHoldsTheDefaults(section, defaults);
  expectEachKeyReachesItsOwnMember(defaults);
}

template <class Params>
std::string errorOf(const std::string& text) {
  try {
    Params::fromConfig(parse(text));
  } catch (const std::exception& e) { return e.what(); }
  return "(no error)";
}

}  // namespace

TEST(ParameterLists, OdometryFileStructAndReaderAgree) {
  const ConfigNode section = shippedSection("odometry.yaml", {"odometry"});
  expectFileStructAndReaderAgree(section, odometry::LoamParams{});
  EXPECT_EQ(listedValues(odometry::LoamParams::fromConfig(section)), listedValues(odometry::LoamParams{}));
}

TEST(ParameterLists, RegistrationFileStructAndReaderAgree) {
  const ConfigNode section = shippedSection("registration.yaml", {"registration"});
  expectFileStructAndReaderAgree(section, registration::RegistrationParams{});
  EXPECT_EQ(listedValues(registration::RegistrationParams::fromConfig(section)),
            listedValues(registration::RegistrationParams{}));
}

TEST(ParameterLists, PlaceRecognitionFileStructAndReaderAgree) {
  const ConfigNode section = shippedSection("place_recognition.yaml", {"place_recognition"});
  expectFileStructAndReaderAgree(section, PlaceRecognitionParams{}, {"scan_context"});
  const ConfigNode sc = shippedSection("place_recognition.yaml", {"place_recognition", "scan_context"});
  expectFileStructAndReaderAgree(sc, ScanContextParams{}, {"empty_columns"});
  const PlaceRecognitionParams read = PlaceRecognitionParams::fromConfig(section);
  EXPECT_EQ(listedValues(read), listedValues(PlaceRecognitionParams{}));
  EXPECT_EQ(listedValues(read.sc), listedValues(ScanContextParams{}));
  EXPECT_EQ(read.sc.empty_columns, ScanContextParams{}.empty_columns);
}

TEST(ParameterLists, FrontendFileStructAndReaderAgree) {
  const ConfigNode section = shippedSection("frontend.yaml", {"frontend"});
  expectFileStructAndReaderAgree(section, frontend::FrontendParams{});
  EXPECT_EQ(listedValues(frontend::FrontendParams::fromConfig(section)), listedValues(frontend::FrontendParams{}));
}

TEST(ParameterLists, RadioFilesHoldTheirPresetsAndTheReaderAgrees) {
  for (const auto& [file, preset] : {std::pair{"comm/wifi.yaml", comm::RadioParams::wifi()},
                                     std::pair{"comm/proradio.yaml", comm::RadioParams::proRadio()}}) {
    const ConfigNode section = shippedSection(file, {"comm"});
    expectFileStructAndReaderAgree(section, preset, {"preset", "timeout_mode", "size_model"});
    const comm::RadioParams read = comm::RadioParams::fromConfig(section);
    EXPECT_EQ(listedValues(read), listedValues(preset)) << file;
    EXPECT_EQ(read.timeout_mode, preset.timeout_mode) << file;
    EXPECT_EQ(read.size_model, preset.size_model) << file;
  }
}

TEST(ParameterLists, AMisspeltKeyStopsTheReadNamingTheFileTheKeyAndTheNearestParameter) {
  EXPECT_EQ(errorOf<odometry::LoamParams>("odometry:\n  min_plane_spred_ratio: 0.1\n"),
            "test.yaml: odometry.min_plane_spred_ratio: unknown parameter (did you mean 'min_plane_spread_ratio'?)");
  EXPECT_EQ(errorOf<registration::RegistrationParams>("registration:\n  voxelsize: 0.5\n"),
            "test.yaml: registration.voxelsize: unknown parameter (did you mean 'voxel_size'?)");
  EXPECT_EQ(errorOf<PlaceRecognitionParams>("place_recognition:\n  scan_context:\n    ring: 20\n"),
            "test.yaml: place_recognition.scan_context.ring: unknown parameter (did you mean 'rings'?)");
  EXPECT_EQ(errorOf<PlaceRecognitionParams>("place_recognition:\n  treshold: 0.3\n"),
            "test.yaml: place_recognition.treshold: unknown parameter (did you mean 'threshold'?)");
  EXPECT_EQ(errorOf<frontend::FrontendParams>("frontend:\n  colour: red\n"),
            "test.yaml: frontend.colour: unknown parameter");
  EXPECT_EQ(errorOf<comm::RadioParams>("comm:\n  preset: wifi\n  dinit: 20\n"),
            "test.yaml: comm.dinit: unknown parameter (did you mean 'd_init'?)");
}

TEST(ParameterLists, ScanContextKeysMayStillSitBesideThePlaceRecognitionKeys) {
  const PlaceRecognitionParams p = PlaceRecognitionParams::fromConfig(parse("rings: 10\nthreshold: 0.2\n"));
  EXPECT_EQ(p.sc.rings, 10);
  EXPECT_DOUBLE_EQ(p.threshold, 0.2);
}
