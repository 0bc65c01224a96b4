// Reading a parameter file: yaml-cpp parses, this walks the tables of fields.hpp and keeps the
// line and column of every value it reads, so that a value found out of range afterwards
// (validate(), params.cpp) is still reported where it is written.

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <climits>
#include <cmath>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "fields.hpp"
#include "read_file.hpp"

namespace grip::params {

namespace {

using detail::Field;
// A mapping's keys and values in the file's order.
using Entries = std::vector<std::pair<std::string, YAML::Node>>;

constexpr std::array<VehicleKind, 3> kModels{VehicleKind::kDdVelocity, VehicleKind::kDdAcceleration,
                                             VehicleKind::kCar};

std::string what_it_is(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Sequence:
      return "a sequence";
    case YAML::NodeType::Map:
      return "a mapping";
    case YAML::NodeType::Scalar:
      return node.Tag() == "?" ? "'" + node.Scalar() + "'" : "the string '" + node.Scalar() + "'";
    default:
      return "nothing";
  }
}

// YAML allows a number a leading '+', std::from_chars does not.
std::string_view without_plus(std::string_view text) {
  const bool plus = text.size() > 1 && text[0] == '+' && text[1] != '+' && text[1] != '-';
  return plus ? text.substr(1) : text;
}

// The whole of `text` as a number; nullopt when it is not one. YAML's own spellings of the
// non-finite values (.inf, .nan) and numbers beyond a double come back too, as non-finite
// values, so that they are refused as such.
std::optional<double> number_in(std::string_view text) {
  const std::string_view digits = without_plus(text);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (end == digits.data() + digits.size() && !digits.empty()) {
    if (ec == std::errc()) return value;
    if (ec == std::errc::result_out_of_range) return HUGE_VAL;
  }
  if (YAML::convert<double>::decode(YAML::Node(std::string(text)), value) &&
      !std::isfinite(value)) {
    return value;
  }
  return std::nullopt;
}

std::optional<long long> whole_number_in(std::string_view text) {
  const std::string_view digits = without_plus(text);
  long long value = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec != std::errc() || end != digits.data() + digits.size() || digits.empty()) {
    return std::nullopt;
  }
  return value;
}

class Reader {
 public:
  explicit Reader(std::string_view name) : name_(name) {}

  Result<GripParams> read(const YAML::Node& root) {
    const YAML::Mark start = root.IsNull() ? YAML::Mark() : root.Mark();
    if (!root.IsNull() && !root.IsMap()) {
      return error_at(start, "expected a mapping of the sections (" + allowed_sections() +
                                 "), got " + what_it_is(root));
    }
    Entries sections;
    if (auto e = check_keys(
            root, "", "allowed: " + allowed_sections(), sections,
            [](std::string_view key) { return key == "vehicle" || section(key) != nullptr; })) {
      return *std::move(e);
    }
    auto kind = read_model(sections, start);
    if (!kind) return kind.error();
    GripParams params = default_params(*kind);
    for (const auto& [key, node] : sections) {
      const detail::Section* s = section(key);
      const auto fields = s ? s->fields : detail::vehicle_fields(*kind);
      if (auto e = read_mapping(node, key, fields, "", params)) return *std::move(e);
    }
    if (auto range = detail::first_range_error(params)) {
      return error_at(mark_of(range->key, start), range->message);
    }
    return params;
  }

  Error error_at(const YAML::Mark& mark, const std::string& message) const {
    return invalid_argument(std::string(name_) + ":" + std::to_string(mark.line + 1) + ":" +
                            std::to_string(mark.column + 1) + ": " + message);
  }

 private:
  static const detail::Section* section(std::string_view key) {
    for (const auto& s : detail::other_sections()) {
      if (s.key == key) return &s;
    }
    return nullptr;
  }
  static std::string allowed_sections() {
    std::string list = "vehicle";
    for (const auto& s : detail::other_sections()) list += ", " + std::string(s.key);
    return list;
  }

  // The keys of `map` at `path` ("" at the top), in the file's order: each a scalar, none twice,
  // each one `known` accepts (else the error lists `allowed`). Records the marks of the values.
  template <typename Known>
  std::optional<Error> check_keys(const YAML::Node& map, const std::string& path,
                                  const std::string& allowed, Entries& entries, Known known) {
    if (map.IsNull()) return std::nullopt;  // a section with every key left out
    if (!map.IsMap()) {
      return error_at(map.Mark(), path + ": expected a mapping, got " + what_it_is(map));
    }
    // yaml-cpp's iterators hand out their pairs by value: the nodes are copies (handles).
    for (const auto& pair : map) {
      const YAML::Node key_node = pair.first;
      const YAML::Node value = pair.second;
      if (!key_node.IsScalar()) {
        return error_at(key_node.Mark(), (path.empty() ? "" : path + ": ") +
                                             "expected a key, got " + what_it_is(key_node));
      }
      const std::string key = key_node.Scalar();
      const std::string full = path.empty() ? key : path + "." + key;
      if (const auto first = marks_.find(full); first != marks_.end()) {
        return error_at(key_node.Mark(), full + ": duplicate key (first at line " +
                                             std::to_string(first->second.line + 1) + ")");
      }
      if (!known(key)) return error_at(key_node.Mark(), full + ": unknown key (" + allowed + ")");
      entries.emplace_back(key, value);
      // A scalar's own mark; a mapping's (and a key with nothing after it) is its key's.
      marks_[full] = value.IsScalar() ? value.Mark() : key_node.Mark();
    }
    return std::nullopt;
  }

  Result<VehicleKind> read_model(const Entries& sections, const YAML::Mark& start) {
    std::string models;
    for (VehicleKind k : kModels) {
      models += (models.empty() ? "" : ", ") + std::string(vehicle_name(k));
    }
    const auto vehicle = std::find_if(sections.begin(), sections.end(),
                                      [](const auto& entry) { return entry.first == "vehicle"; });
    if (vehicle == sections.end()) {
      return error_at(start, "vehicle.model is required (" + models + ")");
    }
    const YAML::Node& section = vehicle->second;
    if (!section.IsNull() && !section.IsMap()) {
      return error_at(section.Mark(), "vehicle: expected a mapping, got " + what_it_is(section));
    }
    const YAML::Node model =
        section.IsMap() ? section[std::string(detail::kModelKey)] : YAML::Node();
    if (!model.IsDefined() || model.IsNull()) {
      return error_at(marks_.at("vehicle"), "vehicle.model is required (" + models + ")");
    }
    for (VehicleKind k : kModels) {
      if (model.IsScalar() && model.Scalar() == vehicle_name(k)) return k;
    }
    return error_at(model.Mark(),
                    "vehicle.model: expected one of " + models + ", got " + what_it_is(model));
  }

  // The keys of one section's mapping, or of a mapping nested in it (`prefix`: "footprint.").
  std::optional<Error> read_mapping(const YAML::Node& map, const std::string& path,
                                    std::span<const Field> fields, const std::string& prefix,
                                    GripParams& params) {
    const bool vehicle = path == "vehicle";
    std::string allowed = vehicle
                              ? "model " + std::string(vehicle_name(vehicle_kind(params.vehicle))) +
                                    " allows: " + std::string(detail::kModelKey)
                              : "allowed:";
    for (const Field& f : fields) {
      const std::string_view rest = f.key.substr(std::min(prefix.size(), f.key.size()));
      if (f.key.starts_with(prefix) && rest.find('.') == std::string_view::npos) {
        allowed += (allowed.ends_with(":") ? " " : ", ") + std::string(rest);
      }
    }
    const auto field = [&](std::string_view key) -> const Field* {
      for (const Field& f : fields) {
        if (f.key.size() == prefix.size() + key.size() && f.key.starts_with(prefix) &&
            f.key.ends_with(key)) {
          return &f;
        }
      }
      return nullptr;
    };
    Entries entries;
    if (auto e = check_keys(map, path, allowed, entries, [&](std::string_view key) {
          return field(key) != nullptr || (vehicle && key == detail::kModelKey);
        })) {
      return e;
    }
    for (const auto& [key, node] : entries) {
      const Field* f = field(key);
      if (f == nullptr) continue;  // vehicle.model, read first
      const std::string full = path + "." + key;
      if (f->value == nullptr) {
        if (auto e = read_mapping(node, full, fields, std::string(f->key) + ".", params)) return e;
      } else if (auto e = read_value(node, full, *f, params)) {
        return e;
      }
    }
    return std::nullopt;
  }

  std::optional<Error> read_value(const YAML::Node& node, const std::string& key, const Field& f,
                                  GripParams& params) {
    const bool plain = node.IsScalar() && node.Tag() == "?";
    const std::string text = node.IsScalar() ? node.Scalar() : "";
    const bool is_auto = f.auto_value && plain && text == "auto";
    const std::string or_auto = f.auto_value ? " or auto" : "";
    const auto refuse = [&](const std::string& expected) -> std::optional<Error> {
      return error_at(marks_.at(key), key + ": expected " + expected + ", got " + what_it_is(node));
    };
    const auto whole = [&](auto* out, long long lo, long long hi) -> std::optional<Error> {
      using T = std::remove_pointer_t<decltype(out)>;
      const auto n = plain ? whole_number_in(text) : std::nullopt;
      if (is_auto) {
        *out = static_cast<T>(*f.auto_value);
      } else if (n && *n >= lo && *n <= hi) {
        *out = static_cast<T>(*n);
      } else {
        return refuse("a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]" +
                      or_auto);
      }
      return std::nullopt;
    };
    return std::visit(
        [&](auto* out) -> std::optional<Error> {
          using T = std::remove_pointer_t<decltype(out)>;
          if constexpr (std::is_same_v<T, double>) {
            const auto n = plain ? number_in(text) : std::nullopt;
            if (is_auto) {
              *out = *f.auto_value;
            } else if (!n) {
              return refuse("a number" + or_auto);
            } else if (!std::isfinite(*n)) {
              return refuse("a finite number" + or_auto);
            } else {
              *out = *n;
            }
          } else if constexpr (std::is_same_v<T, unsigned>) {
            return whole(out, 0, UINT_MAX);
          } else if constexpr (std::is_same_v<T, int>) {
            return whole(out, INT_MIN, INT_MAX);
          } else if constexpr (std::is_same_v<T, bool>) {
            if (!plain || (text != "true" && text != "false")) return refuse("true or false");
            *out = text == "true";
          } else if constexpr (std::is_same_v<T, std::string>) {
            if (!node.IsScalar()) return refuse("a string (\"\" for none)");
            *out = text;
          } else {
            if (!node.IsScalar()) return refuse("a scheduling policy");
            auto policy = platform::parse_policy_request(text);
            if (!policy) return error_at(marks_.at(key), key + ": " + policy.error().message);
            *out = *policy;
          }
          return std::nullopt;
        },
        f.value(params));
  }

  // Where the value of `key` is written; else where the nearest mapping around it is (a rule
  // broken by a default, as budget_s against a shorter cycle_s given in the file).
  YAML::Mark mark_of(std::string key, const YAML::Mark& start) const {
    while (!key.empty()) {
      if (const auto it = marks_.find(key); it != marks_.end()) return it->second;
      const std::size_t dot = key.rfind('.');
      key = dot == std::string::npos ? "" : key.substr(0, dot);
    }
    return start;
  }

  std::string_view name_;
  std::map<std::string, YAML::Mark, std::less<>> marks_;  // by key: "planner.cycle_s"
};

}  // namespace

Result<GripParams> parse_params(std::string_view text, std::string_view name) {
  Reader reader(name);
  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(std::string(text));
  } catch (const YAML::Exception& e) {
    return reader.error_at(e.mark, "invalid YAML: " + e.msg);
  }
  if (documents.size() > 1) {
    return reader.error_at(documents[1].Mark(), "a second YAML document: a parameter file is one");
  }
  return reader.read(documents.empty() ? YAML::Node() : documents.front());
}

Result<GripParams> load_params(const std::string& path) {
  auto text = detail::read_parameter_file(path);
  if (!text) return text.error();
  return parse_params(*text, path);
}

}  // namespace grip::params
