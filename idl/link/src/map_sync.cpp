#include "grip/link/map_sync.hpp"

#include <algorithm>
#include <bit>
#include <utility>

namespace grip::link {

namespace {

constexpr std::uint64_t kFnvOffset = 14695981039346656037ULL;
constexpr std::uint64_t kFnvPrime = 1099511628211ULL;

std::uint64_t fnv_bytes(std::uint64_t h, const void* data, std::size_t n) noexcept {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) h = (h ^ bytes[i]) * kFnvPrime;
  return h;
}

// A cell's share of the checksum: its index and value mixed (SplitMix64's finaliser), so that
// the XOR over cells tells maps apart and follows a write cell by cell.
std::uint64_t cell_term(std::uint32_t index, Cell value) noexcept {
  std::uint64_t z = (static_cast<std::uint64_t>(index) << 2 | static_cast<std::uint64_t>(value)) +
                    0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// Calls f(patch) for each piece of `box` (inclusive, non-empty) of at most 256 x 256 cells,
// bottom row of pieces first.
template <typename F>
void for_each_patch(const CellBox& box, F&& f) {
  for (int y = box.y0; y <= box.y1; y += kPatchSideCells) {
    for (int x = box.x0; x <= box.x1; x += kPatchSideCells) {
      f(CellBox{x, y, std::min(box.x1, x + kPatchSideCells - 1),
                std::min(box.y1, y + kPatchSideCells - 1)});
    }
  }
}

std::uint32_t patch_count(const CellBox& box) noexcept {
  const auto pieces = [](int lo, int hi) {
    return static_cast<std::uint32_t>((hi - lo + kPatchSideCells) / kPatchSideCells);
  };
  return pieces(box.x0, box.x1) * pieces(box.y0, box.y1);
}

}  // namespace

std::uint64_t map_checksum(const OccupancyGrid& grid) noexcept {
  const MapGeometry g = geometry_of(grid);
  std::uint64_t h = kFnvOffset;
  h = fnv_bytes(h, &g.width_cells, sizeof g.width_cells);
  h = fnv_bytes(h, &g.height_cells, sizeof g.height_cells);
  for (const double v : {g.resolution_m, g.origin_x_m, g.origin_y_m}) {
    const auto bits = std::bit_cast<std::uint64_t>(v);
    h = fnv_bytes(h, &bits, sizeof bits);
  }
  return h ^ cells_checksum(grid, CellBox{0, 0, grid.width() - 1, grid.height() - 1});
}

std::uint64_t cells_checksum(const OccupancyGrid& grid, const CellBox& box) noexcept {
  std::uint64_t h = 0;
  const auto cells = grid.cells();
  for (int y = box.y0; y <= box.y1; ++y) {
    for (int x = box.x0; x <= box.x1; ++x) {
      const std::uint32_t i = grid.index(x, y);
      h ^= cell_term(i, cells[i]);
    }
  }
  return h;
}

MapSender::MapSender(OccupancyGrid map)
    : map_(std::move(map)), cells_(static_cast<std::size_t>(grip_msg_kMaxPatchCells)) {}

void MapSender::send_updates(const CellBox& box, std::uint64_t stamp_ns, Send send) {
  const CellBox clipped{std::max(box.x0, 0), std::max(box.y0, 0),
                        std::min(box.x1, map_.width() - 1), std::min(box.y1, map_.height() - 1)};
  if (clipped.empty()) return;
  for_each_patch(clipped, [&](const CellBox& patch) { emit(patch, stamp_ns, 0, 0, 0, send); });
}

void MapSender::send_snapshot(std::uint64_t stamp_ns, Send send) {
  const CellBox whole{0, 0, map_.width() - 1, map_.height() - 1};
  const std::uint32_t parts = patch_count(whole);
  const std::uint64_t id = ++snapshot_id_;
  std::uint32_t part = 0;
  for_each_patch(whole,
                 [&](const CellBox& patch) { emit(patch, stamp_ns, id, part++, parts, send); });
}

void MapSender::emit(const CellBox& patch, std::uint64_t stamp_ns, std::uint64_t snapshot_id,
                     std::uint32_t part, std::uint32_t parts, Send send) {
  grip_msg_MapUpdate msg{};
  msg.sequence_number = ++sequence_;
  msg.stamp_ns = stamp_ns;
  const MapGeometry g = geometry_of(map_);
  msg.map_width_cells = g.width_cells;
  msg.map_height_cells = g.height_cells;
  msg.resolution_m = g.resolution_m;
  msg.map_origin_x_m = g.origin_x_m;
  msg.map_origin_y_m = g.origin_y_m;
  msg.origin_x_cell = static_cast<std::uint32_t>(patch.x0);
  msg.origin_y_cell = static_cast<std::uint32_t>(patch.y0);
  msg.width_cells = static_cast<std::uint32_t>(patch.x1 - patch.x0 + 1);
  msg.height_cells = static_cast<std::uint32_t>(patch.y1 - patch.y0 + 1);
  msg.snapshot_id = snapshot_id;
  msg.snapshot_part = part;
  msg.snapshot_parts = parts;
  std::size_t n = 0;
  for (int y = patch.y0; y <= patch.y1; ++y) {
    for (int x = patch.x0; x <= patch.x1; ++x)
      cells_[n++] = static_cast<std::uint8_t>(map_.at(x, y));
  }
  msg.cells._buffer = cells_.data();  // borrowed: _release false, DDS copies on write
  msg.cells._length = static_cast<std::uint32_t>(n);
  msg.cells._maximum = static_cast<std::uint32_t>(cells_.size());
  msg.cells._release = false;
  send(msg);
}

MapApplied MapReceiver::apply(const grip_msg_MapUpdate& msg) {
  MapApplied out;
  out.verdict = check_map_update(msg, map_ ? &geometry_ : nullptr, max_map_cells_);
  if (!out.verdict.ok()) return out;
  if (!map_) {
    // Start-up: the first valid update says how large the map is.
    geometry_ = geometry_of(msg);
    auto created = OccupancyGrid::create(
        static_cast<int>(geometry_.width_cells), static_cast<int>(geometry_.height_cells),
        geometry_.resolution_m, geometry_.origin_x_m, geometry_.origin_y_m, Cell::kUnknown);
    if (!created) {  // check_map_update accepted what create() refuses: a contract mismatch
      out.verdict = Verdict{Rejection::kBadGeometry, "map geometry"};
      return out;
    }
    map_.emplace(std::move(created).value());
  } else if (msg.sequence_number != last_sequence_ + 1) {
    // Lost updates, or a restarted publisher numbering from 1 again: either way the map may
    // differ from the publisher's until a whole snapshot arrives.
    out.gap = true;
    ++gaps_;
    had_gap_ = true;
    in_sync_ = false;
    assembling_id_ = 0;
  }
  last_sequence_ = msg.sequence_number;

  const int x0 = static_cast<int>(msg.origin_x_cell);
  const int y0 = static_cast<int>(msg.origin_y_cell);
  const int w = static_cast<int>(msg.width_cells);
  const int h = static_cast<int>(msg.height_cells);
  auto cells = map_->mutable_cells();
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* row = msg.cells._buffer + static_cast<std::size_t>(y) * msg.width_cells;
    Cell* dst = cells.data() + map_->index(x0, y0 + y);
    for (int x = 0; x < w; ++x) dst[x] = static_cast<Cell>(row[x]);
  }
  out.changed = CellBox{x0, y0, x0 + w - 1, y0 + h - 1};

  if (msg.snapshot_id != 0) {
    if (msg.snapshot_part == 0) {
      assembling_id_ = msg.snapshot_id;
      next_part_ = 1;
    } else if (assembling_id_ == msg.snapshot_id && msg.snapshot_part == next_part_ && !out.gap) {
      ++next_part_;
    } else {
      assembling_id_ = 0;  // a part is missing: this snapshot cannot heal
    }
    if (assembling_id_ != 0 && next_part_ == msg.snapshot_parts) {
      assembling_id_ = 0;
      if (!in_sync_) {
        in_sync_ = true;
        out.synced = true;
        out.healed = had_gap_;
        heals_ += had_gap_ ? 1 : 0;
        had_gap_ = false;
      }
    }
  }
  return out;
}

bool MapReceiver::should_request(std::int64_t now_ns, std::int64_t retry_ns) const noexcept {
  if (in_sync_) return false;
  return !last_request_ns_ || now_ns - *last_request_ns_ >= retry_ns;
}

}  // namespace grip::link
