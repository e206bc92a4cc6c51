#include "cosmo/nebula/ros1_serialization.hpp"

#include <cstring>
#include <type_traits>

#include "cosmo/common/byte_cursor.hpp"

namespace cosmo::nebula {

namespace {

// Smallest serialized sizes, to reject array lengths the remaining bytes cannot hold before allocating.
constexpr std::size_t kHeaderMinBytes = 4 + 8 + 4;
constexpr std::size_t kPoseBytes = 7 * 8;
constexpr std::size_t kCovarianceBytes = 36 * 8;
constexpr std::size_t kNodeMinBytes = kHeaderMinBytes + 8 + 4 + kPoseBytes + kCovarianceBytes;
constexpr std::size_t kEdgeBytes = 8 + 8 + 4 + kPoseBytes + kCovarianceBytes + 8 + 8;

/// A malformed PoseGraph, named with the element, the field and the byte offset.
struct PoseGraphFail {
  const std::string* context;
  [[noreturn]] void operator()(const char* field, const std::string& problem, std::size_t at) const {
    throw DecodeError("PoseGraph." + *context + (context->empty() ? "" : ".") + field + " at byte " +
                      std::to_string(at) + ": " + problem);
  }
};

/// Reads little-endian fields in order; `field` names what is being read for error messages.
class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size) : in_(data, size, PoseGraphFail{&context_}, 0, "message ends") {}
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  /// The element being read ("nodes[3]"), prefixed to field names in errors.
  void setContext(std::string context) { context_ = std::move(context); }

  template <typename T>
  T scalar(const char* field) {
    return in_.template value<T>(field);
  }
  bool boolean(const char* field) {
    const std::uint8_t v = scalar<std::uint8_t>(field);
    if (v > 1) in_.failAt(field, "bool byte is " + std::to_string(v) + ", not 0 or 1", in_.offset() - 1);
    return v == 1;
  }
  std::string string(const char* field) { return in_.string(field); }
  template <std::size_t N>
  void doubles(std::array<double, N>& out, const char* field) {
    std::memcpy(out.data(), in_.bytes(N * sizeof(double), field), N * sizeof(double));
  }
  /// A variable array's length, checked against the bytes left (each element needs at least min_bytes).
  std::uint32_t arrayLength(const char* field, std::size_t min_bytes) {
    const std::size_t at = in_.offset();
    const std::uint32_t n = scalar<std::uint32_t>(field);
    if (std::uint64_t{n} * min_bytes > in_.left())
      in_.failAt(field,
                 "array length " + std::to_string(n) + " needs at least " + std::to_string(n * min_bytes) + " bytes, " +
                     std::to_string(in_.left()) + " left",
                 at);
    return n;
  }
  void finish() const {
    if (in_.left() != 0)
      throw DecodeError("PoseGraph: " + std::to_string(in_.left()) + " trailing bytes after the message (" +
                        std::to_string(in_.offset()) + " of " + std::to_string(in_.size()) + " bytes decoded)");
  }

 private:
  std::string context_;  // before in_, which points to it
  ByteCursor<PoseGraphFail> in_;
};

Header readHeader(Reader& in) {
  Header h;
  h.seq = in.scalar<std::uint32_t>("header.seq");
  h.sec = in.scalar<std::uint32_t>("header.stamp.secs");
  h.nsec = in.scalar<std::uint32_t>("header.stamp.nsecs");
  h.frame_id = in.string("header.frame_id");
  return h;
}

PoseMsg readPose(Reader& in) {
  PoseMsg p;
  std::array<double, 7> v{};
  in.doubles(v, "pose");
  p.position = {v[0], v[1], v[2]};
  p.orientation = {v[3], v[4], v[5], v[6]};
  return p;
}

PoseGraphNode readNode(Reader& in) {
  PoseGraphNode n;
  n.header = readHeader(in);
  n.key = in.scalar<std::uint64_t>("key");
  n.id = in.string("ID");
  n.pose = readPose(in);
  in.doubles(n.covariance, "covariance");
  return n;
}

PoseGraphEdge readEdge(Reader& in) {
  PoseGraphEdge e;
  e.key_from = in.scalar<std::uint64_t>("key_from");
  e.key_to = in.scalar<std::uint64_t>("key_to");
  e.type = in.scalar<std::int32_t>("type");
  e.pose = readPose(in);
  in.doubles(e.covariance, "covariance");
  e.range = in.scalar<double>("range");
  e.range_error = in.scalar<double>("range_error");
  return e;
}

/// Appends little-endian fields.
class Writer {
 public:
  template <typename T>
  void scalar(T value) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  void string(const std::string& s) {
    scalar(static_cast<std::uint32_t>(s.size()));
    bytes.insert(bytes.end(), s.begin(), s.end());
  }
  template <std::size_t N>
  void doubles(const std::array<double, N>& v) {
    for (double x : v) scalar(x);
  }
  void header(const Header& h) {
    scalar(h.seq);
    scalar(h.sec);
    scalar(h.nsec);
    string(h.frame_id);
  }
  void pose(const PoseMsg& p) {
    doubles(p.position);
    doubles(p.orientation);
  }
  std::vector<std::uint8_t> bytes;
};

}  // namespace

PoseGraph decodePoseGraph(const std::uint8_t* data, std::size_t size) {
  Reader in(data, size);
  PoseGraph g;
  g.header = readHeader(in);
  g.incremental = in.boolean("incremental");
  const std::uint32_t nodes = in.arrayLength("nodes length", kNodeMinBytes);
  g.nodes.reserve(nodes);
  for (std::uint32_t i = 0; i < nodes; ++i) {
    in.setContext("nodes[" + std::to_string(i) + "]");
    g.nodes.push_back(readNode(in));
  }
  in.setContext("");
  const std::uint32_t edges = in.arrayLength("edges length", kEdgeBytes);
  g.edges.reserve(edges);
  for (std::uint32_t i = 0; i < edges; ++i) {
    in.setContext("edges[" + std::to_string(i) + "]");
    g.edges.push_back(readEdge(in));
  }
  in.finish();
  return g;
}

std::vector<std::uint8_t> encodePoseGraph(const PoseGraph& graph) {
  Writer out;
  out.bytes.reserve(64 + graph.nodes.size() * (kNodeMinBytes + 16) + graph.edges.size() * kEdgeBytes);
  out.header(graph.header);
  out.scalar(static_cast<std::uint8_t>(graph.incremental ? 1 : 0));
  out.scalar(static_cast<std::uint32_t>(graph.nodes.size()));
  for (const PoseGraphNode& n : graph.nodes) {
    out.header(n.header);
    out.scalar(n.key);
    out.string(n.id);
    out.pose(n.pose);
    out.doubles(n.covariance);
  }
  out.scalar(static_cast<std::uint32_t>(graph.edges.size()));
  for (const PoseGraphEdge& e : graph.edges) {
    out.scalar(e.key_from);
    out.scalar(e.key_to);
    out.scalar(e.type);
    out.pose(e.pose);
    out.doubles(e.covariance);
    out.scalar(e.range);
    out.scalar(e.range_error);
  }
  return std::move(out.bytes);
}

}  // namespace cosmo::nebula
