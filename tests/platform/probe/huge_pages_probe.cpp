// A helper program for the huge pages test: says who it is (pid, name) before and after
// prefer_huge_pages(), which may start it again, then what glibc was told and whether a large
// allocation it writes is backed by huge pages.

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>

#include "grip/platform/memory.hpp"

int main(int argc, char** argv) {
  std::string name;
  std::getline(std::ifstream("/proc/self/comm"), name);
  std::cout << "GRIP_PROBE started pid=" << getpid() << " name=" << name
            << " argument=" << (argc > 1 ? argv[1] : "")
            << std::endl;  // flushed: an exec would drop what is buffered
  grip::platform::prefer_huge_pages(argv);
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::cout << "GRIP_PROBE tunables=" << (tunables != nullptr ? tunables : "") << "\n";
  constexpr std::size_t kBytes = std::size_t{64} << 20;
  auto* block = static_cast<char*>(std::malloc(kBytes));
  if (block == nullptr) return 1;
  std::memset(block, 1, kBytes);
  std::ifstream rollup("/proc/self/smaps_rollup");
  std::string key;
  long long kb = -1;
  while (rollup >> key) {
    if (key == "AnonHugePages:") {
      rollup >> kb;
      break;
    }
  }
  std::cout << "GRIP_PROBE anon_huge_kb=" << kb << " checksum=" << static_cast<int>(block[12345])
            << "\n";
  std::free(block);
  return 0;
}
