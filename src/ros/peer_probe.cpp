#include "cosmo/ros/peer_probe.hpp"

#include <arpa/inet.h>
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fcntl.h>

#include <ros/console.h>
#include <ros/init.h>
#include <ros/master.h>
#include <ros/network.h>
#include <ros/this_node.h>
#include <xmlrpcpp/XmlRpcClient.h>

namespace cosmo::ros_glue {

namespace {

/// Opens a TCP connection to host:port within `timeout` s; "" when it connected, else why not.
std::string tcpReachable(const std::string& host, std::uint32_t port, double timeout, bool& refused) {
  addrinfo hints{}, *found = nullptr;
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  if (const int rc = getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found); rc != 0)
    return "cannot resolve host " + host + ": " + gai_strerror(rc);
  std::string error = "no address";
  for (addrinfo* a = found; a; a = a->ai_next) {
    const int fd = socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0) continue;
    int rc = connect(fd, a->ai_addr, a->ai_addrlen);
    if (rc != 0 && errno == EINPROGRESS) {
      pollfd p{fd, POLLOUT, 0};
      rc = poll(&p, 1, static_cast<int>(timeout * 1000));
      if (rc == 0) {
        error = "no answer within " + std::to_string(timeout).substr(0, 3) + " s";
        rc = -1;  // not connected
        errno = 0;
      } else {
        int so_error = 0;
        socklen_t len = sizeof so_error;
        getsockopt(fd, SOL_SOCKET, SO_ERROR, &so_error, &len);
        rc = so_error == 0 ? 0 : -1;
        errno = so_error;
      }
    }
    if (rc == 0) error.clear();
    else if (errno != 0) error = std::strerror(errno), refused = errno == ECONNREFUSED;
    close(fd);
    if (error.empty()) break;
  }
  freeaddrinfo(found);
  return error;
}

/// xmlrpcpp's client with a bounded wait (its execute() waits without a limit).
class BoundedXmlRpcClient : public XmlRpc::XmlRpcClient {
 public:
  using XmlRpcClient::XmlRpcClient;
  bool call(const char* method, const XmlRpc::XmlRpcValue& params, XmlRpc::XmlRpcValue& result, double timeout) {
    if (!executeNonBlock(method, params)) return false;
    _disp.work(timeout);
    return _connectionState == IDLE && executeCheckDone(result) && !isFault();
  }
};

}  // namespace

double wallSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

live::PeerProbe probePeer(const std::string& node, double timeout) {
  live::PeerProbe probe;
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = node;
  if (!ros::master::execute("lookupNode", args, result, payload, false) || payload.getType() != XmlRpc::XmlRpcValue::TypeString) {
    probe.error = "the master does not know it";
    return probe;
  }
  probe.registered = true;
  probe.uri = static_cast<std::string>(payload);
  std::string host;
  std::uint32_t port = 0;
  if (!ros::network::splitURI(probe.uri, host, port)) {
    probe.error = "malformed URI";
    return probe;
  }
  probe.error = tcpReachable(host, port, timeout, probe.refused);
  if (!probe.error.empty()) {
    probe.hint = live::unreachableHint(peerAddress(probe));
    return probe;
  }
  BoundedXmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue pid_args, pid_result;
  pid_args[0] = ros::this_node::getName();
  if (!client.call("getPid", pid_args, pid_result, timeout) || pid_result.getType() != XmlRpc::XmlRpcValue::TypeArray ||
      pid_result.size() < 3 || pid_result[2].getType() != XmlRpc::XmlRpcValue::TypeInt) {
    probe.error = "getPid not answered within " + std::to_string(timeout).substr(0, 3) + " s";
    return probe;
  }
  probe.answered = true;
  probe.pid = static_cast<int>(pid_result[2]);
  return probe;
}

live::PeerAddress peerAddress(const live::PeerProbe& probe) {
  live::PeerAddress a;
  a.uri = probe.uri;
  std::uint32_t port = 0;
  ros::network::splitURI(probe.uri, a.host, port);
  a.refused = probe.refused;
  a.resolved = probe.error.rfind("cannot resolve", 0) != 0;
  a.timed_out = probe.error.rfind("no answer", 0) == 0 || probe.error == std::strerror(ENETUNREACH) ||
                probe.error == std::strerror(EHOSTUNREACH);  // no way there from here
  a.loopback = a.host == "localhost" || a.host == "::1" || a.host.rfind("127.", 0) == 0;
  addrinfo hints{}, *found = nullptr;
  hints.ai_socktype = SOCK_STREAM;
  if (!a.loopback && a.resolved && getaddrinfo(a.host.c_str(), nullptr, &hints, &found) == 0) {
    for (addrinfo* i = found; i; i = i->ai_next)
      if (i->ai_family == AF_INET &&
          (ntohl(reinterpret_cast<sockaddr_in*>(i->ai_addr)->sin_addr.s_addr) >> 24) == 127)
        a.loopback = true;  // a host name this machine resolves to itself (Debian's 127.0.1.1)
    freeaddrinfo(found);
  }
  return a;
}

std::string unlinkedReason(const std::string& peer_uri, const std::string& topic, double timeout) {
  std::string host;
  std::uint32_t port = 0;
  if (!ros::network::splitURI(peer_uri, host, port)) return "";
  BoundedXmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue args, result, protocols, tcpros;
  tcpros[0] = std::string("TCPROS");
  protocols[0] = tcpros;
  args[0] = ros::this_node::getName();
  args[1] = topic;
  args[2] = protocols;
  if (!client.call("requestTopic", args, result, timeout) || result.getType() != XmlRpc::XmlRpcValue::TypeArray ||
      result.size() < 3 || result[2].getType() != XmlRpc::XmlRpcValue::TypeArray || result[2].size() < 3 ||
      result[2][1].getType() != XmlRpc::XmlRpcValue::TypeString || result[2][2].getType() != XmlRpc::XmlRpcValue::TypeInt)
    return "it does not name a topic server for " + topic + " (does it publish it?)";
  live::PeerProbe server;
  const std::string server_host = static_cast<std::string>(result[2][1]);
  const std::string endpoint = server_host + ":" + std::to_string(static_cast<int>(result[2][2]));
  server.uri = "http://" + endpoint + "/";
  server.error = tcpReachable(server_host, static_cast<std::uint32_t>(static_cast<int>(result[2][2])), timeout,
                              server.refused);
  if (server.error.empty())
    return "its topic server at " + endpoint + " answers from here, so it cannot reach this node's: " +
           ros::this_node::getName() + " registered the address " + ros::network::getHost() +
           ", which ROS_IP / ROS_HOSTNAME on this machine must make one the peer's machine reaches";
  live::PeerAddress a = peerAddress(server);
  a.uri = endpoint;
  return live::unlinkedHint(a);
}

PeerMonitor::PeerMonitor(std::string owner, live::PeerWatch watch, double period)
    : owner_(std::move(owner)), period_(period), watch_(std::move(watch)) {}

PeerMonitor::~PeerMonitor() {
  quit_ = true;
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void PeerMonitor::setLinkCheck(const std::string& node, std::function<bool()> linked, const std::string& topic) {
  link_checks_[node] = std::move(linked);
  if (!topic.empty()) link_topics_[node] = topic;
}

void PeerMonitor::start() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    watch_.start(wallSeconds());
    watch_.setMaster(ros::master::getURI());
  }
  thread_ = std::thread([this] { loop(); });
}

void PeerMonitor::loop() {
  while (!quit_ && ros::ok()) {
    probeOnce();
    std::unique_lock<std::mutex> lock(wake_mutex_);
    wake_.wait_for(lock, std::chrono::duration<double>(period_), [this] { return quit_.load(); });
  }
}

void PeerMonitor::probeOnce() {
  std::vector<std::string> nodes;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    nodes = watch_.nodes();
  }
  for (const std::string& node : nodes) {
    const live::PeerProbe probe = probePeer(node);
    const auto check = link_checks_.find(node);
    const bool linked = check == link_checks_.end() || check->second();
    std::string hint;  // alive, not linked for 5 s (connections take a moment): why, looked for every 5 s
    const auto topic = link_topics_.find(node);
    if (linked) {
      link_hint_at_.erase(node);
    } else if (probe.answered && topic != link_topics_.end()) {
      const auto [at, first] = link_hint_at_.try_emplace(node, wallSeconds());
      if (!first && wallSeconds() - at->second >= 5.0) {
        at->second = wallSeconds();
        hint = unlinkedReason(probe.uri, topic->second);
      }
    }
    std::lock_guard<std::mutex> lock(mutex_);
    watch_.setLinked(node, linked, hint);
    watch_.observe(node, probe, wallSeconds());
  }
  std::optional<std::string> stop;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const live::PeerNotice& n : watch_.review(wallSeconds())) {
      if (n.warning)
        ROS_WARN("%s: %s", owner_.c_str(), n.text.c_str());
      else
        ROS_INFO("%s: %s", owner_.c_str(), n.text.c_str());
    }
    if (watch_.stopReason() && !stop_reported_) {
      stop_reported_ = true;
      stop = watch_.stopReason();
    }
  }
  if (!stop) return;
  if (on_stop_)
    on_stop_(*stop);  // the owner decides what it means (the recorder: nothing, once the player finished)
  else
    ROS_ERROR("%s: stopping the run: %s", owner_.c_str(), stop->c_str());
}

std::optional<std::string> PeerMonitor::stopReason() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return watch_.stopReason();
}

bool PeerMonitor::connected() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return watch_.connected();
}

bool PeerMonitor::alive(const std::string& node) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return watch_.alive(node);
}

live::PeerState PeerMonitor::state(const std::string& node) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return watch_.state(node);
}

std::string PeerMonitor::describe(const std::string& node) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return watch_.describe(node);
}

}  // namespace cosmo::ros_glue
