#pragma once
// The parameter file's keys, one table per section: the reader, the writer and the range
// checks' messages all take a key's spelling from here, so every key is written once.
// Private to grip_params.

#include <charconv>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "grip/params/params.hpp"

namespace grip::params::detail {

// Where a value lives in GripParams, with its type. The unsigned fields are std::uint32_t or
// unsigned, one type on every platform grip builds for.
static_assert(std::is_same_v<std::uint32_t, unsigned>);
using ValueRef =
    std::variant<double*, unsigned*, int*, bool*, std::string*, platform::PolicyRequest*>;

struct Field {
  // Within its section; "footprint.front_m" for a key of a nested mapping, which has a row of
  // its own ("footprint") without a value.
  std::string_view key;
  ValueRef (*value)(GripParams&) = nullptr;  // nullptr: a nested mapping's row
  std::string_view comment;                  // one line for the file's reader; empty: none
  // The value the word "auto" stands for (written as "auto" when the value is exactly this);
  // nullopt: the key takes no "auto".
  std::optional<double> auto_value = std::nullopt;
};

struct Section {
  std::string_view key;
  std::string_view comment;
  std::span<const Field> fields;
};

inline constexpr std::string_view kModelKey = "model";

// The vehicle section's keys for one model, "model" aside; its values live in that model's
// alternative of GripParams::vehicle.
std::span<const Field> vehicle_fields(VehicleKind kind) noexcept;
// Every section after "vehicle", in the order the file is written.
std::span<const Section> other_sections() noexcept;

// The key of the value at `address` inside `params` ("planner.cycle_s"); empty when no field
// holds it (a value that is not a parameter, as the frontier's clearance_m).
std::string key_of(const GripParams& params, const void* address);

// Shortest text that reads back to the same double ("0.05", "3", "1.5707963267948966").
inline std::string format_number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

// The first value of a parameter set out of range: its key and the sentence saying why, which
// starts with the key ("planner.budget_s must be in (0, cycle_s = 0.05) (got 0.06)").
struct RangeError {
  std::string key;
  std::string message;
};
std::optional<RangeError> first_range_error(const GripParams& params);

}  // namespace grip::params::detail
