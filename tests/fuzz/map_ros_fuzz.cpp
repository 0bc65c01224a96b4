// libFuzzer target: the ROS map_server loader (YAML metadata + PGM image) on any bytes, then
// the simulator's use of what it accepted. The input is the YAML text, a NUL byte, then the
// PGM's bytes (tests/fuzz/corpus/map_ros holds examples). A rejection must name a file.

#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "map_use.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = all.find('\0');
  const std::string_view yaml = all.substr(0, nul);
  const std::string_view pgm =
      nul == std::string_view::npos ? std::string_view{} : all.substr(nul + 1);
  auto map = grip::sim::parse_ros_map(yaml, "dir/fuzz.yaml", pgm);
  if (!map) {
    // The message names the YAML or the image it names (which may be any path).
    if (map.error().message.empty()) std::abort();
    return 0;
  }
  grip::fuzz::use_loaded_map(*map);
  return 0;
}
