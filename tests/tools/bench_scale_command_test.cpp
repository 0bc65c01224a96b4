// `grip bench scale` explores one map made larger for real (here: the small room, and 2 x 2 of
// it side by side, at 10 cells a metre, then the room at 20, briefly, in lockstep; and the room
// as a ROS map, tiled as one): a row per
// map with its cell count, the planner's start-up, memory and every cycle phase, one sensor
// range for all of them, and the chart of their p99 against the cell count where
// tools/grip/scale_chart.hpp's layout puts them; and bad options are refused.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "grip_command.hpp"
#include "png_image.hpp"
#include "small_room_map.hpp"

namespace {

using grip::testing::CommandRun;

// The layout documented in tools/grip/scale_chart.hpp.
constexpr double kLeft = 80.0;
constexpr double kTop = 64.0;
constexpr double kRightMargin = 170.0;
constexpr double kBottomMargin = 60.0;
constexpr const char* kPhases[] = {"prepare_ms", "retain_ms", "grow_ms", "commit_ms", "compute_ms"};
constexpr grip::testing::Rgb kCycle{0, 0, 0};

// Each run's whole-cycle p99 has its black marker where the layout puts it.
void expect_cycle_markers(const std::string& png, const nlohmann::json& runs) {
  const grip::testing::Image image(png);
  ASSERT_TRUE(image.ok()) << png;
  ASSERT_EQ(image.width(), 1000);
  ASSERT_EQ(image.height(), 600);
  double cells_lo = INFINITY;
  double cells_hi = 0.0;
  double ms_lo = INFINITY;
  double ms_hi = 0.0;
  for (const auto& run : runs) {
    cells_lo = std::min(cells_lo, run.at("cells").get<double>());
    cells_hi = std::max(cells_hi, run.at("cells").get<double>());
    for (const char* phase : kPhases) {
      const double ms = run.at(phase).at("p99").get<double>();
      if (!(ms > 0.0)) continue;
      ms_lo = std::min(ms_lo, std::max(ms, 1e-3));
      ms_hi = std::max(ms_hi, ms);
    }
  }
  const double x_lo = std::floor(std::log10(cells_lo));
  const double x_hi = std::max(std::ceil(std::log10(cells_hi)), x_lo + 1.0);
  const double y_lo = std::floor(std::log10(ms_lo));
  const double y_hi = std::max(std::ceil(std::log10(ms_hi)), y_lo + 1.0);
  const double width = 1000 - kLeft - kRightMargin;
  const double height = 600 - kTop - kBottomMargin;
  for (const auto& run : runs) {
    const double x =
        kLeft + (std::log10(run.at("cells").get<double>()) - x_lo) / (x_hi - x_lo) * width;
    const double y =
        kTop + height -
        (std::log10(run.at("compute_ms").at("p99").get<double>()) - y_lo) / (y_hi - y_lo) * height;
    // Beside the centre, off the axis a point at a whole decade sits on.
    EXPECT_TRUE(image.is(static_cast<int>(std::lround(x)) + 3, static_cast<int>(std::lround(y)) - 3,
                         kCycle))
        << "no cycle marker at " << x << ", " << y << " for " << run.dump();
  }
  // Nothing black in the plot area's middle column above the markers' band.
  EXPECT_FALSE(image.is(static_cast<int>(kLeft + width / 2), static_cast<int>(kTop + 2), kCycle));
}

TEST(BenchScaleCommand, ExploresTheMapAtEachResolutionAndTabulatesItsCost) {
  const std::string out_dir = ::testing::TempDir() + "grip-bench-scale";
  const std::string json = ::testing::TempDir() + "grip-bench-scale.json";
  std::filesystem::remove_all(out_dir);
  CommandRun r = grip::testing::run_grip(
      "bench scale --map " + grip::testing::write_small_room_map("grip-bench-scale-room.map") +
      " --tiles 1,2 --subdivisions 10 --max-sim-time 10 --out " + out_dir + " --json " + json +
      " --png " + json + ".png");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("wrote " + json + ".png"), std::string::npos) << r.output;
  r = grip::testing::run_grip("bench scale --map " +
                              grip::testing::write_small_room_map("grip-bench-scale-room.map") +
                              " --tiles 1 --subdivisions 20 --max-sim-time 10 --out " + out_dir +
                              " --json " + json + ".fine");
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j.at("runs").size(), 2U) << r.output;
  EXPECT_EQ(j.at("mode"), "lockstep");
  std::ifstream in_fine(json + ".fine");
  const nlohmann::json j_fine = nlohmann::json::parse(in_fine);
  ASSERT_EQ(j_fine.at("runs").size(), 1U) << r.output;
  EXPECT_EQ(j.at("runs")[0].at("cells").get<int>(), 100 * 100);
  EXPECT_EQ(j.at("runs")[1].at("cells").get<int>(), 200 * 200);  // 2 x 2 rooms
  EXPECT_EQ(j.at("runs")[1].at("tiles").get<int>(), 2);
  EXPECT_EQ(j_fine.at("runs")[0].at("cells").get<int>(), 200 * 200);  // the room at 5 cm
  EXPECT_EQ(j_fine.at("runs")[0].at("subdivision").get<int>(), 20);
  // The tiling is a map file of its own, four rooms in a square.
  std::ifstream tiled(out_dir + "/grip-bench-scale-room-tiled2.map");
  std::string header;
  for (std::string line; header.size() < 40 && std::getline(tiled, line);) header += line + "|";
  EXPECT_EQ(header.rfind("type octile|height 20|width 20|map|", 0), 0U) << header;
  // One sensor for every size: the range `auto` gives the 10 m room, not the 20 m tiling's.
  EXPECT_EQ(j.at("sensor_range_m").get<double>(), 1.0);
  for (const auto& run : {j.at("runs")[0], j.at("runs")[1], j_fine.at("runs")[0]}) {
    std::ifstream report_in(run.at("report").get<std::string>());
    const nlohmann::json report = nlohmann::json::parse(report_in);
    EXPECT_NE(report.at("parameters").get<std::string>().find("\n  range_m: 1 "), std::string::npos)
        << report.at("parameters").get<std::string>();
    EXPECT_EQ(run.at("collisions").get<int>(), 0) << run.dump();
    EXPECT_EQ(run.at("cycles").get<int>(), 201) << run.dump();  // 10 s at 0.05 s, and the first
    const auto& startup = run.at("planner_startup");
    EXPECT_GT(startup.at("map_sync_s").get<double>(), 0.0) << run.dump();
    EXPECT_GE(startup.at("planning_s").get<double>(), startup.at("map_sync_s").get<double>());
    EXPECT_GT(run.at("peak_rss_mb").get<double>(), 1.0) << run.dump();
    for (const char* phase : {"prepare_ms", "retain_ms", "grow_ms", "commit_ms", "compute_ms"}) {
      const auto& p = run.at(phase);
      EXPECT_LE(p.at("p50").get<double>(), p.at("p99").get<double>()) << phase;
      EXPECT_LE(p.at("p99").get<double>(), p.at("max").get<double>()) << phase;
    }
    EXPECT_GT(run.at("compute_ms").at("p50").get<double>(), 0.0);
  }
  EXPECT_NE(r.output.find("     1   20      40000"), std::string::npos) << r.output;
  expect_cycle_markers(json + ".png", j.at("runs"));
}

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The small room as a ROS map (100 x 100 pixels at 0.1 m), with a block of unknown pixels in a
// corner; its path (the YAML).
std::string write_small_room_ros_map(const std::string& stem) {
  const char* rows[] = {"@@@@@@@@@@", "@........@", "@........@", "@...@@...@", "@...@@...@",
                        "@........@", "@.@@@@@..@", "@........@", "@........@", "@@@@@@@@@@"};
  const std::string dir = ::testing::TempDir();
  std::ofstream pgm(dir + stem + ".pgm", std::ios::binary);
  pgm << "P5\n100 100\n255\n";
  for (int y = 0; y < 100; ++y) {
    for (int x = 0; x < 100; ++x) {
      const bool unknown = x >= 10 && x < 20 && y >= 10 && y < 20;
      pgm << static_cast<char>(unknown ? 205 : rows[y / 10][x / 10] == '.' ? 254 : 0);
    }
  }
  std::ofstream(dir + stem + ".yaml") << "image: " << stem << ".pgm\nresolution: 0.1\n"
                                      << "origin: [-2.0, 3.5, 0.0]\nnegate: 0\n"
                                      << "occupied_thresh: 0.65\nfree_thresh: 0.196\n";
  return dir + stem + ".yaml";
}

TEST(BenchScaleCommand, ARosMapIsTiledAsARosMapAtItsOwnResolution) {
  const std::string out_dir = ::testing::TempDir() + "grip-bench-scale-ros";
  const std::string json = ::testing::TempDir() + "grip-bench-scale-ros.json";
  std::filesystem::remove_all(out_dir);
  const std::string map = write_small_room_ros_map("grip-bench-scale-ros-room");
  const CommandRun r =
      grip::testing::run_grip("bench scale --map " + map + " --tiles 1,2 --max-sim-time 5 --out " +
                              out_dir + " --json " + json);
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j.at("runs").size(), 2U) << r.output;
  EXPECT_EQ(j.at("runs")[0].at("cells").get<int>(), 100 * 100);
  EXPECT_EQ(j.at("runs")[1].at("cells").get<int>(), 200 * 200);
  EXPECT_TRUE(j.at("runs")[1].at("subdivision").is_null()) << j.dump();
  for (const auto& run : j.at("runs")) {
    EXPECT_EQ(run.at("collisions").get<int>(), 0) << run.dump();
    EXPECT_EQ(run.at("cycles").get<int>(), 101) << run.dump();
  }
  // The tiling: a YAML at the map's resolution and origin, and its PGM four rooms in a square,
  // the unknown pixels obstacles as the simulator reads them.
  const std::string yaml_text = contents(out_dir + "/grip-bench-scale-ros-room-tiled2.yaml");
  EXPECT_NE(yaml_text.find("image: grip-bench-scale-ros-room-tiled2.pgm\n"), std::string::npos)
      << yaml_text;
  EXPECT_NE(yaml_text.find("resolution: 0.1\n"), std::string::npos) << yaml_text;
  EXPECT_NE(yaml_text.find("origin: [-2, 3.5, 0]\n"), std::string::npos) << yaml_text;
  const std::string pgm = contents(out_dir + "/grip-bench-scale-ros-room-tiled2.pgm");
  const std::string header = "P5\n200 200\n255\n";
  ASSERT_EQ(pgm.size(), header.size() + 200 * 200);
  ASSERT_EQ(pgm.substr(0, header.size()), header);
  const auto pixel = [&](int x, int y) {
    return static_cast<unsigned char>(
        pgm[header.size() + static_cast<std::size_t>(y) * 200 + static_cast<std::size_t>(x)]);
  };
  for (const int dx : {0, 100}) {
    for (const int dy : {0, 100}) {
      EXPECT_EQ(pixel(dx + 25, dy + 15), 254) << dx << ", " << dy;  // free
      EXPECT_EQ(pixel(dx + 45, dy + 35), 0) << dx << ", " << dy;    // the pillar
      EXPECT_EQ(pixel(dx + 15, dy + 15), 0) << dx << ", " << dy;    // unknown: an obstacle
    }
  }
}

TEST(BenchScaleCommand, BadOptionsAreRefusedNamingWhatIsWrong) {
  CommandRun r = grip::testing::run_grip("bench scale");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--map"), std::string::npos) << r.output;
  r = grip::testing::run_grip("bench scale --map /nonexistent/grip.map");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("/nonexistent/grip.map"), std::string::npos) << r.output;
  r = grip::testing::run_grip("bench scale --map " +
                              grip::testing::write_small_room_map("grip-bench-scale-bad.map") +
                              " --subdivisions 0");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--subdivisions"), std::string::npos) << r.output;
  r = grip::testing::run_grip("bench scale --map " +
                              grip::testing::write_small_room_map("grip-bench-scale-bad.map") +
                              " --tiles 17");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--tiles"), std::string::npos) << r.output;
  r = grip::testing::run_grip("bench scale --map " +
                              write_small_room_ros_map("grip-bench-scale-ros-bad") +
                              " --subdivisions 20");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--subdivisions is for MovingAI maps"), std::string::npos) << r.output;
}

}  // namespace
