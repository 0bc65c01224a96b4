// DDS Security on the wire: the on/off matrix between processes (grip_dds_security_probe, one
// identity per process: security_probe.cpp says why), with the keys `grip keys init` makes, and
// the keys command itself. Every participant on the loopback-only configuration, each test on
// a domain of its own (160-169).

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <future>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "grip/platform/dds/security.hpp"
#include "grip_command.hpp"
#include "test_paths.hpp"

namespace grip::platform::dds {
namespace {

namespace fs = std::filesystem;

using ::grip::testing::kGrip;
using ProcessRun = ::grip::testing::CommandRun;
const std::string kProbe = GRIP_BINARY_DIR "/bin/grip_dds_security_probe";

// Runs a command line, stdout and stderr captured.
ProcessRun run(const std::string& command) {
  return ::grip::testing::run_command(command + " 2>&1");
}

// The probe in a process of its own, started now, its result later.
std::future<ProcessRun> probe(int domain, const std::string& keys, const std::string& action,
                              const std::string& topics, double seconds) {
  const std::string command = kProbe + " " + std::to_string(domain) + " " + keys + " " + action +
                              " " + topics + " " + std::to_string(seconds);
  return std::async(std::launch::async, [command] { return run(command); });
}

// The count a probe printed for `topic` ("grip_plan received 12"), -1 if none.
long count_of(const ProcessRun& r, const std::string& topic) {
  const std::size_t at = r.output.find(topic + " ");
  if (at == std::string::npos) return -1;
  const std::size_t number = r.output.find_first_of("0123456789", at + topic.size());
  if (number == std::string::npos) return -1;
  return std::stol(r.output.substr(number));
}

class DdsSecurity : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(GRIP_BINARY_DIR) / "tests" /
           ("security-" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    const ProcessRun made = run(kGrip + " keys init " + dir_.string() + " --days 2");
    ASSERT_EQ(made.status, 0) << made.output;
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string keys(const char* role) const { return (dir_ / role).string(); }

  fs::path dir_;
};

// Long enough for the handshake (about a second) and a few seconds of samples.
constexpr double kSeconds = 5.0;

TEST_F(DdsSecurity, SecuredPlannerAndVehicleExchangePlans) {
  auto planner = probe(160, keys("planner"), "write", "grip_plan", kSeconds);
  auto vehicle = probe(160, keys("vehicle"), "read", "grip_plan", kSeconds);
  const ProcessRun wrote = planner.get();
  const ProcessRun taken = vehicle.get();
  ASSERT_EQ(wrote.status, 0) << wrote.output;
  ASSERT_EQ(taken.status, 0) << taken.output;
  EXPECT_GT(count_of(taken, "grip_plan"), 0) << taken.output;
}

TEST_F(DdsSecurity, AnUnauthenticatedParticipantReadsNoPlanWhileTheVehicleReadsThem) {
  auto planner = probe(161, keys("planner"), "write", "grip_plan", kSeconds);
  auto stranger = probe(161, "-", "read", "grip_plan", kSeconds);
  auto vehicle = probe(161, keys("vehicle"), "read", "grip_plan", kSeconds);
  const ProcessRun wrote = planner.get();
  const ProcessRun unauthenticated = stranger.get();
  const ProcessRun authenticated = vehicle.get();
  ASSERT_EQ(wrote.status, 0) << wrote.output;
  ASSERT_EQ(unauthenticated.status, 0) << unauthenticated.output;
  EXPECT_EQ(count_of(unauthenticated, "grip_plan"), 0) << unauthenticated.output;
  EXPECT_GT(count_of(authenticated, "grip_plan"), 0) << authenticated.output;
}

TEST_F(DdsSecurity, AnUnauthenticatedParticipantInjectsNoPlanStateMapOrGoal) {
  const std::string topics = "grip_plan grip_vehicle_state grip_map_update grip_goal";
  // The `explore` identity reads every topic: what an unauthenticated writer sends it would
  // reach it, were it let in.
  auto stranger = probe(162, "-", "write", topics, kSeconds);
  auto secured = probe(162, keys("explore"), "read", topics, kSeconds);
  const ProcessRun injected = stranger.get();
  const ProcessRun taken = secured.get();
  ASSERT_EQ(injected.status, 0) << injected.output;
  ASSERT_EQ(taken.status, 0) << taken.output;
  for (const char* topic : {"grip_plan", "grip_vehicle_state", "grip_map_update", "grip_goal"}) {
    EXPECT_GT(count_of(injected, topic), 0) << injected.output;
    EXPECT_EQ(count_of(taken, topic), 0) << topic << "\n" << taken.output;
  }
  // The same reader hears an authenticated vehicle on those topics.
  auto vehicle = probe(163, keys("vehicle"), "write",
                       "grip_vehicle_state grip_map_update grip_goal", kSeconds);
  auto planner =
      probe(163, keys("explore"), "read", "grip_vehicle_state grip_map_update grip_goal", kSeconds);
  const ProcessRun heard = planner.get();
  vehicle.get();
  for (const char* topic : {"grip_vehicle_state", "grip_map_update", "grip_goal"}) {
    EXPECT_GT(count_of(heard, topic), 0) << topic << "\n" << heard.output;
  }
}

TEST_F(DdsSecurity, AnAuthenticatedParticipantWithoutThePermissionCannotWritePlans) {
  auto vehicle = probe(164, keys("vehicle"), "write", "grip_plan grip_vehicle_state", 1.0);
  const ProcessRun r = vehicle.get();
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("grip_plan refused"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Not Allowed By Security"), std::string::npos) << r.output;
  // It may write what its permissions allow.
  EXPECT_EQ(r.output.find("grip_vehicle_state refused"), std::string::npos) << r.output;
}

TEST_F(DdsSecurity, PermissionsOrAnIdentityOfAnotherCaAreRejected) {
  const fs::path other = dir_ / "other";
  const ProcessRun made = run(kGrip + " keys init " + other.string());
  ASSERT_EQ(made.status, 0) << made.output;
  // This CA's identity with the other CA's permissions for the same subject.
  const fs::path mixed = dir_ / "mixed";
  fs::copy(dir_ / "vehicle", mixed);
  fs::copy_file(other / "vehicle" / "permissions.p7s", mixed / "permissions.p7s",
                fs::copy_options::overwrite_existing);

  auto planner = probe(165, keys("planner"), "write", "grip_plan", kSeconds);
  auto with_mixed = probe(165, mixed.string(), "read", "grip_plan", kSeconds);
  auto of_other = probe(165, (other / "vehicle").string(), "read", "grip_plan", kSeconds);
  planner.get();
  const ProcessRun m = with_mixed.get();
  const ProcessRun o = of_other.get();
  // Refused when it is created, or never matched: no plan either way.
  EXPECT_TRUE(m.status == 3 || count_of(m, "grip_plan") == 0) << m.output;
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_EQ(count_of(o, "grip_plan"), 0) << o.output;
}

TEST_F(DdsSecurity, KeysInitMakesEveryRolesFolderWithPrivateKeys) {
  for (const char* role : {"planner", "vehicle", "operator", "explore"}) {
    const SecurityFiles files = SecurityFiles::from_directory(keys(role));
    EXPECT_TRUE(files.check().ok()) << role;
    struct stat st {};
    ASSERT_EQ(stat(files.private_key.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0600U) << files.private_key;
    // Signed with the content included: the document is readable inside.
    const ProcessRun inside = run("grep -c '<permissions>' " + files.permissions);
    EXPECT_EQ(inside.output, "1\n") << files.permissions;
  }
  // The keys folder itself stands for each command's role.
  EXPECT_EQ(SecurityFiles::from_directory(dir_.string(), "planner").identity_certificate,
            (dir_ / "planner" / "identity.pem").string());
  struct stat st {};
  ASSERT_EQ(stat((dir_ / "ca" / "ca.key").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600U);
}

TEST_F(DdsSecurity, KeysInitRefusesToOverwriteWithoutForce) {
  const std::string before = run("cat " + keys("planner") + "/identity.pem").output;
  const ProcessRun again = run(kGrip + " keys init " + dir_.string());
  EXPECT_EQ(again.status, 2);
  EXPECT_NE(again.output.find("--force"), std::string::npos) << again.output;
  EXPECT_EQ(run("cat " + keys("planner") + "/identity.pem").output, before);
  const ProcessRun forced = run(kGrip + " keys init " + dir_.string() + " --force");
  EXPECT_EQ(forced.status, 0) << forced.output;
  EXPECT_NE(run("cat " + keys("planner") + "/identity.pem").output, before);
}

TEST_F(DdsSecurity, AnIncompleteFolderIsRefusedNamingTheMissingFile) {
  fs::remove(dir_ / "planner" / "permissions.p7s");
  const SecurityFiles files = SecurityFiles::from_directory(keys("planner"));
  const Status checked = files.check();
  ASSERT_FALSE(checked.ok());
  EXPECT_NE(checked.error().message.find("permissions.p7s"), std::string::npos)
      << checked.error().message;
  const ProcessRun planner = run(
      kGrip + " planner --robot dd-vel --domain 166 --duration 1 --security " + keys("planner"));
  EXPECT_EQ(planner.status, 2);
  EXPECT_NE(planner.output.find("permissions.p7s"), std::string::npos) << planner.output;
  const ProcessRun sim = run(kGrip + " sim --lockstep --domain 166 --security " + keys("planner"));
  EXPECT_EQ(sim.status, 2);
  EXPECT_NE(sim.output.find("permissions.p7s"), std::string::npos) << sim.output;
}

TEST_F(DdsSecurity, PlannerAndSimulatorWithoutSecuritySayTheLinkIsUnauthenticated) {
  const ProcessRun planner = run(kGrip +
                                 " planner --robot dd-vel --domain 167 --duration 1 "
                                 "--startup-timeout 1");
  EXPECT_NE(planner.output.find("UNAUTHENTICATED"), std::string::npos) << planner.output;
  const ProcessRun sim = run("timeout -s INT 3 " + kGrip + " sim --lockstep --domain 167");
  EXPECT_NE(sim.output.find("UNAUTHENTICATED"), std::string::npos) << sim.output;
  // With the keys, no warning.
  const ProcessRun secured = run(kGrip +
                                 " planner --robot dd-vel --domain 167 --duration 1 "
                                 "--startup-timeout 1 --security " +
                                 dir_.string());
  EXPECT_EQ(secured.output.find("UNAUTHENTICATED"), std::string::npos) << secured.output;
  EXPECT_NE(secured.output.find("DDS Security"), std::string::npos) << secured.output;
}

// The hostile participant against a secured planner and simulator (two processes with
// their own keys): for the whole exploration of a small room in lockstep it writes plans of full
// speed ahead, states stamped far in the future, map updates and goals, and reads plans.
TEST_F(DdsSecurity, AnUnauthenticatedInjectorChangesNothingInASecuredExploration) {
  const fs::path map = dir_ / "room.map";
  std::ofstream(map) << "type octile\nheight 10\nwidth 10\nmap\n"
                     << "@@@@@@@@@@\n@........@\n@........@\n@...@@...@\n@...@@...@\n"
                     << "@........@\n@.@@@@@..@\n@........@\n@........@\n@@@@@@@@@@\n";
  const std::string topics = "grip_plan grip_vehicle_state grip_map_update grip_goal";
  auto injector = probe(168, "-", "write", topics, 30.0);
  auto eavesdropper = probe(168, "-", "read", "grip_plan", 30.0);
  const fs::path planner_report = dir_ / "planner.json";
  auto planner = grip::testing::ChildProcess::spawn(
      {"/bin/sh", "-c",
       "exec " + kGrip + " planner --robot dd-vel --domain 168 --startup-timeout 120 --security " +
           dir_.string() + " --report " + planner_report.string() + " > " +
           (dir_ / "planner.log").string() + " 2>&1"});
  ASSERT_TRUE(planner.has_value());
  const ProcessRun sim = run(kGrip + " sim --lockstep --robot dd-vel --map " + map.string() +
                             " --max-sim-time 300 --startup-timeout 120 --domain 168 --security " +
                             dir_.string() + " --report " + (dir_ / "sim.json").string());
  planner->kill(SIGINT);
  planner->wait();
  EXPECT_EQ(sim.status, 0) << sim.output << "\nplanner:\n"  // complete
                           << run("tail -n 40 " + (dir_ / "planner.log").string()).output;
  EXPECT_NE(sim.output.find("collisions 0,"), std::string::npos) << sim.output;
  EXPECT_NE(sim.output.find("(rejected 0,"), std::string::npos) << sim.output;
  const ProcessRun rejected = run("grep -A 4 '\"rejected\"' " + planner_report.string());
  EXPECT_NE(rejected.output.find("\"goal\": 0"), std::string::npos) << rejected.output;
  EXPECT_NE(rejected.output.find("\"map_update\": 0"), std::string::npos) << rejected.output;
  EXPECT_NE(rejected.output.find("\"vehicle_state\": 0"), std::string::npos) << rejected.output;
  const ProcessRun injected = injector.get();
  EXPECT_GT(count_of(injected, "grip_plan"), 0) << injected.output;
  const ProcessRun heard = eavesdropper.get();
  EXPECT_EQ(count_of(heard, "grip_plan"), 0) << heard.output;
  // The attempts are in the planner's log.
  const ProcessRun logged =
      run("grep -c 'DDS Security refused a peer' " + (dir_ / "planner.log").string());
  EXPECT_NE(logged.output, "0\n") << logged.output;
}

}  // namespace
}  // namespace grip::platform::dds
