// libFuzzer target: a stream of received MapUpdates, each validated and applied by the
// planner's map receiver (gaps, snapshots, healing), and the planner's use of the map it then
// holds: the planner builds its planning session (grids, collision checker, pools) on that
// geometry, which must either work or be refused with a message (never a crash or an exit).

#include <cstdint>
#include <cstdlib>
#include <vector>

#include "fuzz_bytes.hpp"
#include "grip/link/map_sync.hpp"
#include "grip/rt/replanning_session.hpp"
#include "grip/vehicles/vehicle_params.hpp"
#include "samples.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  grip::fuzz::FuzzBytes in(data, size);
  // Small maps keep each run fast; the geometry checks do not depend on the cap.
  grip::link::MapReceiver receiver(1U << 14);
  std::vector<std::uint8_t> cells;
  bool had_map = false;
  for (int i = 0; i < 8 && in.remaining() > 0; ++i) {
    const grip_msg_MapUpdate msg = grip::fuzz::map_update_from(in, cells);
    const grip::link::MapApplied applied = receiver.apply(msg);
    if (!applied.verdict.ok()) {
      if (grip::link::rejection_name(applied.verdict.reason).empty()) std::abort();
      continue;
    }
    if (!receiver.has_map()) std::abort();
    const grip::OccupancyGrid& map = receiver.map();
    if (!applied.changed.empty() && !(map.in_bounds(applied.changed.x0, applied.changed.y0) &&
                                      map.in_bounds(applied.changed.x1, applied.changed.y1))) {
      std::abort();
    }
    if (!had_map) {
      had_map = true;
      grip::with_default_vehicle(grip::VehicleKind::kDdVelocity, [&](const auto& vehicle) {
        using V = std::remove_cvref_t<decltype(vehicle)>;
        auto session =
            grip::rt::ReplanningSession<V>::create(vehicle, map, grip::rt::SessionConfig{});
        if (!session && session.error().message.empty()) std::abort();
      });
    }
    static_cast<void>(grip::link::map_checksum(map));
  }
  return 0;
}
