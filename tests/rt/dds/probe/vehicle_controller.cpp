// The vehicle controller as a separate process, for the planner participant's liveliness
// test: it publishes the state, map and goal of tests/rt/dds/vehicle_side.hpp every 10 ms and
// takes plans, until killed. Usage: grip_vehicle_controller_probe DOMAIN

#include <cstdio>
#include <cstdlib>
#include <thread>

#include "../vehicle_side.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s DOMAIN\n", argv[0]);
    return 2;
  }
  const auto domain =
      static_cast<grip::platform::dds::DomainId>(std::strtoul(argv[1], nullptr, 10));
  auto vehicle = grip::link::testing::VehicleSide::create(domain, grip::VehicleKind::kDdVelocity);
  if (!vehicle || !vehicle->publish_goal()) {
    std::fprintf(stderr, "vehicle controller probe: DDS set-up failed\n");
    return 1;
  }
  for (;;) {
    vehicle->service();
    static_cast<void>(vehicle->link().take_plan());
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}
