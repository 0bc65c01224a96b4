// libFuzzer target: the MovingAI .map loader on any text, then the simulator's use of what it
// accepted. A rejection must name the file; nothing may crash, hang or overflow.

#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "map_use.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  // The simulator's default (1 m cells of 10 x 10 grid cells) on small inputs, where the grid
  // stays small; one grid cell per map cell on all of them.
  grip::sim::MapLoadOptions fine;
  fine.movingai_cell_m = 0.1;
  fine.movingai_subdivision = 1;
  for (const grip::sim::MapLoadOptions& options : {fine, grip::sim::MapLoadOptions{}}) {
    if (options.movingai_subdivision > 1 && size > 512) break;
    auto map = grip::sim::parse_movingai_map(text, "fuzz.map", options);
    if (!map) {
      if (map.error().message.rfind("fuzz.map:", 0) != 0) std::abort();
      continue;
    }
    grip::fuzz::use_loaded_map(*map);
  }
  return 0;
}
