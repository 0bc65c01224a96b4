// The map parsers on damaged input: every mutation of a good file either parses or returns an
// error that names the file; none crashes, hangs or reads out of bounds (run under ASan too).

#include <gtest/gtest.h>

#include <string>

#include "damaged_text.hpp"
#include "grip/common/random.hpp"
#include "grip/sim/map_file.hpp"

namespace grip::sim {
namespace {

using grip::testing::damaged;

TEST(MapParserFuzzTest, DamagedMovingAiMapsParseOrFailNamingTheFile) {
  const std::string good = "type octile\nheight 4\nwidth 6\nmap\n@@@@@@\n@..G.@\n@.S.T@\n@@@@@@\n";
  ASSERT_TRUE(parse_movingai_map(good, "fuzz.map").ok());
  Random rng(11);
  int failures = 0;
  for (int i = 0; i < 3000; ++i) {
    const std::string text = damaged(good, rng);
    auto r = parse_movingai_map(text, "fuzz.map");
    if (!r.ok()) {
      ++failures;
      ASSERT_EQ(r.error().message.rfind("fuzz.map:", 0), 0U) << r.error().message;
    } else {
      ASSERT_GE(r->grid.cell_count(), 1U);
    }
  }
  EXPECT_GT(failures, 1000);  // the mutations do break files
}

TEST(MapParserFuzzTest, DamagedPgmImagesParseOrFailNamingTheFile) {
  std::string binary = "P5\n# c\n4 3\n255\n";
  for (int i = 0; i < 12; ++i) binary.push_back(static_cast<char>(i * 20));
  const std::string ascii = "P2\n4 3\n15\n0 1 2 3\n4 5 6 7\n8 9 10 15\n";
  Random rng(12);
  for (const std::string& good : {binary, ascii}) {
    ASSERT_TRUE(parse_pgm(good, "fuzz.pgm").ok());
    for (int i = 0; i < 3000; ++i) {
      const std::string bytes = damaged(good, rng);
      auto r = parse_pgm(bytes, "fuzz.pgm");
      if (!r.ok()) {
        ASSERT_EQ(r.error().message.rfind("fuzz.pgm:", 0), 0U) << r.error().message;
      } else {
        ASSERT_EQ(r->pixels.size(),
                  static_cast<std::size_t>(r->width) * static_cast<std::size_t>(r->height));
        for (const auto p : r->pixels) ASSERT_LE(p, r->maxval);
      }
    }
  }
}

}  // namespace
}  // namespace grip::sim
