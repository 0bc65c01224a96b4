#include "receive_side.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iterator>
#include <string>
#include <utility>

#include "grip/platform/clock.hpp"

namespace grip::rt::dds {

namespace {

namespace pdds = platform::dds;

// The DDS time of a sample's source timestamp against now, for freshness checks: volatile
// topics by default; a durable topic's samples may be as old as their writer.
link::Verdict check_sample_freshness(const dds_sample_info_t& info,
                                     const link::FreshnessLimits& limits = {}) {
  return link::check_freshness(info.source_timestamp, dds_time(), limits);
}

}  // namespace

template <VehicleModel V>
ReceiveSide<V>::ReceiveSide(const V& vehicle, const VehicleParams& params, ReceiveEntities entities,
                            Handoffs& handoffs, platform::Wakeup& lockstep_inputs,
                            std::uint32_t max_map_cells, std::int64_t takeover_ns,
                            std::uint64_t planner_incarnation,
                            std::function<void(const std::string&)> warn)
    : vehicle_(vehicle),
      dds_(entities),
      handoffs_(handoffs),
      lockstep_inputs_(lockstep_inputs),
      warn_(std::move(warn)),
      max_map_cells_(max_map_cells),
      receiver_(max_map_cells),
      vehicle_incarnation_(takeover_ns, takeover_ns),
      planner_incarnation_(planner_incarnation),
      description_(params) {}

template <VehicleModel V>
link::Verdict ReceiveSide<V>::follow(std::uint64_t incarnation, std::int64_t now_ns) {
  const std::uint64_t before = vehicle_incarnation_.followed();
  switch (vehicle_incarnation_.observe(incarnation, now_ns)) {
    case link::Peer::kNone:
      return link::Verdict{link::Rejection::kNoIncarnation, "incarnation"};
    case link::Peer::kOther:
      return link::Verdict{link::Rejection::kOtherIncarnation, "incarnation"};
    case link::Peer::kSame:
      return {};
    case link::Peer::kNew:
      break;
  }
  if (before != 0) {
    // A restarted vehicle side: nothing the old one said holds for the new one.
    last_state_stamp_ = 0;
    last_state_sequence_ = 0;
    last_state_local_ns_ = 0;
    lockstep_seen_ = false;
    clock_.reset();
    forget_map();
    counters_.vehicle_restarts.fetch_add(1, std::memory_order_relaxed);
    warn("a new vehicle incarnation (" + std::to_string(incarnation) + ") replaced " +
         std::to_string(before) + ": planning for it anew");
  }
  counters_.vehicle_incarnation.store(incarnation, std::memory_order_release);
  return {};
}

template <VehicleModel V>
void ReceiveSide<V>::forget_map() {
  receiver_ = link::MapReceiver(max_map_cells_);
  geometry_ready_.store(false, std::memory_order_release);
  dirty_.clear();
  tiles_x_ = 0;
  tiles_y_ = 0;
}

template <VehicleModel V>
void ReceiveSide<V>::refuse_geometry(const link::MapGeometry& geometry) {
  {
    const std::lock_guard<std::mutex> lock(geometry_mutex_);
    refused_geometry_ = geometry;
  }
  counters_.rejected_map_update.fetch_add(1, std::memory_order_relaxed);
  forget_map_.store(true, std::memory_order_release);
}

template <VehicleModel V>
void ReceiveSide<V>::run(const std::atomic<bool>& stop_threads, const std::atomic<bool>& stopping) {
  // Sample storage reused for every take: after the first few, takes no longer allocate.
  auto state_buffer =
      std::make_unique<pdds::SampleBuffer<grip_msg_VehicleState, 8>>(&grip_msg_VehicleState_desc);
  auto map_buffer =
      std::make_unique<pdds::SampleBuffer<grip_msg_MapUpdate, 8>>(&grip_msg_MapUpdate_desc);
  auto goal_buffer = std::make_unique<pdds::SampleBuffer<grip_msg_Goal, 4>>(&grip_msg_Goal_desc);
  auto description_buffer = std::make_unique<pdds::SampleBuffer<grip_msg_VehicleDescription, 2>>(
      &grip_msg_VehicleDescription_desc);
  while (!stop_threads.load(std::memory_order_acquire)) {
    // The timeout paces the periodic work: snapshot requests, tiles the ring had no room for,
    // liveliness.
    static_cast<void>(dds_.waitset.wait(std::chrono::milliseconds(20)));
    if (forget_map_.exchange(false, std::memory_order_acq_rel)) forget_map();
    if (hand_over_again_.exchange(false, std::memory_order_acq_rel) && receiver_.has_map()) {
      const OccupancyGrid& map = receiver_.map();
      mark_dirty(CellBox{0, 0, map.width() - 1, map.height() - 1});
    }
    take_states(*state_buffer);
    take_maps(*map_buffer);
    take_goals(*goal_buffer);
    take_descriptions(*description_buffer);
    const std::int64_t now = platform::now_ns();
    if (receiver_.should_request(now, 500'000'000)) {
      grip_msg_MapRequest request{};
      request.from_sequence = receiver_.next_expected();
      request.stamp_ns = static_cast<std::uint64_t>(clock_.vehicle_ns(now, 1.0));
      if (dds_.requests.write(request).ok()) receiver_.note_requested(now);
    }
    hand_over_tiles();
    check_liveliness(stopping.load(std::memory_order_acquire));
    if (lockstep_seen_) lockstep_inputs_.signal();
  }
}

template <VehicleModel V>
void ReceiveSide<V>::take_states(pdds::SampleBuffer<grip_msg_VehicleState, 8>& buffer) {
  for (;;) {
    const Result<std::size_t> taken = dds_.states.take(buffer);
    if (!taken.ok() || *taken == 0) return;
    for (std::size_t i = 0; i < *taken; ++i) {
      const grip_msg_VehicleState& msg = buffer[i];
      // A lockstep simulator repeats the state it waits on (for a planner that joins late):
      // a repeat is neither new nor an error. Planned for again only by a standby (the vehicle
      // follows another planner): its earlier answer was refused, and once the followed one
      // has gone silent, an answer to the repeat is what the vehicle fails over to. The
      // followed planner's answer did not arrive: it is written again (Handoffs::plan_wanted_for).
      if (msg.stamp_ns == last_state_stamp_ && msg.sequence_number == last_state_sequence_) {
        const bool standby =
            msg.plan_incarnation != 0 && msg.plan_incarnation != planner_incarnation_;
        if (standby) {
          hand_over_state(msg);
        } else {
          handoffs_.plan_wanted_for.store(msg.sequence_number, std::memory_order_release);
        }
        continue;
      }
      const std::int64_t now = platform::now_ns();
      link::Verdict verdict = check_sample_freshness(buffer.info(i));
      if (verdict.ok()) verdict = follow(msg.incarnation, now);
      if (verdict.ok()) verdict = link::check_vehicle_state(msg, vehicle_, last_state_stamp_);
      if (verdict.ok() &&
          !link::stamp_lead_allowed(msg.stamp_ns, last_state_stamp_, now - last_state_local_ns_)) {
        verdict = link::Verdict{link::Rejection::kStampInFuture, "stamp_ns"};
      }
      if (!verdict.ok()) {
        counters_.rejected_vehicle_state.fetch_add(1, std::memory_order_relaxed);
        rejected("vehicle state", verdict, now);
        continue;
      }
      last_state_stamp_ = msg.stamp_ns;
      last_state_sequence_ = msg.sequence_number;
      last_state_local_ns_ = now;
      lockstep_seen_ = msg.lockstep;
      clock_.observe(msg.stamp_ns, now, msg.time_scale);
      hand_over_state(msg);
    }
  }
}

template <VehicleModel V>
void ReceiveSide<V>::hand_over_state(const grip_msg_VehicleState& msg) {
  VehicleSample& sample = handoffs_.states->write_buffer();
  std::copy(std::begin(msg.state), std::end(msg.state), sample.state.begin());
  sample.stamp_ns = msg.stamp_ns;
  sample.sequence_number = msg.sequence_number;
  sample.plan_cycle = msg.plan_cycle;
  sample.map_sequence = msg.map_sequence;
  sample.time_scale = msg.time_scale;
  sample.lockstep = msg.lockstep;
  sample.incarnation = msg.incarnation;
  // How early this planner's plans arrive; a report about another planner's says nothing.
  const bool ours = msg.plan_incarnation == planner_incarnation_;
  sample.plan_arrival_cycle = ours ? msg.plan_arrival_cycle : 0;
  sample.plan_arrival_margin_ns = ours ? msg.plan_arrival_margin_ns : 0;
  handoffs_.states->publish();
}

template <VehicleModel V>
void ReceiveSide<V>::take_maps(pdds::SampleBuffer<grip_msg_MapUpdate, 8>& buffer) {
  for (;;) {
    const Result<std::size_t> taken = dds_.maps.take(buffer);
    if (!taken.ok() || *taken == 0) return;
    for (std::size_t i = 0; i < *taken; ++i) {
      const std::int64_t now = platform::now_ns();
      link::Verdict fresh = check_sample_freshness(buffer.info(i));
      if (fresh.ok()) fresh = follow(buffer[i].incarnation, now);
      if (fresh.ok() && refused(link::geometry_of(buffer[i]))) {
        fresh = link::Verdict{link::Rejection::kBadGeometry, "map geometry (the planner's)"};
      }
      const bool had_map = receiver_.has_map();
      const link::MapApplied applied = fresh.ok()
                                           ? receiver_.apply(buffer[i])
                                           : link::MapApplied{fresh, false, false, false, {}};
      if (!applied.verdict.ok()) {
        counters_.rejected_map_update.fetch_add(1, std::memory_order_relaxed);
        if (applied.verdict.reason == link::Rejection::kMapTooLarge) too_large(buffer[i]);
        rejected("map update", applied.verdict, now);
        continue;
      }
      if (!had_map) {
        {
          const std::lock_guard<std::mutex> lock(geometry_mutex_);
          geometry_ = link::geometry_of(receiver_.map());
        }
        tiles_x_ = (receiver_.map().width() + kTileSide - 1) / kTileSide;
        tiles_y_ = (receiver_.map().height() + kTileSide - 1) / kTileSide;
        dirty_.assign(static_cast<std::size_t>(tiles_x_ * tiles_y_), CellBox{});
        geometry_ready_.store(true, std::memory_order_release);
        if (pending_goal_) accept_goal(*pending_goal_);
        pending_goal_.reset();
      }
      if (applied.gap) {
        counters_.map_gaps.fetch_add(1, std::memory_order_relaxed);
        warn("map update gap before sequence " + std::to_string(buffer[i].sequence_number) +
             "; requesting a snapshot");
      }
      if (applied.healed) counters_.map_heals.fetch_add(1, std::memory_order_relaxed);
      mark_dirty(applied.changed);
    }
  }
}

template <VehicleModel V>
void ReceiveSide<V>::take_goals(pdds::SampleBuffer<grip_msg_Goal, 4>& buffer) {
  for (;;) {
    const Result<std::size_t> taken = dds_.goals.take(buffer);
    if (!taken.ok() || *taken == 0) return;
    for (std::size_t i = 0; i < *taken; ++i) {
      // Durable: a goal set long before this planner started is still the goal.
      const link::Verdict fresh =
          check_sample_freshness(buffer.info(i), link::FreshnessLimits::durable());
      if (!fresh.ok()) {
        counters_.rejected_goal.fetch_add(1, std::memory_order_relaxed);
        rejected("goal", fresh, platform::now_ns());
      } else if (!receiver_.has_map()) {
        pending_goal_ = buffer[i];
      } else {
        accept_goal(buffer[i]);
      }
    }
  }
}

// No freshness check: a durable description is as old as the vehicle side, and still true.
template <VehicleModel V>
void ReceiveSide<V>::take_descriptions(pdds::SampleBuffer<grip_msg_VehicleDescription, 2>& buffer) {
  const auto warn_line = [this](const std::string& line) { warn(line); };
  for (;;) {
    const Result<std::size_t> taken = dds_.descriptions.take(buffer);
    if (!taken.ok() || *taken == 0) return;
    for (std::size_t i = 0; i < *taken; ++i) description_.observe(buffer[i], warn_line);
  }
}

template <VehicleModel V>
void ReceiveSide<V>::accept_goal(const grip_msg_Goal& goal) {
  const link::Verdict verdict = link::check_goal(goal, receiver_.map());
  if (!verdict.ok()) {
    counters_.rejected_goal.fetch_add(1, std::memory_order_relaxed);
    rejected("goal", verdict, platform::now_ns());
    return;
  }
  handoffs_.goals->write(link::goal_from_wire(goal));
}

template <VehicleModel V>
void ReceiveSide<V>::mark_dirty(const CellBox& box) {
  for (int ty = box.y0 / kTileSide; ty <= box.y1 / kTileSide; ++ty) {
    for (int tx = box.x0 / kTileSide; tx <= box.x1 / kTileSide; ++tx) {
      const CellBox tile{tx * kTileSide, ty * kTileSide, tx * kTileSide + kTileSide - 1,
                         ty * kTileSide + kTileSide - 1};
      const CellBox part{std::max(box.x0, tile.x0), std::max(box.y0, tile.y0),
                         std::min(box.x1, tile.x1), std::min(box.y1, tile.y1)};
      dirty_[static_cast<std::size_t>(ty * tiles_x_ + tx)].add(part);
    }
  }
}

template <VehicleModel V>
void ReceiveSide<V>::hand_over_tiles() {
  // Tiles carry the receiver's map as it is now, so a tile cut later is never older; a tile
  // the ring has no room for stays dirty and goes next time.
  if (!receiver_.has_map()) return;
  const OccupancyGrid& map = receiver_.map();
  std::size_t pending = 0;
  for (const CellBox& box : dirty_) pending += box.empty() ? 0U : 1U;
  MapTile* tile = handover_tile_.get();
  for (CellBox& box : dirty_) {
    if (box.empty()) continue;
    tile->box = box;
    tile->map_sequence = receiver_.last_sequence();
    tile->in_sync = receiver_.in_sync();
    tile->vehicle_incarnation = vehicle_incarnation_.followed();
    tile->last_of_batch = --pending == 0;
    const int w = box.x1 - box.x0 + 1;
    for (int y = box.y0; y <= box.y1; ++y) {
      for (int x = box.x0; x <= box.x1; ++x) {
        tile->cells[static_cast<std::size_t>((y - box.y0) * w + (x - box.x0))] = map.at(x, y);
      }
    }
    if (!handoffs_.tiles->try_push(*tile)) return;
    box = CellBox{};
  }
}

template <VehicleModel V>
void ReceiveSide<V>::check_liveliness(bool stopping) {
  const auto live = dds_.states.liveliness_changed();
  if (!live.ok()) return;
  const bool alive = live->alive_count > 0;
  // Once planning has been told to stop, the vehicle leaving is the end of the run, not a loss.
  if (was_alive_ && !alive && !stopping) {
    counters_.vehicle_losses.fetch_add(1, std::memory_order_relaxed);
    warn("vehicle controller lost (liveliness); planning goes on with the last map and state");
  }
  was_alive_ = alive;
  counters_.vehicle_alive.store(alive, std::memory_order_relaxed);
}

template <VehicleModel V>
void ReceiveSide<V>::rejected(const char* topic, const link::Verdict& verdict,
                              std::int64_t now_ns) {
  if (now_ns - last_log_ns_ < 1'000'000'000 && last_log_ns_ != 0) {
    ++log_suppressed_;
    return;
  }
  std::string line = std::string("rejected ") + topic + ": " +
                     std::string(link::rejection_name(verdict.reason)) + " (" + verdict.field + ")";
  if (log_suppressed_ > 0) {
    line += "; " + std::to_string(log_suppressed_) + " more rejected in the last second";
  }
  warn(line);
  log_suppressed_ = 0;
  last_log_ns_ = now_ns;
}

// Once per map: what to change, which the rate-limited rejection line cannot say.
template <VehicleModel V>
void ReceiveSide<V>::too_large(const grip_msg_MapUpdate& msg) {
  const link::MapGeometry geometry = link::geometry_of(msg);
  if (too_large_reported_ == geometry) return;
  too_large_reported_ = geometry;
  const std::uint64_t cells =
      static_cast<std::uint64_t>(msg.map_width_cells) * msg.map_height_cells;
  std::string line = "the vehicle's map is ";
  line.append(std::to_string(msg.map_width_cells))
      .append(" x ")
      .append(std::to_string(msg.map_height_cells))
      .append(" cells (")
      .append(std::to_string(cells))
      .append("), more than this planner is sized for (planner.max_map_cells ")
      .append(std::to_string(max_map_cells_))
      .append("): raise planner.max_map_cells in the parameter file");
  warn(line);
}

template <VehicleModel V>
void ReceiveSide<V>::warn(const std::string& line) const {
  if (warn_) {
    warn_(line);
  } else {
    std::fprintf(stderr, "grip planner: %s\n", line.c_str());
  }
}

template class ReceiveSide<DdVelocity>;
template class ReceiveSide<DdAcceleration>;
template class ReceiveSide<Car>;

}  // namespace grip::rt::dds
