#pragma once
// A single-node Slurm cluster of the test's own: munged, slurmctld and slurmd (Debian's slurm-wlm and munge) as the
// user who runs the test, with a minimal slurm.conf (proctrack/linuxproc, task/none, one node = this host, its own
// state and spool folders, log files and free ports, all under `dir`), started in the foreground as children of the
// test (they die with it) and stopped by their pids. `why_not` says why it could not start.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "cosmo/suite/child_process.hpp"
#include "cosmo/suite/slurm.hpp"

namespace suite_e2e {

class SlurmCluster {
 public:
  explicit SlurmCluster(const std::filesystem::path& dir) : dir_(dir) {
    namespace fs = std::filesystem;
    for (const char* tool : {"munged", "slurmctld", "slurmd", "sbatch", "squeue", "sinfo"})
      if (!onPath(tool)) {
        why_not_ = std::string(tool) + " is not installed (Debian: slurm-wlm, munge)";
        return;
      }
    for (const char* sub : {"munge", "state", "spool", "log"}) fs::create_directories(dir_ / sub);
    fs::permissions(dir_ / "munge", fs::perms::owner_all, fs::perm_options::replace);
    writeKey();
    const std::string sock = (dir_ / "munge" / "munge.sock").string();
    pids_.push_back(cosmo::suite::spawnChild(
        {which("munged"), "-F", "-f", "--socket=" + sock, "--key-file=" + (dir_ / "munge" / "munge.key").string(),
         "--pid-file=" + (dir_ / "munge" / "munged.pid").string(), "--seed-file=" + (dir_ / "munge" / "seed").string(),
         "--log-file=" + (dir_ / "log" / "munged.log").string()},
        (dir_ / "log" / "munged.out").string()));
    if (!waitFor([&] { return fs::exists(sock); }, 10)) {
      why_not_ = "munged did not start: " + cosmo::suite::tailOfFile((dir_ / "log" / "munged.out").string(), 3);
      return;
    }
    writeConfig(sock);
    ::setenv("SLURM_CONF", (dir_ / "slurm.conf").c_str(), 1);
    pids_.push_back(cosmo::suite::spawnChild({which("slurmctld"), "-D", "-i"}, (dir_ / "log" / "slurmctld.out").string()));
    pids_.push_back(cosmo::suite::spawnChild({which("slurmd"), "-D"}, (dir_ / "log" / "slurmd.out").string()));
    if (!waitFor([&] { return nodeIdle(); }, 30))
      why_not_ = "the node did not come up: " + cosmo::suite::tailOfFile((dir_ / "log" / "slurmctld.out").string(), 3) +
                 cosmo::suite::tailOfFile((dir_ / "log" / "slurmd.out").string(), 3);
  }

  ~SlurmCluster() {
    if (why_not_.empty()) {  // whatever is left in this cluster's own queue (a failed test)
      int status = 0;
      cosmo::suite::captureCommand({"scancel", "--full", "--state=PENDING"}, status);
      cosmo::suite::captureCommand({"scancel", "--full", "--state=RUNNING"}, status);
    }
    for (auto it = pids_.rbegin(); it != pids_.rend(); ++it) {
      ::kill(*it, SIGTERM);
      int status = 0;
      for (int i = 0; i < 50 && ::waitpid(*it, &status, WNOHANG) == 0; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (::waitpid(*it, &status, WNOHANG) == 0) {
        ::kill(*it, SIGKILL);
        ::waitpid(*it, &status, 0);
      }
    }
    ::unsetenv("SLURM_CONF");
  }

  const std::string& whyNot() const { return why_not_; }

 private:
  std::filesystem::path dir_;
  std::vector<pid_t> pids_;
  std::string why_not_;

  static std::string which(const std::string& tool) {
    for (const char* d : {"/usr/sbin/", "/usr/bin/", "/sbin/", "/bin/"})
      if (std::filesystem::exists(std::string(d) + tool)) return std::string(d) + tool;
    return "";
  }
  static bool onPath(const std::string& tool) { return !which(tool).empty(); }

  template <class F>
  static bool waitFor(F ready, double seconds) {
    const double end = cosmo::suite::monotonicSeconds() + seconds;
    while (cosmo::suite::monotonicSeconds() < end) {
      if (ready()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    return ready();
  }

  static int freePort() {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof a;
    ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
    const int port = ntohs(a.sin_port);
    ::close(fd);
    return port;
  }

  void writeKey() {
    std::random_device rd;
    std::ofstream key(dir_ / "munge" / "munge.key", std::ios::binary);
    for (int i = 0; i < 1024; ++i) key.put(static_cast<char>(rd() & 0xff));
    key.close();
    std::filesystem::permissions(dir_ / "munge" / "munge.key", std::filesystem::perms::owner_read,
                                 std::filesystem::perm_options::replace);
  }

  void writeConfig(const std::string& sock) {
    char host[256] = {0};
    ::gethostname(host, sizeof host - 1);
    std::string h = host;
    h = h.substr(0, h.find('.'));
    const long cpus = std::max(1L, ::sysconf(_SC_NPROCESSORS_ONLN));
    const char* user = std::getenv("USER");
    const std::string me = user && *user ? user : (::getuid() == 0 ? "root" : std::to_string(::getuid()));
    std::ofstream c(dir_ / "slurm.conf");
    c << "ClusterName=cosmotest\nSlurmctldHost=" << h << "(127.0.0.1)\nSlurmctldPort=" << freePort()
      << "\nSlurmdPort=" << freePort() << "\nSlurmUser=" << me << "\nSlurmdUser=" << me
      << "\nAuthType=auth/munge\nAuthInfo=socket=" << sock << "\nCredType=cred/munge\nStateSaveLocation="
      << (dir_ / "state").string() << "\nSlurmdSpoolDir=" << (dir_ / "spool").string()
      << "\nSlurmctldPidFile=" << (dir_ / "state" / "slurmctld.pid").string()
      << "\nSlurmdPidFile=" << (dir_ / "spool" / "slurmd.pid").string()
      << "\nSlurmctldLogFile=" << (dir_ / "log" / "slurmctld.log").string()
      << "\nSlurmdLogFile=" << (dir_ / "log" / "slurmd.log").string()
      << "\nProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\nJobAcctGatherType=jobacct_gather/none\n"
         "AccountingStorageType=accounting_storage/none\nJobCompType=jobcomp/none\nMpiDefault=none\n"
         "SchedulerType=sched/backfill\nSelectType=select/cons_tres\nSelectTypeParameters=CR_CPU\n"
         "ReturnToService=2\nSwitchType=switch/none\nNodeName="
      << h << " NodeAddr=127.0.0.1 CPUs=" << cpus << " State=UNKNOWN\nPartitionName=test Nodes=ALL Default=YES "
      << "MaxTime=INFINITE State=UP\n";
  }

  static bool nodeIdle() {
    int status = 0;
    const std::string out = cosmo::suite::captureCommand({"sinfo", "-h", "-o", "%t"}, status);
    return status == 0 && out.find("idle") != std::string::npos;
  }
};

}  // namespace suite_e2e
