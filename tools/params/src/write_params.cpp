// Writing a parameter set as a parameter file: every key of fields.hpp in its order, with its
// comment, numbers in their shortest text that reads back to the same double.

#include <cstdio>
#include <string>

#include "fields.hpp"

namespace grip::params {

namespace {

using detail::Field;

// A YAML double-quoted string: any text reads back as itself.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\x%02x", static_cast<unsigned>(c));
      out += escape;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string value_text(const Field& f, GripParams& params) {
  return std::visit(
      [&f](const auto* value) -> std::string {
        using T = std::remove_cvref_t<decltype(*value)>;
        if constexpr (std::is_same_v<T, bool>) {
          return *value ? "true" : "false";
        } else if constexpr (std::is_same_v<T, std::string>) {
          return quoted(*value);
        } else if constexpr (std::is_same_v<T, platform::PolicyRequest>) {
          return std::string(platform::request_name(*value));
        } else {
          if (f.auto_value && static_cast<double>(*value) == *f.auto_value) return "auto";
          if constexpr (std::is_same_v<T, double>) {
            return detail::format_number(*value);
          } else {
            return std::to_string(*value);
          }
        }
      },
      f.value(params));
}

void write_line(std::string& out, std::size_t depth, std::string_view key, const std::string& value,
                std::string_view comment) {
  out.append(2 * depth, ' ');
  out += key;
  out += ':';
  if (!value.empty()) out += " " + value;
  if (!comment.empty()) out += "  # " + std::string(comment);
  out += '\n';
}

// The keys of one section; a nested mapping's keys ("footprint.front_m") under its row.
void write_fields(std::string& out, std::span<const Field> fields, GripParams& params) {
  for (const Field& f : fields) {
    const std::size_t dot = f.key.rfind('.');
    const std::size_t depth = dot == std::string_view::npos ? 1 : 2;
    const std::string_view key = dot == std::string_view::npos ? f.key : f.key.substr(dot + 1);
    write_line(out, depth, key, f.value ? value_text(f, params) : "", f.comment);
  }
}

}  // namespace

std::string to_yaml(const GripParams& params) {
  GripParams p = params;  // the fields' accessors take a GripParams they may write
  std::string out =
      "# grip parameters: SI units, the unit in each key; \"auto\": derived at start-up.\n"
      "# A key left out takes its default; a vehicle key the default of vehicle.model.\n"
      "vehicle:\n";
  write_line(out, 1, detail::kModelKey, std::string(vehicle_name(vehicle_kind(p.vehicle))),
             "dd-vel | dd-accel | car: decides the vehicle's other keys");
  write_fields(out, detail::vehicle_fields(vehicle_kind(p.vehicle)), p);
  for (const detail::Section& s : detail::other_sections()) {
    out += "\n# " + std::string(s.comment) + "\n";
    write_line(out, 0, s.key, "", "");
    write_fields(out, s.fields, p);
  }
  return out;
}

}  // namespace grip::params
