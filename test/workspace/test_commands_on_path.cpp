// The workspace as a user meets it: after `source <devel>/setup.bash` in a fresh shell, every command-line tool
// is found by name on the PATH (catkin's global bin folder) and answers --help, and every command the README
// runs by name (`cosmo_*`, `rosrun cosmo X`) exists. Each check runs in its own `env -i` bash, as a new terminal.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "../support/run_command.hpp"

namespace {

namespace fs = std::filesystem;

const std::string kDevel = COSMO_DEVEL_PREFIX;

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string item; std::getline(in, item, sep);)
    if (!item.empty()) out.push_back(item);
  return out;
}

using Result = cosmo::test::CommandRun;

/// Runs `script` in a fresh bash (no inherited environment but HOME) that has sourced the devel space.
Result inSourcedShell(const std::string& script) {
  const std::string home = std::getenv("HOME") ? std::getenv("HOME") : "/tmp";
  const std::string cmd = "env -i HOME='" + home + "' PATH=/usr/bin:/bin bash -c 'source \"" + kDevel +
                          "/setup.bash\" && " + script + "' 2>&1";
  return cosmo::test::runCommand(cmd);
}

/// The first word of every command in the README's ```bash blocks (after `;`, `&&`, `|`, and `VAR=value`).
std::vector<std::vector<std::string>> readmeCommands() {
  std::ifstream in(std::string(COSMO_SOURCE_DIR) + "/README.md");
  std::vector<std::vector<std::string>> commands;
  bool in_block = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("```", 0) == 0) {
      in_block = !in_block && line.find("bash") != std::string::npos;
      continue;
    }
    if (!in_block) continue;
    line = line.substr(0, line.find('#'));
    for (const auto& part : std::vector<std::string>{std::regex_replace(line, std::regex("&&|\\|"), ";")}) {
      for (const auto& cmd : split(part, ';')) {
        std::istringstream words(cmd);
        std::vector<std::string> w;
        for (std::string x; words >> x;)
          if (!(w.empty() && x.find('=') != std::string::npos)) w.push_back(x);
        if (!w.empty()) commands.push_back(w);
      }
    }
  }
  return commands;
}

}  // namespace

TEST(CommandsOnPath, EveryToolIsFoundByNameAndAnswersHelp) {
  if (!fs::exists(kDevel + "/setup.bash")) GTEST_SKIP() << "no " << kDevel << "/setup.bash (not a catkin devel build)";
  const auto tools = split(COSMO_COMMANDS, ',');
  ASSERT_FALSE(tools.empty());
  // one shell for all: per tool "<tool> <path or -> <exit status of --help> <usage printed: 0/1>"
  std::string script = "for t in";
  for (const auto& tool : tools) script += " " + tool;
  script +=
      "; do p=$(command -v $t || echo -); h=$($t --help 2>&1); s=$?; "
      "u=$(echo \"$h\" | grep -ci usage); echo \"$t $p $s $u\"; done";
  const Result r = inSourcedShell(script);
  ASSERT_EQ(r.status, 0) << r.output;
  std::istringstream lines(r.output);
  std::set<std::string> seen;
  for (std::string tool, path; lines >> tool >> path;) {
    int status = -1, usage = 0;
    lines >> status >> usage;
    seen.insert(tool);
    EXPECT_EQ(path, kDevel + "/bin/" + tool)
        << tool << " is not on the PATH after sourcing " << kDevel << "/setup.bash";
    EXPECT_EQ(status, 0) << tool << " --help exits with " << status;
    EXPECT_GT(usage, 0) << tool << " --help prints no usage";
  }
  EXPECT_EQ(seen.size(), tools.size()) << r.output;
}

TEST(CommandsOnPath, TheReadmesCommandsExist) {
  if (!fs::exists(kDevel + "/setup.bash")) GTEST_SKIP() << "no " << kDevel << "/setup.bash (not a catkin devel build)";
  std::set<std::string> by_name, by_rosrun;
  for (const auto& w : readmeCommands()) {
    if (w[0].rfind("cosmo_", 0) == 0) by_name.insert(w[0]);
    if (w[0] == "rosrun" && w.size() >= 3 && w[1] == "cosmo") by_rosrun.insert(w[2]);
  }
  EXPECT_FALSE(by_name.empty()) << "the README runs no cosmo_* command in a ```bash block";
  std::string script = "m=; for c in";
  for (const auto& c : by_name) script += " " + c;
  script += "; do command -v $c > /dev/null || m=\"$m $c\"; done; echo $m; test -z \"$m\"";
  const Result r = inSourcedShell(script);
  EXPECT_EQ(r.status, 0) << "the README runs" << r.output << ", not on the PATH after sourcing the workspace";
  for (const auto& c : by_rosrun)
    EXPECT_TRUE(fs::exists(kDevel + "/lib/cosmo/" + c)) << "README runs `rosrun cosmo " << c << "`: no such program";
}
