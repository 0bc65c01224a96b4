#include "grip/sim/map_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

namespace grip::sim {

namespace {

Error parse_error(const std::string& name, int line, const std::string& message) {
  return Error{ErrorCode::kParse, name + ":" + std::to_string(line) + ": " + message};
}
Error parse_error(const std::string& name, int line, int column, const std::string& message) {
  return Error{ErrorCode::kParse,
               name + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + message};
}

// Reads a whole map file, refusing what is not a regular file (a directory, a FIFO, a device
// such as /dev/zero behind a symlink: reading one would block or never end) and anything over
// kMaxMapFileBytes; the read itself stops at the cap, so a file that grows meanwhile is refused
// too.
Result<std::string> read_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) {
    return Error{ErrorCode::kIo, path + ": cannot open " + what};
  }
  if (std::filesystem::is_directory(status)) {
    return Error{ErrorCode::kIo, path + ": " + what + " is a directory, not a file"};
  }
  if (!std::filesystem::is_regular_file(status)) {
    return Error{ErrorCode::kIo,
                 path + ": " + what + " is not a regular file (a device, FIFO or socket); refused"};
  }
  const auto too_large = [&] {
    return Error{ErrorCode::kIo, path + ": " + what + " is larger than " +
                                     std::to_string(kMaxMapFileBytes) + " bytes; refused"};
  };
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxMapFileBytes) return too_large();
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{ErrorCode::kIo, path + ": cannot open " + what};
  std::string text;
  char chunk[1 << 16];
  while (in) {
    in.read(chunk, static_cast<std::streamsize>(sizeof chunk));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (text.size() + got > kMaxMapFileBytes) return too_large();
    text.append(chunk, got);
  }
  if (in.bad()) return Error{ErrorCode::kIo, path + ": error while reading " + what};
  return text;
}

// Shortest round-trip text of a number ("0.001", "10", "1e-300").
std::string number_text(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

// Parses all of `text` as a whole number in [lo, hi].
bool parse_int(std::string_view text, long lo, long hi, long& out) {
  long value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value < lo || value > hi) {
    return false;
  }
  out = value;
  return true;
}

std::string printable(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (u >= 0x20 && u < 0x7f) return std::string("'") + c + "'";
  static constexpr char kHex[] = "0123456789abcdef";
  return std::string("byte 0x") + kHex[u >> 4] + kHex[u & 15];
}

// ---- MovingAI --------------------------------------------------------------------------------

class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {}
  // The next line without its end-of-line ("\n" or "\r\n"); false at the end of the text.
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
    line = text_.substr(pos_, end - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = end + 1;
    ++number_;
    return true;
  }
  int number() const { return number_; }  // of the line last returned (1-based)

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  int number_ = 0;
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// Splits "key value" at the first run of blanks.
std::pair<std::string_view, std::string_view> key_value(std::string_view line) {
  line = trim(line);
  const std::size_t blank = line.find_first_of(" \t");
  if (blank == std::string_view::npos) return {line, {}};
  return {line.substr(0, blank), trim(line.substr(blank))};
}

enum class MapChar { kFree, kObstacle, kUnknown };

MapChar classify(char c) {
  switch (c) {
    case '.':
    case 'G':
    case 'S':
      return MapChar::kFree;
    case '@':
    case 'O':
    case 'T':
    case 'W':
      return MapChar::kObstacle;
    default:
      return MapChar::kUnknown;
  }
}

// ---- PGM -------------------------------------------------------------------------------------

class PgmReader {
 public:
  PgmReader(std::string_view bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  // Skips whitespace and comments, then reads a token of digits into `value` in [lo, hi].
  Status number(const char* what, long lo, long hi, long& value) {
    skip_space_and_comments();
    if (pos_ >= bytes_.size()) {
      return parse_error(name_, line_, std::string("truncated header: missing ") + what);
    }
    const int column = column_();
    const std::size_t start = pos_;
    while (pos_ < bytes_.size() && !is_space(bytes_[pos_]) && bytes_[pos_] != '#') ++pos_;
    const std::string_view token = bytes_.substr(start, pos_ - start);
    if (!parse_int(token, lo, hi, value)) {
      return parse_error(name_, line_, column,
                         std::string(what) + " must be a whole number in [" + std::to_string(lo) +
                             ", " + std::to_string(hi) + "] (got '" + std::string(token) + "')");
    }
    return Ok{};
  }

  void skip_space_and_comments() {
    while (pos_ < bytes_.size()) {
      const char c = bytes_[pos_];
      if (c == '#') {
        while (pos_ < bytes_.size() && bytes_[pos_] != '\n') ++pos_;
      } else if (is_space(c)) {
        advance();
      } else {
        return;
      }
    }
  }

  void advance() {
    if (bytes_[pos_] == '\n') {
      ++line_;
      line_start_ = pos_ + 1;
    }
    ++pos_;
  }

  static bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
  }

  std::string_view bytes_;
  const std::string& name_;
  std::size_t pos_ = 0;
  std::size_t line_start_ = 0;
  int line_ = 1;

  int column_() const { return static_cast<int>(pos_ - line_start_) + 1; }
};

// ---- ROS map_server YAML ---------------------------------------------------------------------

enum class RosMode { kTrinary, kScale, kRaw };

struct RosMetadata {
  std::string image;
  int image_line = 1;
  double resolution = 0.0;
  double origin_x = 0.0;
  double origin_y = 0.0;
  bool negate = false;
  double occupied_thresh = 0.0;
  double free_thresh = 0.0;
  RosMode mode = RosMode::kTrinary;
};

int line_of(const YAML::Node& node) { return node.Mark().line + 1; }
int column_of(const YAML::Node& node) { return node.Mark().column + 1; }

std::string scalar_text(const YAML::Node& node) {
  return node.IsScalar() ? node.Scalar() : std::string("a non-scalar value");
}

// The metadata of a map_server YAML document; yaml-cpp throws on conversions, so every access
// happens inside the caller's try block.
Result<RosMetadata> read_metadata(const YAML::Node& root, const std::string& name) {
  if (!root.IsMap()) {
    return parse_error(name, root.IsDefined() ? line_of(root) : 1,
                       "expected a YAML mapping with the map_server fields (image, resolution, "
                       "origin, negate, occupied_thresh, free_thresh)");
  }
  for (const char* key :
       {"image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh"}) {
    if (!root[key]) {
      return parse_error(name, line_of(root), std::string("missing required field '") + key + "'");
    }
  }
  RosMetadata m;
  auto bad = [&](const YAML::Node& node, const std::string& what) {
    return parse_error(name, line_of(node), column_of(node),
                       what + " (got " + scalar_text(node) + ")");
  };
  auto number = [&](const YAML::Node& node, double& out) {
    double value = 0.0;
    if (!node.IsScalar() || !YAML::convert<double>::decode(node, value) || !std::isfinite(value)) {
      return false;
    }
    out = value;
    return true;
  };

  const YAML::Node image = root["image"];
  if (!image.IsScalar() || image.Scalar().empty()) {
    return bad(image, "'image' must name the PGM file");
  }
  m.image = image.Scalar();
  m.image_line = line_of(image);

  const YAML::Node resolution = root["resolution"];
  if (!number(resolution, m.resolution) || !(m.resolution >= OccupancyGrid::kMinResolutionM &&
                                             m.resolution <= OccupancyGrid::kMaxResolutionM)) {
    return bad(resolution, "'resolution' must be a number in [" +
                               number_text(OccupancyGrid::kMinResolutionM) + ", " +
                               number_text(OccupancyGrid::kMaxResolutionM) + "] [m/pixel]");
  }

  const YAML::Node origin = root["origin"];
  double yaw = 0.0;
  if (!origin.IsSequence() || origin.size() != 3 || !number(origin[0], m.origin_x) ||
      !number(origin[1], m.origin_y) || !number(origin[2], yaw)) {
    return parse_error(name, line_of(origin), column_of(origin),
                       "'origin' must be a list of three finite numbers [x, y, yaw]");
  }
  if (std::abs(m.origin_x) > OccupancyGrid::kMaxOriginM ||
      std::abs(m.origin_y) > OccupancyGrid::kMaxOriginM) {
    return parse_error(name, line_of(origin), column_of(origin),
                       "'origin' x and y must lie within +-" +
                           std::to_string(static_cast<long>(OccupancyGrid::kMaxOriginM)) + " m");
  }
  // yaw is accepted and not applied, as most of ROS does: the simulator works in the grid frame.

  const YAML::Node negate = root["negate"];
  long negate_int = 0;
  bool negate_bool = false;
  if (negate.IsScalar() && parse_int(negate.Scalar(), 0, 1, negate_int)) {
    m.negate = negate_int == 1;
  } else if (negate.IsScalar() && YAML::convert<bool>::decode(negate, negate_bool)) {
    m.negate = negate_bool;
  } else {
    return bad(negate, "'negate' must be 0, 1, true or false");
  }

  const YAML::Node occupied = root["occupied_thresh"];
  if (!number(occupied, m.occupied_thresh) || m.occupied_thresh < 0.0 || m.occupied_thresh > 1.0) {
    return bad(occupied, "'occupied_thresh' must be a number in [0, 1]");
  }
  const YAML::Node free = root["free_thresh"];
  if (!number(free, m.free_thresh) || m.free_thresh < 0.0 || m.free_thresh > 1.0) {
    return bad(free, "'free_thresh' must be a number in [0, 1]");
  }
  if (m.free_thresh > m.occupied_thresh) {
    return bad(
        free, "'free_thresh' must not exceed occupied_thresh " + std::to_string(m.occupied_thresh));
  }

  if (const YAML::Node mode = root["mode"]) {
    const std::string text = mode.IsScalar() ? mode.Scalar() : "";
    if (text == "trinary") {
      m.mode = RosMode::kTrinary;
    } else if (text == "scale") {
      m.mode = RosMode::kScale;
    } else if (text == "raw") {
      m.mode = RosMode::kRaw;
    } else {
      return bad(mode, "'mode' must be trinary, scale or raw");
    }
  }
  return m;
}

// The ground-truth value of a pixel, as map_server classifies it (Nav2 map_io): the shade is
// the pixel over maxval, inverted when negate is set; occupancy = 1 - shade. trinary and scale
// agree on what is surely free or occupied (scale grades only the unknown band between the
// thresholds, which the ground truth makes an obstacle). raw reads the (negated) pixel on a
// 0..255 scale as an occupancy percentage, values above 100 unknown.
Cell classify_pixel(std::uint16_t pixel, int maxval, const RosMetadata& m) {
  double shade = static_cast<double>(pixel) / maxval;
  if (m.negate) shade = 1.0 - shade;
  double occupancy = 1.0 - shade;
  if (m.mode == RosMode::kRaw) {
    const double percent = std::round(shade * 255.0);
    if (percent > 100.0) return Cell::kUnknown;
    occupancy = percent / 100.0;
  }
  if (occupancy > m.occupied_thresh) return Cell::kObstacle;
  if (occupancy < m.free_thresh) return Cell::kFree;
  return Cell::kUnknown;
}

}  // namespace

Status MapLoadOptions::validate() const {
  if (!std::isfinite(movingai_cell_m) || movingai_cell_m <= 0.0) {
    return invalid_argument("movingai_cell_m must be a finite number > 0 (got " +
                            std::to_string(movingai_cell_m) + ")");
  }
  if (movingai_subdivision < 1 || movingai_subdivision > 100) {
    return invalid_argument("movingai_subdivision must be in [1, 100] (got " +
                            std::to_string(movingai_subdivision) + ")");
  }
  const double cell_m = movingai_cell_m / movingai_subdivision;
  if (!(cell_m >= OccupancyGrid::kMinResolutionM && cell_m <= OccupancyGrid::kMaxResolutionM)) {
    return invalid_argument("movingai_cell_m / movingai_subdivision must be in [" +
                            number_text(OccupancyGrid::kMinResolutionM) + ", " +
                            number_text(OccupancyGrid::kMaxResolutionM) +
                            "] m per grid cell (got " + number_text(cell_m) + ")");
  }
  return Ok{};
}

std::string LoadedMap::describe_cell(int cx, int cy) const {
  const int px = cx / cells_per_pixel;
  const int rows = grid.height() / cells_per_pixel;
  const int row = rows - 1 - cy / cells_per_pixel;  // files store the top row first
  if (format == MapFormat::kMovingAi) {
    return path + ":" + std::to_string(first_row_line + row) + ":" + std::to_string(px + 1);
  }
  return image_path + " pixel (column " + std::to_string(px) + ", row " + std::to_string(row) + ")";
}

Result<LoadedMap> parse_movingai_map(std::string_view text, const std::string& name,
                                     const MapLoadOptions& options) {
  if (auto s = options.validate(); !s) return s.error();
  const long max_side = OccupancyGrid::kMaxSideCells / options.movingai_subdivision;
  LineReader lines(text);
  std::string_view line;

  if (!lines.next(line)) return parse_error(name, 1, "empty file: expected 'type octile'");
  if (key_value(line).first != "type") {
    return parse_error(name, lines.number(),
                       "expected 'type <name>' (got '" + std::string(line) + "')");
  }
  long height = -1;
  long width = -1;
  while (true) {
    if (!lines.next(line)) {
      return parse_error(name, lines.number() + 1, "truncated header: expected 'map'");
    }
    const auto [key, value] = key_value(line);
    if (key == "map" && value.empty()) break;
    long* target = key == "height" ? &height : key == "width" ? &width : nullptr;
    if (target == nullptr) {
      return parse_error(
          name, lines.number(),
          "expected 'height <rows>', 'width <columns>' or 'map' (got '" + std::string(line) + "')");
    }
    if (!parse_int(value, 1, max_side, *target)) {
      return parse_error(name, lines.number(),
                         std::string(key) + " must be a whole number in [1, " +
                             std::to_string(max_side) + "] (got '" + std::string(value) + "')");
    }
  }
  if (height < 0 || width < 0) {
    return parse_error(
        name, lines.number(),
        std::string("header lacks '") + (height < 0 ? "height" : "width") + "' before 'map'");
  }
  const int sub = options.movingai_subdivision;
  const auto w = static_cast<int>(width);
  const auto h = static_cast<int>(height);
  if (static_cast<std::uint64_t>(w * sub) * static_cast<std::uint64_t>(h * sub) >
      OccupancyGrid::kMaxCells) {
    return parse_error(name, lines.number(),
                       "map of " + std::to_string(w) + " x " + std::to_string(h) + " cells at " +
                           std::to_string(sub) + " grid cells per map cell exceeds " +
                           std::to_string(OccupancyGrid::kMaxCells) + " grid cells");
  }
  auto grid =
      OccupancyGrid::create(w * sub, h * sub, options.movingai_cell_m / sub, 0.0, 0.0, Cell::kFree);
  if (!grid) return Error{grid.error().code, name + ": " + grid.error().message};

  LoadedMap map{
      std::move(grid).value(), MapFormat::kMovingAi, name, {}, 0, lines.number() + 1, sub};
  for (int row = 0; row < h; ++row) {
    if (!lines.next(line)) {
      return parse_error(
          name, lines.number() + 1,
          "truncated: expected " + std::to_string(h) + " map rows, found " + std::to_string(row));
    }
    if (line.size() != static_cast<std::size_t>(w)) {
      return parse_error(name, lines.number(),
                         "map row " + std::to_string(row + 1) + " has " +
                             std::to_string(line.size()) + " characters, expected width " +
                             std::to_string(w));
    }
    const int gy = (h - 1 - row) * sub;
    for (int col = 0; col < w; ++col) {
      const MapChar kind = classify(line[static_cast<std::size_t>(col)]);
      if (kind == MapChar::kUnknown) {
        return parse_error(name, lines.number(), col + 1,
                           "unknown map character " +
                               printable(line[static_cast<std::size_t>(col)]) +
                               " (free: . G S; obstacle: @ O T W)");
      }
      if (kind == MapChar::kObstacle) {
        for (int dy = 0; dy < sub; ++dy) {
          for (int dx = 0; dx < sub; ++dx) map.grid.set(col * sub + dx, gy + dy, Cell::kObstacle);
        }
      }
    }
  }
  while (lines.next(line)) {
    if (!trim(line).empty()) {
      return parse_error(name, lines.number(),
                         "more map rows than the header's height " + std::to_string(h));
    }
  }
  return map;
}

Result<PgmImage> parse_pgm(std::string_view bytes, const std::string& name) {
  if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != '5' && bytes[1] != '2')) {
    const std::string magic(bytes.substr(0, std::min<std::size_t>(2, bytes.size())));
    return parse_error(
        name, 1, 1, "not a PGM image: magic '" + magic + "', expected P5 (binary) or P2 (ASCII)");
  }
  const bool binary = bytes[1] == '5';
  PgmReader reader(bytes, name);
  reader.pos_ = 2;
  if (reader.pos_ < bytes.size() && !PgmReader::is_space(bytes[2]) && bytes[2] != '#') {
    return parse_error(name, 1, 3,
                       "expected whitespace after the magic P" + std::string(1, bytes[1]));
  }
  long width = 0;
  long height = 0;
  long maxval = 0;
  if (auto s = reader.number("width", 1, OccupancyGrid::kMaxSideCells, width); !s) return s.error();
  if (auto s = reader.number("height", 1, OccupancyGrid::kMaxSideCells, height); !s) {
    return s.error();
  }
  if (auto s = reader.number("maxval", 1, 65535, maxval); !s) return s.error();
  if (static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) >
      OccupancyGrid::kMaxCells) {
    return parse_error(name, reader.line_,
                       "image of " + std::to_string(width) + " x " + std::to_string(height) +
                           " pixels exceeds " + std::to_string(OccupancyGrid::kMaxCells));
  }
  PgmImage image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  image.maxval = static_cast<int>(maxval);
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  image.pixels.resize(count);

  if (binary) {
    // Exactly one whitespace byte separates maxval from the raster.
    if (reader.pos_ >= bytes.size() || !PgmReader::is_space(bytes[reader.pos_])) {
      return parse_error(name, reader.line_,
                         "truncated: no pixel data after the header (expected " +
                             std::to_string(count) + " pixels)");
    }
    const int raster_line = reader.line_ + (bytes[reader.pos_] == '\n' ? 1 : 0);
    const std::size_t start = reader.pos_ + 1;
    const std::size_t bytes_per_pixel = maxval > 255 ? 2 : 1;
    const std::size_t needed = count * bytes_per_pixel;
    const std::size_t available = bytes.size() - start;
    if (available < needed) {
      return parse_error(name, raster_line,
                         "truncated raster: expected " + std::to_string(needed) +
                             " bytes of pixels for " + std::to_string(width) + " x " +
                             std::to_string(height) + ", found " + std::to_string(available));
    }
    for (std::size_t i = 0; i < count; ++i) {
      const auto* p =
          reinterpret_cast<const unsigned char*>(bytes.data() + start + i * bytes_per_pixel);
      const auto value =
          static_cast<std::uint16_t>(bytes_per_pixel == 2 ? (p[0] << 8) | p[1] : p[0]);
      if (value > maxval) {
        return parse_error(name, raster_line,
                           "pixel " + std::to_string(i) + " (column " +
                               std::to_string(i % static_cast<std::size_t>(width)) + ", row " +
                               std::to_string(i / static_cast<std::size_t>(width)) + ") is " +
                               std::to_string(value) + ", above maxval " + std::to_string(maxval));
      }
      image.pixels[i] = value;
    }
    return image;
  }
  for (std::size_t i = 0; i < count; ++i) {
    long value = 0;
    reader.skip_space_and_comments();
    if (reader.pos_ >= bytes.size()) {
      return parse_error(name, reader.line_,
                         "truncated raster: expected " + std::to_string(count) +
                             " pixel values, found " + std::to_string(i));
    }
    if (auto s = reader.number("pixel value", 0, maxval, value); !s) return s.error();
    image.pixels[i] = static_cast<std::uint16_t>(value);
  }
  return image;
}

Result<LoadedMap> load_movingai_map(const std::string& path, const MapLoadOptions& options) {
  auto text = read_file(path, "MovingAI map");
  if (!text) return text.error();
  return parse_movingai_map(*text, path, options);
}

namespace {

Result<RosMetadata> parse_ros_metadata(std::string_view yaml_text, const std::string& yaml_name) {
  try {
    const YAML::Node root = YAML::Load(std::string(yaml_text));
    return read_metadata(root, yaml_name);
  } catch (const YAML::Exception& e) {
    return parse_error(yaml_name, e.mark.line + 1, e.mark.column + 1, e.msg);
  }
}

// The image the metadata names, resolved against the YAML file's folder.
std::string image_path_of(const RosMetadata& meta, const std::string& yaml_name) {
  std::filesystem::path image_path(meta.image);
  if (image_path.is_relative()) {
    image_path = std::filesystem::path(yaml_name).parent_path() / image_path;
  }
  return image_path.string();
}

Result<LoadedMap> ros_map_of(const RosMetadata& meta, const std::string& yaml_name,
                             std::string_view pgm_bytes, const std::string& image_name) {
  auto image = parse_pgm(pgm_bytes, image_name);
  if (!image) return image.error();
  auto grid = OccupancyGrid::create(image->width, image->height, meta.resolution, meta.origin_x,
                                    meta.origin_y, Cell::kFree);
  if (!grid) return Error{grid.error().code, yaml_name + ": " + grid.error().message};
  LoadedMap map{std::move(grid).value(), MapFormat::kRosMapServer, yaml_name, image_name, 0, 0, 1};
  for (int row = 0; row < image->height; ++row) {
    for (int col = 0; col < image->width; ++col) {
      const std::size_t i = static_cast<std::size_t>(row) * static_cast<std::size_t>(image->width) +
                            static_cast<std::size_t>(col);
      const Cell value = classify_pixel(image->pixels[i], image->maxval, meta);
      if (value == Cell::kFree) continue;
      if (value == Cell::kUnknown) ++map.unknown_pixels;
      map.grid.set(col, image->height - 1 - row, Cell::kObstacle);
    }
  }
  return map;
}

}  // namespace

Result<LoadedMap> parse_ros_map(std::string_view yaml_text, const std::string& yaml_name,
                                std::string_view pgm_bytes) {
  auto meta = parse_ros_metadata(yaml_text, yaml_name);
  if (!meta) return meta.error();
  return ros_map_of(*meta, yaml_name, pgm_bytes, image_path_of(*meta, yaml_name));
}

Result<LoadedMap> load_ros_map(const std::string& yaml_path) {
  auto text = read_file(yaml_path, "map_server YAML");
  if (!text) return text.error();
  auto meta = parse_ros_metadata(*text, yaml_path);
  if (!meta) return meta.error();
  const std::string image_path = image_path_of(*meta, yaml_path);
  auto bytes = read_file(image_path, "PGM image");
  if (!bytes) {
    return Error{ErrorCode::kIo, yaml_path + ":" + std::to_string(meta->image_line) + ": image '" +
                                     meta->image + "' cannot be read (" + bytes.error().message +
                                     ")"};
  }
  return ros_map_of(*meta, yaml_path, *bytes, image_path);
}

Result<LoadedMap> load_map(const std::string& path, const MapLoadOptions& options) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".map") return load_movingai_map(path, options);
  if (ext == ".yaml" || ext == ".yml") return load_ros_map(path);
  return invalid_argument(path + ": unknown map format '" + ext +
                          "': expected a MovingAI .map or a ROS map_server .yaml");
}

}  // namespace grip::sim
