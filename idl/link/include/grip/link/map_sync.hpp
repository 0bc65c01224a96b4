#pragma once
// Map synchronisation over MapUpdate / MapRequest (idl/map_update.idl): both ends of the
// contract, with no DDS calls in them, so that tests can drop, reorder or corrupt updates at will.
//
// MapSender (the mapping side) owns the authoritative map, numbers every update it emits, cuts
// rectangles into patches that fit one message, and answers a request with a snapshot.
// MapReceiver (the planner) validates each update, applies it, and detects every gap: a
// sequence number that is not the next one. It is in sync only after it applied every part of
// one snapshot without a gap and every update since; out of sync it asks for a snapshot (and
// asks again while none completes), and it keeps applying what arrives, which is never older
// than what it has. Both run on ordinary threads; they allocate only when created.

#include <cstdint>
#include <optional>
#include <vector>

#include "grip/common/function_ref.hpp"
#include "grip/link/messages.hpp"
#include "grip/world/occupancy_grid.hpp"
#include "map_update.h"

namespace grip::link {

// Equal maps have equal checksums; the planner reports its map's in the status so that anyone
// can compare it with the mapper's. FNV-1a (64 bit) over the geometry XOR, for every cell, a
// 64-bit mix of its index and value: a write changes it at the cost of the cells written, not
// of the map (cells_checksum).
std::uint64_t map_checksum(const OccupancyGrid& grid) noexcept;
// The cells of `box` (inside the grid): their share of map_checksum. XORed out of a checksum
// before they are written and in after, it keeps the checksum of a changing map.
std::uint64_t cells_checksum(const OccupancyGrid& grid, const CellBox& box) noexcept;

// The largest square patch side: kMaxPatchCells = 256 x 256.
inline constexpr int kPatchSideCells = 256;

class MapSender {
 public:
  using Send = FunctionRef<void(const grip_msg_MapUpdate&)>;

  explicit MapSender(OccupancyGrid map);

  // The authoritative map. Change it, then send_updates() for where it changed.
  OccupancyGrid& map() noexcept { return map_; }
  const OccupancyGrid& map() const noexcept { return map_; }

  // Emits the cells of `box` (clipped to the map) as updates of at most 256 x 256 cells, each
  // with the next sequence number. A message that `send` fails to deliver is a gap to the
  // receiver, which heals it: sequence numbers are never reused.
  void send_updates(const CellBox& box, std::uint64_t stamp_ns, Send send);
  // Emits the whole map as one snapshot: consecutive updates, parts 0 .. n-1 of a new id.
  void send_snapshot(std::uint64_t stamp_ns, Send send);

  std::uint64_t last_sequence() const noexcept { return sequence_; }
  std::uint64_t snapshots_sent() const noexcept { return snapshot_id_; }

 private:
  void emit(const CellBox& patch, std::uint64_t stamp_ns, std::uint64_t snapshot_id,
            std::uint32_t part, std::uint32_t parts, Send send);

  OccupancyGrid map_;
  std::uint64_t sequence_ = 0;
  std::uint64_t snapshot_id_ = 0;
  std::vector<std::uint8_t> cells_;  // the patch being sent, kMaxPatchCells
};

struct MapApplied {
  Verdict verdict;      // rejected when !verdict.ok(): nothing changed
  bool gap = false;     // a sequence number was skipped (or went backwards: publisher restart)
  bool healed = false;  // this update completed a snapshot after a gap
  bool synced = false;  // this update completed a snapshot (first sync or heal)
  CellBox changed;      // the patch rectangle, applied
};

class MapReceiver {
 public:
  // Accepts maps of up to max_map_cells; the map is created from the first valid update.
  explicit MapReceiver(std::uint32_t max_map_cells) : max_map_cells_(max_map_cells) {}

  MapApplied apply(const grip_msg_MapUpdate& msg);

  // Out of sync and no request made within `retry_ns`: the caller should send a MapRequest for
  // next_expected() now, and then call note_requested().
  bool should_request(std::int64_t now_ns, std::int64_t retry_ns) const noexcept;
  void note_requested(std::int64_t now_ns) noexcept { last_request_ns_ = now_ns; }

  bool has_map() const noexcept { return map_.has_value(); }
  const OccupancyGrid& map() const noexcept { return *map_; }
  bool in_sync() const noexcept { return in_sync_; }
  std::uint64_t last_sequence() const noexcept { return last_sequence_; }
  std::uint64_t next_expected() const noexcept { return last_sequence_ + 1; }
  std::uint64_t gaps() const noexcept { return gaps_; }
  std::uint64_t heals() const noexcept { return heals_; }

 private:
  std::uint32_t max_map_cells_;
  std::optional<OccupancyGrid> map_;
  MapGeometry geometry_;
  std::uint64_t last_sequence_ = 0;
  bool in_sync_ = false;
  bool had_gap_ = false;             // since the last completed snapshot
  std::uint64_t assembling_id_ = 0;  // snapshot being received without a gap; 0: none
  std::uint32_t next_part_ = 0;
  std::optional<std::int64_t> last_request_ns_;
  std::uint64_t gaps_ = 0;
  std::uint64_t heals_ = 0;
};

}  // namespace grip::link
