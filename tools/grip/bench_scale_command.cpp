// `grip bench scale`: how grip's cost grows with the map. The same exploration (one vehicle,
// one seed, a fixed simulated time) on one map made larger, up to about 16 M cells: tiled (n x n
// copies side by side: a larger building at the same resolution) and, for a MovingAI map,
// subdivided (finer cells: the same building at a higher resolution; a ROS map is explored at
// its own). Every run has the same sensor (its range in metres: what `auto` gives the untiled
// map), so that the map's size is the only thing
// that changes; left to `auto` it would reach a tenth of the tiled map. Each run is a private
// `grip explore` child process with its report and cycle trace kept in one directory. A row per
// map: cells, the planner's start-up (map in sync, planning), the process's peak memory, and
// every cycle phase's p50 / p99 / max, and (--png) their p99 against the cell count as a chart.
// A benchmark: it measures and prints, it asserts nothing.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bench_children.hpp"
#include "commands.hpp"
#include "grip/sim/map_file.hpp"
#include "grip/sim/range_sensor.hpp"
#include "report_file.hpp"
#include "scale_chart.hpp"
#include "stats.hpp"
#include "vehicle_arg.hpp"

namespace grip::tools {

namespace {

struct BenchScaleOptions {
  std::string map;
  std::vector<int> tiles{1, 2, 4, 6};
  // MovingAI: grid cells per map cell; none given: 10 cm cells (coarser than 12.5 cm ones do not
  // leave the frontier approach its range). A ROS map has its own resolution.
  std::vector<int> subdivisions;
  std::string robot = "dd-vel";
  double max_sim_time_s = 60.0;
  double sensor_range_m = 0.0;  // 0: a tenth of the untiled map's larger side
  bool real_time = false;       // time scale 1 instead of lockstep
  std::string out_dir = "bench-scale";
  std::string json;
  std::string png;
};

// The cycle trace's phases (tools/grip/cycle_trace.cpp), in microseconds: the chart's, in order.
constexpr const char* kPhases[] = {"prepare_us", "retain_us", "grow_us", "commit_us", "compute_us"};
static_assert(std::size(kPhases) == kScalePhases.size());

struct Run {
  int tiles = 1;
  int subdivision = 0;  // grid cells per MovingAI cell side; 0: a ROS map's own cells
  std::string map;      // the file explored: the map, or its tiling in the output directory
  std::string stem;
  int exit_status = -1;
  nlohmann::json report;                    // empty when the run left none
  std::uint64_t cells = 0;                  // of the grid
  std::vector<std::vector<double>> phases;  // per kPhases entry, one sample per cycle
  std::uint64_t missed = 0;
};

// Reads the cycle trace's phase columns and its missed column; false when it is unreadable.
bool read_trace(const std::string& path, Run& r) {
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line)) return false;
  std::vector<std::string> header;
  std::stringstream names(line);
  for (std::string name; std::getline(names, name, ',');) header.push_back(name);
  std::vector<std::size_t> columns;
  for (const char* phase : kPhases) {
    const auto it = std::find(header.begin(), header.end(), phase);
    if (it == header.end()) return false;
    columns.push_back(static_cast<std::size_t>(it - header.begin()));
  }
  const auto missed = std::find(header.begin(), header.end(), "missed");
  r.phases.assign(std::size(kPhases), {});
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::stringstream values(line);
    for (std::string v; std::getline(values, v, ',');) fields.push_back(v);
    if (fields.size() < header.size()) continue;
    for (std::size_t p = 0; p < columns.size(); ++p) {
      r.phases[p].push_back(std::strtod(fields[columns[p]].c_str(), nullptr));
    }
    if (missed != header.end() &&
        fields[static_cast<std::size_t>(missed - header.begin())] == "1") {
      ++r.missed;
    }
  }
  return true;
}

// n x n copies of a map of width x height file cells, `pixel(x, row)` the character of each
// (grid row 0 is the map's bottom), written top row first as both file formats store them, each
// row followed by `row_end`.
template <typename Pixel>
void write_tiles(std::ostream& out, int width, int height, int n, Pixel pixel,
                 const char* row_end) {
  std::string line;
  for (int tile_row = 0; tile_row < n; ++tile_row) {
    for (int row = height - 1; row >= 0; --row) {
      line.clear();
      for (int x = 0; x < width; ++x) line += pixel(x, row);
      for (int tile = 0; tile < n; ++tile) out << line;
      out << row_end;
    }
  }
}

// The map n x n times side by side, as a MovingAI file; false if it cannot be written.
bool write_tiled_movingai(const sim::LoadedMap& map, int n, const std::string& path) {
  const int sub = map.cells_per_pixel;
  const int width = map.grid.width() / sub;
  const int height = map.grid.height() / sub;
  std::ofstream out(path);
  out << "type octile\nheight " << height * n << "\nwidth " << width * n << "\nmap\n";
  write_tiles(
      out, width, height, n,
      [&](int x, int row) { return map.grid.at(x * sub, row * sub) == Cell::kFree ? '.' : '@'; },
      "\n");
  return static_cast<bool>(out.flush());
}

// The map n x n times side by side, as a ROS map (`path` the YAML, its PGM beside it) at the
// map's resolution and origin; false if it cannot be written. The ground truth holds free cells
// and obstacles only (unknown pixels became obstacles when it was read), and so does the tiling.
bool write_tiled_ros(const sim::LoadedMap& map, int n, const std::string& path) {
  const OccupancyGrid& grid = map.grid;
  const std::filesystem::path yaml(path);
  const std::filesystem::path pgm = std::filesystem::path(yaml).replace_extension(".pgm");
  std::ofstream image(pgm, std::ios::binary);
  image << "P5\n" << grid.width() * n << " " << grid.height() * n << "\n255\n";
  constexpr char kFreePixel = static_cast<char>(254);
  constexpr char kObstaclePixel = 0;
  write_tiles(
      image, grid.width(), grid.height(), n,
      [&](int x, int row) { return grid.at(x, row) == Cell::kFree ? kFreePixel : kObstaclePixel; },
      "");
  if (!image.flush()) return false;
  std::ofstream out(yaml);
  out << std::setprecision(15) << "image: " << pgm.filename().string()
      << "\nmode: trinary\nresolution: " << grid.resolution() << "\norigin: [" << grid.origin_x()
      << ", " << grid.origin_y() << ", 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  return static_cast<bool>(out.flush());
}

std::vector<std::string> explore_args(const BenchScaleOptions& o, const Run& r,
                                      double sensor_range_m, const std::string& self) {
  std::vector<std::string> args{self,
                                "explore",
                                "--map",
                                r.map,
                                vehicle_args(o.robot)[0],
                                o.robot,
                                "--max-sim-time",
                                std::to_string(o.max_sim_time_s),
                                "--sensor-range",
                                std::to_string(sensor_range_m),
                                "--private",
                                "--report",
                                o.out_dir + "/" + r.stem + ".json",
                                "--cycle-trace",
                                o.out_dir + "/" + r.stem + ".cycles.csv"};
  if (r.subdivision > 0) {
    args.insert(args.end(), {"--movingai-subdivision", std::to_string(r.subdivision)});
  }
  if (o.real_time) {
    args.insert(args.end(), {"--time-scale", "1"});
  } else {
    args.emplace_back("--lockstep");
  }
  return args;
}

double phase_ms(const Run& r, std::size_t phase, double q) {
  if (r.phases.empty() || r.phases[phase].empty()) return NAN;
  return percentile(r.phases[phase], q) / 1000.0;
}

void print_table(const std::vector<Run>& runs) {
  std::cout << "\n"
            << std::right << std::setw(6) << "tiles" << std::setw(5) << "sub" << std::setw(11)
            << "cells" << std::setw(9) << "sync s" << std::setw(11) << "planning s" << std::setw(9)
            << "rss MB" << std::setw(8) << "cycles" << std::setw(7) << "missed";
  for (const char* phase : kPhases) {
    std::string name(phase);
    name.resize(name.size() - 3);
    std::cout << std::setw(24) << name + " p50/p99/max ms";
  }
  std::cout << "\n";
  for (const Run& r : runs) {
    const nlohmann::json& j = r.report;
    const nlohmann::json startup =
        j.is_null() ? nlohmann::json() : j.value("planner_startup", nlohmann::json());
    std::cout << std::fixed << std::setw(6) << r.tiles << std::setw(5)
              << (r.subdivision > 0 ? std::to_string(r.subdivision) : "-") << std::setw(11)
              << r.cells << std::setprecision(2) << std::setw(9)
              << (startup.is_null() ? NAN : startup.value("map_sync_s", NAN)) << std::setw(11)
              << (startup.is_null() ? NAN : startup.value("planning_s", NAN))
              << std::setprecision(0) << std::setw(9)
              << (j.is_null() ? NAN : j.value("peak_rss_mb", NAN)) << std::setw(8)
              << (j.is_null() ? 0 : j.value("cycles", 0)) << std::setw(7) << r.missed;
    for (std::size_t p = 0; p < std::size(kPhases); ++p) {
      std::ostringstream cell;
      cell << std::fixed << std::setprecision(2) << phase_ms(r, p, 0.5) << "/"
           << phase_ms(r, p, 0.99) << "/" << phase_ms(r, p, 1.0);
      std::cout << std::setw(24) << cell.str();
    }
    if (j.is_null()) std::cout << "  (no report: exit " << r.exit_status << ")";
    std::cout << "\n";
  }
}

int run_bench(const BenchScaleOptions& o) {
  const char* command = "grip bench scale";
  std::string self;
  if (const int rc = prepare_bench_children(command, o.out_dir, self); rc != 0) return rc;
  sim::MapLoadOptions one_cell;
  one_cell.movingai_subdivision = 1;
  auto loaded = sim::load_map(o.map, one_cell);  // refuses a bad file before any run
  if (!loaded) {
    std::cerr << command << ": " << loaded.error().message << "\n";
    return 2;
  }
  const bool ros = loaded->format == sim::MapFormat::kRosMapServer;
  if (ros && !o.subdivisions.empty()) {
    std::cerr << command << ": --subdivisions is for MovingAI maps; " << o.map
              << " is a ROS map, explored at its own resolution\n";
    return 2;
  }
  // 0: the map's own cells (ROS).
  const std::vector<int> subdivisions = ros                      ? std::vector<int>{0}
                                        : o.subdivisions.empty() ? std::vector<int>{10}
                                                                 : o.subdivisions;
  const double sensor_range_m =
      o.sensor_range_m > 0.0 ? o.sensor_range_m : sim::RangeSensor::default_radius_m(loaded->grid);
  const std::string stem = std::filesystem::path(o.map).stem().string();
  std::vector<Run> runs;
  for (const int n : o.tiles) {
    std::string map = o.map;
    if (n > 1) {
      map = o.out_dir + "/" + stem + "-tiled" + std::to_string(n) + (ros ? ".yaml" : ".map");
      if (!(ros ? write_tiled_ros(*loaded, n, map) : write_tiled_movingai(*loaded, n, map))) {
        std::cerr << command << ": cannot write " << map << "\n";
        return 1;
      }
    }
    for (const int s : subdivisions) {
      Run r;
      r.tiles = n;
      r.subdivision = s;
      r.map = map;
      const int side = std::max(s, 1);
      r.cells = static_cast<std::uint64_t>(loaded->grid.cell_count()) *
                static_cast<std::uint64_t>(n * n * side * side);
      r.stem = stem + "-t" + std::to_string(n) + (s > 0 ? "-x" + std::to_string(s) : "");
      runs.push_back(std::move(r));
    }
  }
  std::cout << command << ": " << o.map << " in " << runs.size() << " sizes, "
            << vehicle_label(o.robot) << ", sensor range " << sensor_range_m << " m, "
            << (o.real_time ? "real time" : "lockstep") << ", " << o.max_sim_time_s
            << " s simulated each; reports in " << o.out_dir << "/" << std::endl;
  for (Run& r : runs) {
    const std::string report = o.out_dir + "/" + r.stem + ".json";
    std::error_code ec;
    std::filesystem::remove(report, ec);
    auto child = Child::spawn(explore_args(o, r, sensor_range_m, self), {},
                              o.out_dir + "/" + r.stem + ".log", true);
    if (child) r.exit_status = child->wait();
    r.report = read_child_report(report);
    if (!read_trace(o.out_dir + "/" + r.stem + ".cycles.csv", r)) r.phases.clear();
    std::cout << "  " << r.tiles << " x " << r.tiles << " tiles"
              << (r.subdivision > 0 ? ", x" + std::to_string(r.subdivision) : "") << " (" << r.cells
              << " cells): " << (r.report.is_null() ? "no report" : r.report.value("result", "?"))
              << (child ? "" : " (" + child.error().message + ")") << std::endl;
  }
  print_table(runs);
  if (!o.json.empty()) {
    nlohmann::json j;
    j["map"] = o.map;
    j["robot"] = vehicle_label(o.robot);
    j["mode"] = o.real_time ? "real time" : "lockstep";
    j["max_sim_time_s"] = o.max_sim_time_s;
    j["sensor_range_m"] = sensor_range_m;
    nlohmann::json rows = nlohmann::json::array();
    for (const Run& r : runs) {
      nlohmann::json row{{"tiles", r.tiles},
                         {"cells", r.cells},
                         {"exit_status", r.exit_status},
                         {"missed", r.missed},
                         {"report", o.out_dir + "/" + r.stem + ".json"}};
      // null for a ROS map: its own cells
      row["subdivision"] = r.subdivision > 0 ? nlohmann::json(r.subdivision) : nlohmann::json();
      if (!r.report.is_null()) {
        for (const char* key : {"result", "coverage", "collisions", "cycles", "wall_time_s",
                                "peak_rss_mb", "planner_startup"}) {
          if (r.report.contains(key)) row[key] = r.report.at(key);
        }
      }
      for (std::size_t p = 0; p < std::size(kPhases) && !r.phases.empty(); ++p) {
        std::string name(kPhases[p]);
        name.resize(name.size() - 3);
        row[name + "_ms"] = {{"p50", phase_ms(r, p, 0.5)},
                             {"p99", phase_ms(r, p, 0.99)},
                             {"max", phase_ms(r, p, 1.0)}};
      }
      rows.push_back(row);
    }
    j["runs"] = rows;
    if (!write_report(command, o.json, std::move(j), 1)) return 1;
  }
  if (!o.png.empty()) {
    std::vector<ScaleChartRow> rows;
    for (const Run& r : runs) {
      ScaleChartRow row;
      row.cells = static_cast<double>(r.cells);
      for (std::size_t p = 0; p < std::size(kPhases); ++p) row.p99_ms[p] = phase_ms(r, p, 0.99);
      rows.push_back(row);
    }
    const std::string title = std::filesystem::path(o.map).filename().string() + ", " +
                              vehicle_label(o.robot) + ", " +
                              (o.real_time ? "real time" : "lockstep") +
                              ": each cycle phase's p99 against the map's size";
    if (Status s = write_scale_chart_png(rows, title, o.png); !s) {
      std::cerr << command << ": " << s.error().message << "\n";
      return 1;
    }
    std::cout << command << ": wrote " << o.png << "\n";
  }
  return 0;
}

}  // namespace

void register_bench_scale_command(CLI::App& bench) {
  auto o = std::make_shared<BenchScaleOptions>();
  CLI::App* cmd = bench.add_subcommand(
      "scale", "How the cost grows with the map: one exploration at several resolutions");
  cmd->add_option("--map", o->map,
                  "A MovingAI .map file (its cells are 1 m) or a ROS map_server .yaml")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--tiles", o->tiles,
                  "n: the map n x n times side by side, a run each (cells grow as n^2)")
      ->delimiter(',')
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  cmd->add_option("--subdivisions", o->subdivisions,
                  "Grid cells per MovingAI cell side, a run each with every --tiles (default: "
                  "10; not for a ROS map)")
      ->delimiter(',')
      ->check(CLI::Range(1, 100));
  cmd->add_option("--robot", o->robot, "dd-vel, dd-accel, car, or a parameter file (.yaml)")
      ->check(CLI::IsMember({"dd-vel", "dd-accel", "car"}) | CLI::ExistingFile)
      ->capture_default_str();
  cmd->add_option("--max-sim-time", o->max_sim_time_s, "Per run [s of simulated time]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--sensor-range", o->sensor_range_m,
                  "Every run's sensor range [m] (default: a tenth of the untiled map's larger "
                  "side, the range `auto` gives it)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--real-time", o->real_time, "Real time at time scale 1 instead of lockstep");
  cmd->add_option("--out", o->out_dir, "Directory for every run's report, log and cycle trace")
      ->capture_default_str();
  cmd->add_option("--json", o->json, "Write the table and every run's figures here");
  cmd->add_option("--png", o->png, "Draw each cycle phase's p99 against the map's size here");
  cmd->callback([o]() {
    if (const int rc = run_bench(*o); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace grip::tools
