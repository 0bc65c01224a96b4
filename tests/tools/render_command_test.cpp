// `grip render REPORT --speed-profile OUT.png` run as users run it, on hand-written reports: the
// picture has the size asked for and its curve, maximum-speed line and collision marks where
// the layout documented in tools/grip/speed_profile_chart.hpp puts them (read back with cairo);
// the printed summary has the hand-computed numbers; every bad input is refused with a
// message naming the file and the problem, and a non-zero exit.

#include <cairo.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "grip_command.hpp"
#include "png_image.hpp"

namespace {

using grip::testing::CommandRun;
using nlohmann::json;

// The layout documented in tools/grip/speed_profile_chart.hpp.
constexpr double kLeft = 70.0;
constexpr double kTop = 64.0;
constexpr double kRightMargin = 25.0;
constexpr double kBottomMargin = 56.0;
constexpr double kHeadroom = 1.15;

using grip::testing::Image;
using grip::testing::Rgb;

constexpr Rgb kSpeed{0, 102, 204};
constexpr Rgb kAverage{204, 102, 0};
constexpr Rgb kMaxLine{51, 51, 51};
constexpr Rgb kCollision{255, 0, 0};
constexpr Rgb kBrakingBound{51, 166, 51};
constexpr Rgb kTurningBound{153, 51, 204};

// Where the chart puts a time and a speed, for an image of w x h pixels whose time axis ends at
// t_max_s and whose fastest speed (the maximum, or a faster sample) is top_m_s.
struct Layout {
  int w = 1200;
  int h = 500;
  double t_max_s;
  double top_m_s;

  double x(double t_s) const { return kLeft + t_s / t_max_s * (w - kLeft - kRightMargin); }
  double y(double v_m_s) const {
    const double bottom = h - kBottomMargin;
    return bottom - v_m_s / (kHeadroom * top_m_s) * (bottom - kTop);
  }
  int plot_top() const { return static_cast<int>(kTop); }
  int plot_bottom() const { return static_cast<int>(h - kBottomMargin); }
};

class RenderCommand : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const {
    return ::testing::TempDir() + "grip-render-" + name;
  }
  std::string write_text(const std::string& name, const std::string& text) const {
    const std::string p = path(name);
    std::ofstream(p) << text;
    return p;
  }
  // A report as `grip explore --report` writes it, with only what rendering reads.
  static nlohmann::json report(const std::vector<std::array<double, 2>>& profile,
                               double max_speed_m_s = 3.0) {
    nlohmann::json j;
    j["robot"] = "dd-vel";
    j["world"] = "rooms";
    j["result"] = "complete";
    j["max_speed_m_s"] = max_speed_m_s;
    j["mean_speed_fraction"] = 0.75;
    j["collision_events"] = nlohmann::json::array();
    nlohmann::json p = nlohmann::json::array();
    for (const auto& s : profile) p.push_back({s[0], s[1]});
    j["speed_profile"] = p;
    return j;
  }
  std::string write_report(const std::string& name, const nlohmann::json& j) const {
    return write_text(name, j.dump());
  }
  CommandRun render(const std::string& report_path, const std::string& png,
                    const std::string& extra = "") const {
    return grip::testing::run_grip("render " + report_path + " --speed-profile " + png + " " +
                                   extra);
  }
};

// n samples at 0.05 s ticks with the speed given by f(t).
template <typename F>
std::vector<std::array<double, 2>> ticks(int n, F speed_of_t) {
  std::vector<std::array<double, 2>> p;
  for (int i = 1; i <= n; ++i) {
    const double t = 0.05 * i;
    p.push_back({t, speed_of_t(t)});
  }
  return p;
}

// Every row of the curve's colour in column x lies within 2 px of y, and there is one.
void expect_curve_at(const Image& img, const Layout& l, double x, double y, Rgb colour) {
  const std::vector<int> rows =
      img.rows_with(static_cast<int>(x), colour, l.plot_top(), l.plot_bottom());
  ASSERT_FALSE(rows.empty()) << "no curve in column " << x << " (expected near row " << y << ")";
  for (const int row : rows) EXPECT_NEAR(row, y, 2.0) << "column " << x;
}

TEST_F(RenderCommand, ALongConstantSpeedRunIsAHorizontalLineAtItsHeightUnderTheDashedMaximum) {
  // 900 s of ticks (18,000 samples) at half the maximum speed.
  const std::string in =
      write_report("constant.json", report(ticks(18000, [](double) { return 1.5; })));
  const std::string png = path("constant.png");
  const CommandRun r = render(in, png, "--smooth 0");
  ASSERT_EQ(r.status, 0) << r.output;

  const Image img(png);
  ASSERT_TRUE(img.ok());
  EXPECT_EQ(img.width(), 1200);
  EXPECT_EQ(img.height(), 500);
  const Layout l{1200, 500, 900.0, 3.0};
  for (const double t : {100.0, 450.0, 800.0}) expect_curve_at(img, l, l.x(t), l.y(1.5), kSpeed);
  // The maximum speed, dashed: some of its row has the line's colour, not all of it.
  int dark = 0;
  const int max_row = static_cast<int>(l.y(3.0));
  for (int x = static_cast<int>(kLeft) + 2; x < 1200 - static_cast<int>(kRightMargin); ++x) {
    if (img.is(x, max_row, kMaxLine)) ++dark;
  }
  EXPECT_GT(dark, 300);
  EXPECT_LT(dark, 1000);
  EXPECT_FALSE(img.has_near(l.x(450.0), l.y(1.5), kAverage, 4)) << "--smooth 0 draws no average";
}

TEST_F(RenderCommand, TheMovingAverageIsDrawnOverTheSpeedByDefault) {
  const std::string in =
      write_report("average.json", report(ticks(400, [](double) { return 1.5; })));
  const std::string png = path("average.png");
  const CommandRun r = render(in, png);
  ASSERT_EQ(r.status, 0) << r.output;
  const Image img(png);
  ASSERT_TRUE(img.ok());
  const Layout l{1200, 500, 20.0, 3.0};
  expect_curve_at(img, l, l.x(10.0), l.y(1.5), kAverage);
}

TEST_F(RenderCommand, ASpeedStepIsDrawnAtBothHeightsAtTheirTimes) {
  // 0.6 m/s for 5 s, then 2.4 m/s for 5 s.
  const std::string in =
      write_report("step.json", report(ticks(200, [](double t) { return t <= 5.0 ? 0.6 : 2.4; })));
  const std::string png = path("step.png");
  const CommandRun r = render(in, png, "--smooth 0 --width 800 --height 300");
  ASSERT_EQ(r.status, 0) << r.output;
  const Image img(png);
  ASSERT_TRUE(img.ok());
  EXPECT_EQ(img.width(), 800);
  EXPECT_EQ(img.height(), 300);
  const Layout l{800, 300, 10.0, 3.0};
  expect_curve_at(img, l, l.x(2.5), l.y(0.6), kSpeed);
  expect_curve_at(img, l, l.x(7.5), l.y(2.4), kSpeed);
}

TEST_F(RenderCommand, TheBoundsAreDrawnUnderTheSpeedAndSummarised) {
  // The speed 0.6 m/s throughout; the braking bound 1.2 m/s for 5 s, then 2.4 m/s; within the
  // route's turns, 0.9 m/s throughout.
  nlohmann::json j = report(ticks(200, [](double) { return 0.6; }));
  nlohmann::json bound = nlohmann::json::array();
  for (int i = 1; i <= 200; ++i) bound.push_back(i <= 100 ? 1.2 : 2.4);
  j["braking_bound_profile"] = bound;
  j["braking_bound_fraction"] = 0.6;
  j["turning_bound_profile"] = std::vector<double>(200, 0.9);
  j["turning_bound_fraction"] = 0.3;
  const std::string png = path("bound.png");
  const CommandRun r = render(write_report("bound.json", j), png, "--smooth 0");
  ASSERT_EQ(r.status, 0) << r.output;
  const Image img(png);
  ASSERT_TRUE(img.ok());
  const Layout l{1200, 500, 10.0, 3.0};
  expect_curve_at(img, l, l.x(2.5), l.y(1.2), kBrakingBound);
  expect_curve_at(img, l, l.x(7.5), l.y(2.4), kBrakingBound);
  expect_curve_at(img, l, l.x(7.5), l.y(0.6), kSpeed);
  expect_curve_at(img, l, l.x(2.5), l.y(0.9), kTurningBound);
  expect_curve_at(img, l, l.x(7.5), l.y(0.9), kTurningBound);
  EXPECT_NE(r.output.find("braking bound fraction (braking within the sensed region) 0.600"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("turning bound fraction (the same, within the route's turns) 0.300"),
            std::string::npos)
      << r.output;
  // Without one, nothing of its colour.
  const std::string plain = path("no-bound.png");
  ASSERT_EQ(render(write_report("no-bound.json", report(ticks(200, [](double) { return 0.6; }))),
                   plain, "--smooth 0")
                .status,
            0);
  const Image none(plain);
  ASSERT_TRUE(none.ok());
  for (const Rgb colour : {kBrakingBound, kTurningBound}) {
    EXPECT_TRUE(
        none.rows_with(static_cast<int>(l.x(2.5)), colour, l.plot_top(), l.plot_bottom()).empty());
  }
}

TEST_F(RenderCommand, ASingleSampleIsADot) {
  const std::string in = write_report("single.json", report({{0.0, 1.5}}));
  const std::string png = path("single.png");
  const CommandRun r = render(in, png, "--smooth 0");
  ASSERT_EQ(r.status, 0) << r.output;
  const Image img(png);
  ASSERT_TRUE(img.ok());
  const Layout l{1200, 500, 1.0, 3.0};
  EXPECT_TRUE(img.has_near(l.x(0.0) + 1.0, l.y(1.5), kSpeed, 1));
}

TEST_F(RenderCommand, CollisionsAreMarkedInRedOnTheTimeAxisEvenAfterTheProfileEnds) {
  nlohmann::json j = report(ticks(200, [](double) { return 0.0; }));  // stopped on the axis
  j["collisions"] = 2;
  j["collision_events"] = {{{"time_s", 3.0}, {"x_m", 1.0}, {"y_m", 2.0}, {"theta_rad", 0.0}},
                           {{"time_s", 12.0}, {"x_m", 1.0}, {"y_m", 2.0}, {"theta_rad", 0.0}}};
  const std::string png = path("collisions.png");
  const CommandRun r = render(write_report("collisions.json", j), png);
  ASSERT_EQ(r.status, 0) << r.output;
  const Image img(png);
  ASSERT_TRUE(img.ok());
  const Layout l{1200, 500, 12.0, 3.0};  // the time axis reaches the last collision
  const int just_above_axis = l.plot_bottom() - 3;
  EXPECT_TRUE(img.is(static_cast<int>(l.x(3.0)), just_above_axis, kCollision));
  EXPECT_TRUE(img.is(static_cast<int>(l.x(12.0)) - 1, just_above_axis, kCollision));
  EXPECT_FALSE(img.is(static_cast<int>(l.x(7.5)), just_above_axis, kCollision));
  EXPECT_NE(r.output.find("collisions 2"), std::string::npos) << r.output;
}

TEST_F(RenderCommand, TheSummaryHasTheHandComputedNumbers) {
  // Ten ticks against a maximum of 3 m/s: the sum is 20.6 m/s, so the mean is 2.060 m/s, 0.687
  // of the maximum; 7 of 10 samples exceed 1.5 m/s (50%) and 5 exceed 2.4 m/s (80%).
  const std::vector<double> speeds{0.0, 0.6, 1.2, 1.8, 2.3, 2.7, 3.0, 3.0, 3.0, 3.0};
  std::vector<std::array<double, 2>> profile;
  for (std::size_t i = 0; i < speeds.size(); ++i) {
    profile.push_back({0.05 * static_cast<double>(i + 1), speeds[i]});
  }
  const CommandRun r = render(write_report("summary.json", report(profile)), path("summary.png"));
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* expected :
       {"dd-vel in rooms, complete", "duration 0.50 s (10 samples)", "mean speed 2.060 m/s",
        "0.687 of the maximum 3.000 m/s", "above 50% of the maximum 0.700", "above 80% 0.500",
        "(since the first plan) 0.750", "collisions 0"}) {
    EXPECT_NE(r.output.find(expected), std::string::npos) << expected << "\n" << r.output;
  }
}

TEST_F(RenderCommand, BadReportsAreRefusedNamingTheFileAndTheProblem) {
  const nlohmann::json good = report(ticks(4, [](double) { return 1.0; }));
  struct Case {
    std::string name;
    std::string text;
    std::string problem;
  };
  const auto with = [&](const char* key, const nlohmann::json& value) {
    nlohmann::json j = good;
    j[key] = value;
    return j.dump();
  };
  nlohmann::json no_profile = good;
  no_profile.erase("speed_profile");
  nlohmann::json no_max = good;
  no_max.erase("max_speed_m_s");
  const std::vector<Case> cases{
      {"not-json", "{\"speed_profile\": [[0.05, 1.0]", "not JSON"},
      {"nan-literal", "{\"speed_profile\": [[0.05, NaN]]}", "not JSON"},
      {"array", "[[0.05, 1.0]]", "not a JSON object"},
      {"no-profile", no_profile.dump(), "no speed_profile"},
      {"profile-object", with("speed_profile", json::parse(R"({"t": 1})")),
       "speed_profile is not an array"},
      {"empty", with("speed_profile", json::array()), "speed_profile is empty"},
      {"single", with("speed_profile", json::parse("[[0.05, 1.0], [0.1]]")),
       "speed_profile[1] is not a pair"},
      {"triple", with("speed_profile", json::parse("[[0.05, 1.0, 2.0]]")),
       "speed_profile[0] is not a pair"},
      {"string", with("speed_profile", json::parse(R"([[0.05, "fast"]])")),
       "speed_profile[0] is not a pair"},
      // nlohmann::json writes a NaN as null.
      {"nan", with("speed_profile", json::parse("[[0.05, 1.0], [0.1, null]]")),
       "speed_profile[1] is not a pair"},
      {"infinite", "{\"max_speed_m_s\": 3, \"speed_profile\": [[0.05, 1e999]]}",
       "not JSON: number overflow parsing '1e999'"},
      {"backwards", with("speed_profile", json::parse("[[0.05, 1.0], [0.1, 1.0], [0.07, 1.0]]")),
       "speed_profile[2]: time 0.07 s is before the previous sample's (0.1 s)"},
      {"negative-time", with("speed_profile", json::parse("[[-0.05, 1.0]]")),
       "time -0.05 s is negative"},
      {"negative-speed", with("speed_profile", json::parse("[[0.05, -1.0]]")),
       "speed -1 m/s is negative"},
      {"no-max", no_max.dump(), "no max_speed_m_s"},
      {"zero-max", with("max_speed_m_s", 0.0), "max_speed_m_s is not a speed > 0"},
      {"text-max", with("max_speed_m_s", "3"), "max_speed_m_s is not a speed > 0"},
      {"collision", with("collision_events", json::parse(R"([{"x_m": 1.0}])")),
       "collision_events[0] has no numeric time_s"},
      {"robot", with("robot", 3), "robot is not a string"},
      {"bound-count", with("braking_bound_profile", json::parse("[1.0, 1.0]")),
       "braking_bound_profile has 2 samples, speed_profile 4"},
      {"bound-negative", with("braking_bound_profile", json::parse("[1.0, 1.0, -1.0, 1.0]")),
       "braking_bound_profile[2] is not a speed >= 0"},
      {"bound-fraction", with("braking_bound_fraction", "high"),
       "braking_bound_fraction is not a fraction >= 0"},
      {"turning-count", with("turning_bound_profile", json::parse("[1.0]")),
       "turning_bound_profile has 1 samples, speed_profile 4"},
      {"turning-fraction", with("turning_bound_fraction", -0.5),
       "turning_bound_fraction is not a fraction >= 0"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string in = write_text(c.name + ".json", c.text);
    const std::string png = path(c.name + ".png");
    std::remove(png.c_str());
    const CommandRun r = render(in, png);
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find(in + ": "), std::string::npos) << "the file is not named:\n"
                                                           << r.output;
    EXPECT_NE(r.output.find(c.problem), std::string::npos) << r.output;
    EXPECT_FALSE(std::ifstream(png).good()) << "a picture was drawn from a bad report";
  }
}

TEST_F(RenderCommand, AMissingReportAnUnwritableImageAndBadOptionsAreRefused) {
  const std::string missing = path("does-not-exist.json");
  CommandRun r = render(missing, path("missing.png"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(missing + ": cannot open: No such file or directory"), std::string::npos)
      << r.output;

  const std::string directory = ::testing::TempDir();
  r = render(directory, path("directory.png"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(directory + ": is a directory"), std::string::npos) << r.output;

  const std::string good = write_report("good.json", report(ticks(4, [](double) { return 1.0; })));
  r = render(good, "/nonexistent-grip-dir/out.png");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("cannot write '/nonexistent-grip-dir/out.png'"), std::string::npos)
      << r.output;

  r = render(good, path("options.png"), "--smooth -1");
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("moving-average window (--smooth)"), std::string::npos) << r.output;

  r = render(good, path("options.png"), "--width 100");
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("400 to 8000 pixels wide"), std::string::npos) << r.output;

  r = grip::testing::run_grip("render " + good);  // nothing to draw
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("--speed-profile"), std::string::npos) << r.output;
}

}  // namespace
