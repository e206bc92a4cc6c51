#include "cosmo/nebula/message_definition.hpp"

#include <openssl/evp.h>

#include <cstdio>
#include <set>
#include <sstream>
#include <stdexcept>

namespace cosmo::nebula {

namespace {

// Fields and constants of LAMP's pose_graph_msgs (real_data_formats.md §4), written without comments: comments
// and spacing do not enter the md5sum.
constexpr std::string_view kPoseGraphMsg =
    "Header header\n"
    "bool incremental\n"
    "PoseGraphNode[] nodes\n"
    "PoseGraphEdge[] edges\n";

constexpr std::string_view kPoseGraphNodeMsg =
    "Header header\n"
    "uint64 key\n"
    "string ID\n"
    "geometry_msgs/Pose pose\n"
    "float64[36] covariance\n";

constexpr std::string_view kPoseGraphEdgeMsg =
    "uint64 key_from\n"
    "uint64 key_to\n"
    "int32 type\n"
    "int32 ODOM=0\n"
    "int32 PRIOR=1\n"
    "int32 IMU=2\n"
    "int32 LOOPCLOSE=3\n"
    "int32 ARTIFACT=4\n"
    "int32 UWB_RANGE=5\n"
    "int32 UWB_BETWEEN=6\n"
    "int32 INTERROB_RANGE=7\n"
    "int32 INTERROB_BETW=8\n"
    "geometry_msgs/Pose pose\n"
    "float64[36] covariance\n"
    "float64 range\n"
    "float64 range_error\n";

const std::set<std::string>& builtinTypes() {
  static const std::set<std::string> kTypes = {"bool",   "int8",     "uint8",  "int16",   "uint16",  "int32",
                                               "uint32", "int64",    "uint64", "float32", "float64", "string",
                                               "time",   "duration", "char",   "byte"};
  return kTypes;
}

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return std::string(s.substr(b, e - b + 1));
}

}  // namespace

std::string_view poseGraphMsgText() { return kPoseGraphMsg; }
std::string_view poseGraphNodeMsgText() { return kPoseGraphNodeMsg; }
std::string_view poseGraphEdgeMsgText() { return kPoseGraphEdgeMsg; }

std::string md5Text(std::string_view msg_text, const std::map<std::string, std::string>& nested_md5) {
  std::ostringstream constants, fields;
  std::istringstream lines{std::string(msg_text)};
  for (std::string raw; std::getline(lines, raw);) {
    // A string constant keeps everything after '=' ('#' included); any other line loses its comment.
    const std::string first = trim(raw).substr(0, trim(raw).find_first_of(" \t"));
    const bool string_constant = first == "string" && raw.find('=') != std::string::npos;
    std::string line = trim(string_constant ? std::string_view(raw) : std::string_view(raw).substr(0, raw.find('#')));
    if (line.empty()) continue;
    const bool constant = line.find('=') != std::string::npos;
    const std::size_t space = line.find_first_of(" \t");
    if (space == std::string::npos) throw std::invalid_argument("message definition line '" + raw + "': no name");
    const std::string type = line.substr(0, space);
    if (constant) {
      const std::size_t e = line.find('=');
      const std::string name = trim(std::string_view(line).substr(space, e - space));
      const std::string value = trim(std::string_view(line).substr(e + 1));
      constants << type << ' ' << name << '=' << value << '\n';
      continue;
    }
    const std::string name = trim(std::string_view(line).substr(space));
    const std::string bare = type.substr(0, type.find('['));
    if (builtinTypes().count(bare)) {
      fields << type << ' ' << name << '\n';
    } else {
      const auto it = nested_md5.find(bare);
      if (it == nested_md5.end())
        throw std::invalid_argument("message definition: no md5 for nested type '" + bare + "'");
      fields << it->second << ' ' << name << '\n';
    }
  }
  std::string text = constants.str() + fields.str();
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

std::string md5Hex(std::string_view bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), digest, &length, EVP_md5(), nullptr) != 1)
    throw std::runtime_error("md5: OpenSSL EVP_Digest failed");
  std::string hex;
  char buf[3];
  for (unsigned int i = 0; i < length; ++i) {
    std::snprintf(buf, sizeof buf, "%02x", digest[i]);
    hex += buf;
  }
  return hex;
}

std::string poseGraphNodeMd5() {
  return md5Hex(md5Text(kPoseGraphNodeMsg, {{"Header", kHeaderMd5}, {"geometry_msgs/Pose", kPoseMd5}}));
}

std::string poseGraphEdgeMd5() { return md5Hex(md5Text(kPoseGraphEdgeMsg, {{"geometry_msgs/Pose", kPoseMd5}})); }

std::string poseGraphMd5() {
  return md5Hex(
      md5Text(kPoseGraphMsg,
              {{"Header", kHeaderMd5}, {"PoseGraphNode", poseGraphNodeMd5()}, {"PoseGraphEdge", poseGraphEdgeMd5()}}));
}

std::string poseGraphFullDefinition(std::string_view header_text, std::string_view pose_text,
                                    std::string_view point_text, std::string_view quaternion_text) {
  const std::string separator(80, '=');
  std::string text(kPoseGraphMsg);
  auto section = [&](const char* type, std::string_view body) {
    text += separator + "\nMSG: " + type + "\n";
    text += body;
    if (!text.empty() && text.back() != '\n') text += '\n';
  };
  section("std_msgs/Header", header_text);
  section("pose_graph_msgs/PoseGraphNode", kPoseGraphNodeMsg);
  section("geometry_msgs/Pose", pose_text);
  section("geometry_msgs/Point", point_text);
  section("geometry_msgs/Quaternion", quaternion_text);
  section("pose_graph_msgs/PoseGraphEdge", kPoseGraphEdgeMsg);
  return text;
}

}  // namespace cosmo::nebula
