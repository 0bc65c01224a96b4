#include "grip/sim/map_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>

namespace grip::sim {
namespace {

namespace fs = std::filesystem;

// Writes each test's fixtures into its own fresh directory.
class MapFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / "grip_map_file_test" / info->name();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string write(const std::string& name, const std::string& content) {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << content;
    return path.string();
  }
  // The error's message, after checking there is one with the given code.
  template <typename T>
  std::string error_of(const Result<T>& r, ErrorCode code = ErrorCode::kParse) {
    EXPECT_FALSE(r.ok());
    if (r.ok()) return {};
    EXPECT_EQ(r.error().code, code) << r.error().message;
    return r.error().message;
  }
  static std::string ros_yaml(const std::string& image, const std::string& extra = "") {
    return "image: " + image +
           "\nresolution: 0.5\norigin: [-1.0, 2.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\n"
           "free_thresh: 0.196\n" +
           extra;
  }

  fs::path dir_;
};

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

constexpr const char* kGoodMovingAi =
    "type octile\nheight 3\nwidth 4\nmap\n"
    "@..T\n"
    ".GS.\n"
    "O..W\n";

TEST_F(MapFileTest, AMovingAiMapLoadsWithRowZeroAtTheBottom) {
  const std::string path = write("good.map", kGoodMovingAi);
  MapLoadOptions options;
  options.movingai_cell_m = 0.5;
  options.movingai_subdivision = 1;
  auto map = load_map(path, options);
  ASSERT_TRUE(map.ok()) << map.error().message;
  const OccupancyGrid& g = map->grid;
  EXPECT_EQ(map->format, MapFormat::kMovingAi);
  EXPECT_EQ(g.width(), 4);
  EXPECT_EQ(g.height(), 3);
  EXPECT_DOUBLE_EQ(g.resolution(), 0.5);
  EXPECT_EQ(g.at(0, 2), Cell::kObstacle);  // '@', top-left in the file
  EXPECT_EQ(g.at(3, 2), Cell::kObstacle);  // 'T'
  EXPECT_EQ(g.at(1, 1), Cell::kFree);      // 'G'
  EXPECT_EQ(g.at(2, 1), Cell::kFree);      // 'S'
  EXPECT_EQ(g.at(0, 0), Cell::kObstacle);  // 'O', bottom-left
  EXPECT_EQ(g.at(3, 0), Cell::kObstacle);  // 'W'
  EXPECT_EQ(g.at(1, 0), Cell::kFree);
  EXPECT_EQ(map->describe_cell(3, 2), path + ":5:4");
  EXPECT_EQ(map->describe_cell(0, 0), path + ":7:1");
}

TEST_F(MapFileTest, ByDefaultAMovingAiCellIsOneMetreOfTenByTenGridCells) {
  auto map = load_map(write("good.map",
                            "type octile\r\nwidth 4\r\nheight 3\r\nmap\r\n"
                            "@..T\r\n.GS.\r\nO..W\r\n"));
  ASSERT_TRUE(map.ok()) << map.error().message;
  EXPECT_EQ(map->grid.width(), 40);
  EXPECT_EQ(map->grid.height(), 30);
  EXPECT_DOUBLE_EQ(map->grid.resolution(), 0.1);
  EXPECT_EQ(map->grid.at(9, 29), Cell::kObstacle);
  EXPECT_EQ(map->grid.at(10, 29), Cell::kFree);
  EXPECT_EQ(map->describe_cell(39, 0), map->path + ":7:4");
}

TEST_F(MapFileTest, ATruncatedMovingAiMapNamesTheLineWhereRowsAreMissing) {
  const std::string path = write("short.map", "type octile\nheight 3\nwidth 4\nmap\n@..T\n.GS.\n");
  const std::string m = error_of(load_map(path));
  EXPECT_TRUE(contains(m, path + ":7: truncated")) << m;
  EXPECT_TRUE(contains(m, "expected 3 map rows, found 2")) << m;
  EXPECT_TRUE(contains(error_of(load_map(write("header.map", "type octile\nheight 3\n"))),
                       "header.map:3: truncated header"));
  EXPECT_TRUE(contains(error_of(load_map(write("empty.map", ""))), "empty.map:1: empty file"));
}

TEST_F(MapFileTest, AMovingAiRowOfTheWrongLengthNamesItsLine) {
  const std::string path =
      write("row.map", "type octile\nheight 3\nwidth 4\nmap\n@..T\n.GS\nO..W\n");
  const std::string m = error_of(load_map(path));
  EXPECT_TRUE(contains(m, path + ":6: map row 2 has 3 characters, expected width 4")) << m;
  const std::string extra =
      error_of(load_map(write("extra.map", "type octile\nheight 1\nwidth 2\nmap\n..\n..\n")));
  EXPECT_TRUE(contains(extra, "extra.map:6: more map rows than the header's height 1")) << extra;
}

TEST_F(MapFileTest, AnUnknownMovingAiCharacterNamesLineAndColumn) {
  const std::string path =
      write("char.map", "type octile\nheight 3\nwidth 4\nmap\n@..T\n.Gx.\nO..W\n");
  const std::string m = error_of(load_map(path));
  EXPECT_TRUE(contains(m, path + ":6:3: unknown map character 'x'")) << m;
  const std::string tab =
      error_of(load_map(write("tab.map", "type octile\nheight 1\nwidth 2\nmap\n.\t\n")));
  EXPECT_TRUE(contains(tab, "tab.map:5:2: unknown map character byte 0x09")) << tab;
}

TEST_F(MapFileTest, ABadMovingAiHeaderNamesTheLineAndTheValue) {
  const std::string m =
      error_of(load_map(write("h.map", "type octile\nheight three\nwidth 4\nmap\n")));
  EXPECT_TRUE(contains(m, "h.map:2: height must be a whole number in [1, 1638] (got 'three')"))
      << m;
  const std::string t = error_of(load_map(write("t.map", "height 3\n")));
  EXPECT_TRUE(contains(t, "t.map:1: expected 'type <name>'")) << t;
  const std::string k = error_of(load_map(write("k.map", "type octile\nheigth 3\n")));
  EXPECT_TRUE(contains(k, "k.map:2: expected 'height <rows>'")) << k;
  const std::string missing = error_of(load_map(write("w.map", "type octile\nheight 3\nmap\n")));
  EXPECT_TRUE(contains(missing, "w.map:3: header lacks 'width'")) << missing;
}

TEST_F(MapFileTest, MissingFilesAndUnknownExtensionsAreErrorsNamingThePath) {
  const std::string missing = (dir_ / "absent.map").string();
  EXPECT_TRUE(contains(error_of(load_map(missing), ErrorCode::kIo), missing));
  const std::string txt = write("map.txt", kGoodMovingAi);
  EXPECT_TRUE(contains(error_of(load_map(txt), ErrorCode::kInvalidArgument), "'.txt'"));
}

// A 3 x 2 binary PGM: top row occupied (0), free (254), unknown (205); bottom row free.
std::string pgm_p5() {
  std::string s = "P5\n# a comment\n3 2\n255\n";
  for (const int v : {0, 254, 205, 254, 254, 254}) s.push_back(static_cast<char>(v));
  return s;
}

TEST_F(MapFileTest, ARosMapLoadsWithOriginResolutionAndUnknownAsObstacle) {
  write("img.pgm", pgm_p5());
  const std::string yaml = write("map.yaml", ros_yaml("img.pgm", "mode: trinary\n"));
  auto map = load_map(yaml);
  ASSERT_TRUE(map.ok()) << map.error().message;
  const OccupancyGrid& g = map->grid;
  EXPECT_EQ(map->format, MapFormat::kRosMapServer);
  EXPECT_EQ(g.width(), 3);
  EXPECT_EQ(g.height(), 2);
  EXPECT_DOUBLE_EQ(g.resolution(), 0.5);
  EXPECT_DOUBLE_EQ(g.origin_x(), -1.0);
  EXPECT_DOUBLE_EQ(g.origin_y(), 2.0);
  EXPECT_EQ(g.at(0, 1), Cell::kObstacle);  // the file's top row is the grid's row 1
  EXPECT_EQ(g.at(1, 1), Cell::kFree);
  EXPECT_EQ(g.at(2, 1), Cell::kObstacle);  // unknown: an obstacle in the ground truth
  EXPECT_EQ(g.at(0, 0), Cell::kFree);
  EXPECT_EQ(map->unknown_pixels, 1U);
  EXPECT_TRUE(contains(map->describe_cell(2, 1), "img.pgm pixel (column 2, row 0)"));
}

TEST_F(MapFileTest, AnAsciiPgmWithNegateAndASmallMaxvalLoads) {
  // negate: 1 makes dark pixels free. maxval 4: 0 -> free, 4 -> occupied, 2 -> unknown.
  write("img.pgm", "P2\n3 1\n# maxval next\n4\n0 4\n2\n");
  auto map =
      load_map(write("map.yaml", ros_yaml("img.pgm").replace(ros_yaml("img.pgm").find("negate: 0"),
                                                             9, "negate: 1")));
  ASSERT_TRUE(map.ok()) << map.error().message;
  EXPECT_EQ(map->grid.at(0, 0), Cell::kFree);
  EXPECT_EQ(map->grid.at(1, 0), Cell::kObstacle);
  EXPECT_EQ(map->grid.at(2, 0), Cell::kObstacle);
  EXPECT_EQ(map->unknown_pixels, 1U);
}

TEST_F(MapFileTest, RawModeReadsPixelsAsOccupancyPercentages) {
  std::string pgm = "P5 3 1 255\n";
  for (const int v : {0, 100, 200}) pgm.push_back(static_cast<char>(v));
  write("img.pgm", pgm);
  auto map = load_map(write("map.yaml", ros_yaml("img.pgm", "mode: raw\n")));
  ASSERT_TRUE(map.ok()) << map.error().message;
  EXPECT_EQ(map->grid.at(0, 0), Cell::kFree);
  EXPECT_EQ(map->grid.at(1, 0), Cell::kObstacle);
  EXPECT_EQ(map->grid.at(2, 0), Cell::kObstacle);  // above 100: unknown
  EXPECT_EQ(map->unknown_pixels, 1U);
}

TEST_F(MapFileTest, AMissingYamlFieldIsNamed) {
  write("img.pgm", pgm_p5());
  const std::string yaml =
      write("map.yaml",
            "image: img.pgm\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: "
            "0.2\n");
  const std::string m = error_of(load_map(yaml));
  EXPECT_TRUE(contains(m, yaml + ":1: missing required field 'resolution'")) << m;
}

TEST_F(MapFileTest, ABadYamlValueNamesLineAndColumn) {
  write("img.pgm", pgm_p5());
  const std::string m =
      error_of(load_map(write("map.yaml",
                              "image: img.pgm\nresolution: -0.5\norigin: [0, 0, 0]\nnegate: 0\n"
                              "occupied_thresh: 0.65\nfree_thresh: 0.2\n")));
  EXPECT_TRUE(contains(m, "map.yaml:2:13: 'resolution' must be a number in [0.001, 10]")) << m;
  EXPECT_TRUE(contains(m, "(got -0.5)")) << m;
  const std::string origin =
      error_of(load_map(write("o.yaml",
                              "image: img.pgm\nresolution: 0.5\norigin: [0, 0]\nnegate: 0\n"
                              "occupied_thresh: 0.65\nfree_thresh: 0.2\n")));
  EXPECT_TRUE(contains(origin, "o.yaml:3:9: 'origin' must be a list of three")) << origin;
  const std::string mode =
      error_of(load_map(write("m.yaml", ros_yaml("img.pgm", "mode: fancy\n"))));
  EXPECT_TRUE(contains(mode, "m.yaml:7:7: 'mode' must be trinary, scale or raw")) << mode;
  const std::string syntax =
      error_of(load_map(write("s.yaml", "image: [img.pgm\nresolution: 1\n")));
  EXPECT_TRUE(contains(syntax, "s.yaml:")) << syntax;
  const std::string list = error_of(load_map(write("l.yaml", "- a\n- b\n")));
  EXPECT_TRUE(contains(list, "l.yaml:1: expected a YAML mapping")) << list;
}

TEST_F(MapFileTest, AMissingImageNamesTheYamlLineAndTheResolvedPath) {
  const std::string yaml = write("map.yaml", ros_yaml("nowhere.pgm"));
  const std::string m = error_of(load_map(yaml), ErrorCode::kIo);
  EXPECT_TRUE(contains(m, yaml + ":1: image 'nowhere.pgm' cannot be read")) << m;
  EXPECT_TRUE(contains(m, (dir_ / "nowhere.pgm").string())) << m;
}

TEST_F(MapFileTest, WrongPgmHeadersAreNamedWithTheImageAndLine) {
  const std::string yaml = write("map.yaml", ros_yaml("img.pgm"));
  const std::string image = (dir_ / "img.pgm").string();
  write("img.pgm", "P6\n3 2\n255\n");
  EXPECT_TRUE(contains(error_of(load_map(yaml)), image + ":1:1: not a PGM image: magic 'P6'"));
  write("img.pgm", "P5\n0 2\n255\n");
  EXPECT_TRUE(contains(error_of(load_map(yaml)),
                       image + ":2:1: width must be a whole number in [1, 16384] (got '0')"));
  write("img.pgm", "P5\n3 x2\n255\n");
  EXPECT_TRUE(contains(error_of(load_map(yaml)), image + ":2:3: height must be"));
  write("img.pgm", "P5\n3 2\n# comment\n70000\n");
  EXPECT_TRUE(contains(error_of(load_map(yaml)),
                       image + ":4:1: maxval must be a whole number in [1, 65535] (got '70000')"));
  write("img.pgm", "P5\n3 2\n");
  EXPECT_TRUE(contains(error_of(load_map(yaml)), image + ":3: truncated header: missing maxval"));
}

TEST_F(MapFileTest, TruncatedPgmRastersAreNamed) {
  const std::string yaml = write("map.yaml", ros_yaml("img.pgm"));
  const std::string image = (dir_ / "img.pgm").string();
  write("img.pgm", "P5\n3 2\n255\n\xfe\xfe");
  const std::string binary = error_of(load_map(yaml));
  EXPECT_TRUE(contains(binary, image + ":4: truncated raster: expected 6 bytes")) << binary;
  EXPECT_TRUE(contains(binary, "found 2")) << binary;
  write("img.pgm", "P2\n3 2\n255\n254 254 254\n254\n");
  const std::string ascii = error_of(load_map(yaml));
  EXPECT_TRUE(contains(ascii, image + ":6: truncated raster: expected 6 pixel values, found 4"))
      << ascii;
  write("img.pgm", "P2\n3 1\n255\n254 256 254\n");
  const std::string big = error_of(load_map(yaml));
  EXPECT_TRUE(contains(big, image + ":4:5: pixel value must be a whole number in [0, 255]")) << big;
}

TEST_F(MapFileTest, SixteenBitBinaryPgmsAreRead) {
  std::string pgm = "P5\n2 1\n1000\n";
  for (const int v : {0x03, 0xE8, 0x00, 0x00}) pgm.push_back(static_cast<char>(v));  // 1000, 0
  auto image = parse_pgm(pgm, "x.pgm");
  ASSERT_TRUE(image.ok()) << image.error().message;
  EXPECT_EQ(image->pixels[0], 1000);
  EXPECT_EQ(image->pixels[1], 0);
  pgm[pgm.size() - 2] = '\x04';  // 1024 > maxval
  EXPECT_FALSE(parse_pgm(pgm, "x.pgm").ok());
}

// ---- Hostile files: refused with an error naming the file and the field, never a crash ------

TEST_F(MapFileTest, ExtremeResolutionsAreRefusedNamingTheField) {
  write("img.pgm", pgm_p5());
  for (const char* resolution : {"1e-300", "0.0009", "10.5", "1e300", "4.9e-324"}) {
    const std::string yaml =
        write("map.yaml", std::string("image: img.pgm\nresolution: ") + resolution +
                              "\norigin: [0, 0, 0]\nnegate: 0\n"
                              "occupied_thresh: 0.65\nfree_thresh: 0.2\n");
    const std::string m = error_of(load_map(yaml));
    EXPECT_TRUE(contains(m, yaml + ":2:13: 'resolution' must be a number in [0.001, 10]")) << m;
    EXPECT_TRUE(contains(m, std::string("(got ") + resolution + ")")) << m;
  }
  // The bounds themselves are accepted.
  for (const char* resolution : {"0.001", "10"}) {
    auto map = load_map(write("ok.yaml", std::string("image: img.pgm\nresolution: ") + resolution +
                                             "\norigin: [0, 0, 0]\nnegate: 0\n"
                                             "occupied_thresh: 0.65\nfree_thresh: 0.2\n"));
    EXPECT_TRUE(map.ok()) << map.error().message;
  }
}

TEST_F(MapFileTest, AFarAwayOriginIsRefusedNamingTheField) {
  write("img.pgm", pgm_p5());
  const std::string yaml = write("map.yaml",
                                 "image: img.pgm\nresolution: 0.5\norigin: [1e9, 0, 0]\nnegate: 0\n"
                                 "occupied_thresh: 0.65\nfree_thresh: 0.2\n");
  const std::string m = error_of(load_map(yaml));
  EXPECT_TRUE(contains(m, yaml + ":3:9: 'origin' x and y must lie within +-1000000 m")) << m;
}

TEST_F(MapFileTest, MovingAiCellSizesOutsideTheGridsBoundsAreRefused) {
  const std::string path = write("good.map", kGoodMovingAi);
  for (const double cell_m : {1e-300, 5e-3, 2000.0}) {
    MapLoadOptions options;
    options.movingai_cell_m = cell_m;
    const std::string m = error_of(load_map(path, options), ErrorCode::kInvalidArgument);
    EXPECT_TRUE(contains(m, "movingai_cell_m / movingai_subdivision must be in [0.001, 10]")) << m;
  }
}

TEST_F(MapFileTest, ALinkToAnEndlessDeviceIsRefusedNotRead) {
  for (const char* device : {"/dev/zero", "/dev/urandom"}) {
    if (!fs::exists(device)) continue;
    const fs::path map = dir_ / "endless.map";
    fs::remove(map);
    fs::create_symlink(device, map);
    const std::string m = error_of(load_map(map.string()), ErrorCode::kIo);
    EXPECT_TRUE(contains(m, map.string() + ": MovingAI map is not a regular file")) << m;
    // The same device as the image a map_server YAML names.
    fs::remove(dir_ / "img.pgm");
    fs::create_symlink(device, dir_ / "img.pgm");
    const std::string yaml = write("map.yaml", ros_yaml("img.pgm"));
    const std::string image = error_of(load_map(yaml), ErrorCode::kIo);
    EXPECT_TRUE(contains(image, yaml + ":1: image 'img.pgm' cannot be read")) << image;
    EXPECT_TRUE(contains(image, "PGM image is not a regular file")) << image;
  }
}

TEST_F(MapFileTest, AFifoIsRefusedWithoutBlocking) {
  const fs::path fifo = dir_ / "pipe.yaml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string m = error_of(load_map(fifo.string()), ErrorCode::kIo);
  EXPECT_TRUE(contains(m, fifo.string() + ": map_server YAML is not a regular file")) << m;
}

TEST_F(MapFileTest, AFileOverTheSizeCapIsRefusedUnread) {
  const std::string path = write("huge.map", kGoodMovingAi);
  fs::resize_file(path, kMaxMapFileBytes + 1);  // sparse: costs no disk
  const std::string m = error_of(load_map(path), ErrorCode::kIo);
  EXPECT_TRUE(contains(m, path + ": MovingAI map is larger than 67108864 bytes")) << m;
}

TEST_F(MapFileTest, APgmBeyondTheGridsCellCapIsRefused) {
  const std::string m = error_of(parse_pgm("P5\n16384 16384\n255\n", "big.pgm"));
  EXPECT_TRUE(contains(m, "big.pgm:3: image of 16384 x 16384 pixels exceeds 16777216")) << m;
}

}  // namespace
}  // namespace grip::sim
