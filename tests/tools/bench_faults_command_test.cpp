// `grip bench faults` runs for real (root: network namespaces and netfilter rules): the small room
// explored by dd-vel through a 2 s cut and 10% loss, each ending complete without a collision,
// and nothing left behind: no namespace, no process. Without root it says so.

#include <dirent.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "grip_command.hpp"
#include "small_room_map.hpp"

namespace {

using grip::testing::CommandRun;

// The bench's namespaces (grip-f<pid>p, grip-f<pid>v) whose bench is no longer running: left
// behind. Those of a bench still running (another run on this machine) are not counted.
std::set<std::string> orphaned_grip_namespaces() {
  std::set<std::string> names;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/run/netns", ec)) {
    const std::string name = e.path().filename().string();
    if (!name.starts_with("grip-f") || name.size() < 8) continue;
    const std::string pid = name.substr(6, name.size() - 7);
    if (!std::filesystem::exists("/proc/" + pid)) names.insert(name);
  }
  return names;
}

// The processes whose command line mentions `text`.
int processes_mentioning(const std::string& text) {
  int count = 0;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/proc", ec)) {
    const std::string pid = e.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(e.path() / "cmdline");
    std::string cmdline;  // its arguments, NUL-separated: read whole
    std::getline(in, cmdline, '\x01');
    count += cmdline.find(text) != std::string::npos ? 1 : 0;
  }
  return count;
}

bool have_tools() {
  return geteuid() == 0 &&
         std::system("command -v iptables >/dev/null && command -v ip >/dev/null") == 0;
}

TEST(BenchFaultsCommand, ExplorationCompletesThroughACutAndLossAndLeavesNothingBehind) {
  if (!have_tools()) GTEST_SKIP() << "needs root, iproute2 and iptables";
  const std::string out_dir = ::testing::TempDir() + "grip-bench-faults";
  const std::string json = ::testing::TempDir() + "grip-bench-faults.json";
  std::filesystem::remove_all(out_dir);
  std::filesystem::remove(json);
  const std::set<std::string> before = orphaned_grip_namespaces();
  const CommandRun r = grip::testing::run_grip(
      "bench faults --map " + grip::testing::write_small_room_map("grip-bench-faults-room.map") +
      " --robots dd-vel --profiles cut-2s,loss-10 --fault-at 3 --time-scale 2 --max-sim-time 300"
      " --domain 210 --out " +
      out_dir + " --json " + json);
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j.at("runs").size(), 2U) << r.output;
  EXPECT_EQ(j.at("runs")[0].at("profile"), "cut-2s");
  EXPECT_EQ(j.at("runs")[1].at("profile"), "loss-10");
  for (const auto& run : j.at("runs")) {
    EXPECT_EQ(run.at("result"), "complete") << run.dump() << "\n" << r.output;
    EXPECT_EQ(run.at("collisions").get<int>(), 0) << run.dump();
    EXPECT_TRUE(run.at("target_met").get<bool>()) << run.dump();
    EXPECT_FALSE(run.contains("error")) << run.dump();
  }
  // The cut ended, and the vehicle moved again after it.
  EXPECT_FALSE(j.at("runs")[0].at("recovery_s").is_null()) << j.at("runs")[0].dump();
  EXPECT_EQ(orphaned_grip_namespaces(), before);
  EXPECT_EQ(processes_mentioning(out_dir), 0);
}

TEST(BenchFaultsCommand, WithoutRootItSaysItNeedsRoot) {
  if (geteuid() != 0) {
    const CommandRun r = grip::testing::run_grip("bench faults --profiles none");
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.output.find("needs root"), std::string::npos) << r.output;
    return;
  }
  // As root: as nobody, without any capability.
  const std::string command = "setpriv --reuid=65534 --regid=65534 --clear-groups " +
                              grip::testing::kGrip + " bench faults --profiles none 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buffer[1024];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) output += buffer;
  const int status = pclose(pipe);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << output;
  EXPECT_NE(output.find("needs root"), std::string::npos) << output;
}

TEST(BenchFaultsCommand, AnUnknownProfileIsRefusedByName) {
  const CommandRun r = grip::testing::run_grip("bench faults --profiles loss-99");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("loss-99"), std::string::npos) << r.output;
}

}  // namespace
