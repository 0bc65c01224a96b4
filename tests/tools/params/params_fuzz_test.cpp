// The parameter file reader on damaged files: every damaged copy of a good file is read or
// refused at a place ("fuzz.yaml:LINE:COLUMN: "); none crashes, hangs or reads out of bounds
// (run under ASan too), and what is read is a valid set that reads back to itself.

#include <gtest/gtest.h>

#include <string>

#include "damaged_text.hpp"
#include "grip/common/random.hpp"
#include "grip/params/params.hpp"

namespace {

using grip::testing::damaged;

// "fuzz.yaml:<digits>:<digits>: ".
bool names_a_place(const std::string& message) {
  const std::string head = "fuzz.yaml:";
  if (!message.starts_with(head)) return false;
  std::size_t at = head.size();
  for (const char end : {':', ':'}) {
    const std::size_t digits = message.find_first_not_of("0123456789", at);
    if (digits == at || digits == std::string::npos || message[digits] != end) return false;
    at = digits + 1;
  }
  return message.compare(at, 1, " ") == 0;
}

TEST(ParamsFuzz, DamagedFilesAreReadOrRefusedAtAPlace) {
  grip::Random rng(21);
  int refused = 0;
  for (const grip::VehicleKind kind :
       {grip::VehicleKind::kDdVelocity, grip::VehicleKind::kDdAcceleration,
        grip::VehicleKind::kCar}) {
    const std::string good = grip::params::to_yaml(grip::params::default_params(kind));
    for (int i = 0; i < 1000; ++i) {
      const std::string text = damaged(good, rng);
      const auto read = grip::params::parse_params(text, "fuzz.yaml");
      if (!read.ok()) {
        ++refused;
        ASSERT_TRUE(names_a_place(read.error().message)) << read.error().message << "\n" << text;
        continue;
      }
      ASSERT_TRUE(grip::params::validate(*read).ok()) << text;
      const auto again = grip::params::parse_params(grip::params::to_yaml(*read), "again.yaml");
      ASSERT_TRUE(again.ok()) << again.error().message;
      ASSERT_EQ(*again, *read) << text;
    }
  }
  EXPECT_GT(refused, 500);  // the damage does break files
}

}  // namespace
