#include "planning_side.hpp"

#include <algorithm>
#include <cstddef>
#include <span>
#include <utility>

#include "grip/link/map_sync.hpp"
#include "grip/platform/clock.hpp"

namespace grip::rt::dds {

template <VehicleModel V>
Status PlanningSide<V>::create_map(const link::MapGeometry& geometry) {
  auto grid = OccupancyGrid::create(static_cast<int>(geometry.width_cells),
                                    static_cast<int>(geometry.height_cells), geometry.resolution_m,
                                    geometry.origin_x_m, geometry.origin_y_m, Cell::kUnknown);
  if (!grid) return grid.error();
  SessionConfig session;
  session.cycle_s = config_.cycle_s;
  session.budget_s = config_.budget_s;
  session.margin_s = config_.margin_s;
  session.max_edges = config_.max_edges;
  session.lockstep_edges = config_.lockstep_edges;
  session.seed = config_.seed;
  session.no_safety = config_.no_safety;
  session.max_plan_steps = grip_msg_kMaxPlanSteps;
  session.target_refresh_cycles = config_.target_refresh_cycles;
  session.tuning = config_.tuning;
  auto created = ReplanningSession<V>::create(vehicle_, std::move(grid).value(), session);
  if (!created) return created.error();
  session_.emplace(std::move(created).value());
  running_checksum_ = link::map_checksum(session_->grid());  // once; then by the cells written
  return Ok{};
}

template <VehicleModel V>
void PlanningSide<V>::apply_tiles(MapChanges& changes) noexcept {
  bool applied = false;  // by this call (changes.applied may come from an earlier one)
  bool batch_complete = false;
  OccupancyGrid& grid = session_->grid();
  while (handoffs_.tiles->try_pop(*tile_)) {
    const MapTile& t = *tile_;
    if (t.vehicle_incarnation != vehicle_incarnation_) continue;  // an earlier vehicle's map
    const auto area = static_cast<std::size_t>(t.box.x1 - t.box.x0 + 1) *
                      static_cast<std::size_t>(t.box.y1 - t.box.y0 + 1);
    running_checksum_ ^= link::cells_checksum(grid, t.box);  // out with the old cells
    changes.apply(grid, t.box, std::span<const Cell>(t.cells.data(), area));
    running_checksum_ ^= link::cells_checksum(grid, t.box);  // in with the new
    map_sequence_ = t.map_sequence;
    map_in_sync_ = t.in_sync;
    batch_complete = t.last_of_batch;
    applied = true;
  }
  // The checksum describes a whole hand-over, not a map half way through one.
  if (applied && batch_complete) map_checksum_ = running_checksum_;
}

template <VehicleModel V>
Status PlanningSide<V>::prepare(const VehicleSample& state, bool explore) {
  ReplanningSession<V>& session = *session_;
  if (Status s = session.create_cycle(state.time_scale, state.lockstep, explore); !s) return s;
  ExplorationDriverConfig exploration;
  exploration.target.frontier = config_.frontier;
  exploration.target.give_up_after_s = config_.frontier_give_up_s;
  exploration.target.give_up_reached_after_s = config_.frontier_give_up_reached_s;
  exploration.target.rho_margin_m = config_.frontier_rho_margin_m;
  exploration.refresh_cycles = config_.target_refresh_cycles;
  exploration.path_weight = config_.path_weight;
  auto driver = ExplorationDriver<V>::create(session.vehicle(), session.grid(), exploration,
                                             session.sizing().planner);
  if (!driver) return driver.error();
  driver_.emplace(std::move(driver).value());
  driver_ready_.store(true, std::memory_order_release);
  return Ok{};
}

template <VehicleModel V>
Status PlanningSide<V>::start(const VehicleSample& state, const std::optional<Goal>& goal) {
  ReplanningSession<V>& session = *session_;
  exploring_ = !goal;
  // Exploring, the first target is where the vehicle stands; the first cycle picks a frontier.
  const Goal first = goal ? *goal : Goal::disk(state.state[0], state.state[1], 0.5);
  heading_x_m_ = first.x_m();
  heading_y_m_ = first.y_m();
  return session.start(state, first);
}

template <VehicleModel V>
void PlanningSide<V>::choose_first_target() noexcept {
  if (!exploring_) return;
  ReplanningSession<V>& session = *session_;
  driver_->choose_now(session.cycle(), session.grid(), session.plan_start_ns());
  if (driver_->has_target()) {
    heading_x_m_ = driver_->target_x_m();
    heading_y_m_ = driver_->target_y_m();
  }
}

template <VehicleModel V>
CycleOutcome PlanningSide<V>::cycle_body(std::int64_t release_ns,
                                         std::int64_t deadline_ns) noexcept {
  const std::int64_t start = platform::now_ns();
  ReplanningSession<V>& session = *session_;
  session.note_release(release_ns);
  MapChanges changes;
  apply_tiles(changes);
  const bool new_state = handoffs_.states->update() &&
                         handoffs_.states->read_buffer().incarnation == vehicle_incarnation_;
  if (new_state) session.note_state(handoffs_.states->read_buffer());
  session.chain_plan_start(release_ns, clock_);
  if (new_state) session.check_vehicle_follows();
  return plan_cycle(start, changes, deadline_ns);
}

template <VehicleModel V>
CycleOutcome PlanningSide<V>::lockstep_cycle(const VehicleSample& state, const MapChanges& changes,
                                             std::int64_t start_ns) noexcept {
  ReplanningSession<V>& session = *session_;
  session.note_state(state);
  session.set_plan_start_after(state);
  session.check_vehicle_follows();
  return plan_cycle(start_ns, changes, 0);
}

// Both modes: the cycle's inputs, growth (until the deadline, or by edge count in lockstep),
// and the hand-over of its plan and status to the publish thread.
template <VehicleModel V>
CycleOutcome PlanningSide<V>::plan_cycle(std::int64_t start_ns, const MapChanges& changes,
                                         std::int64_t deadline_ns) noexcept {
  ReplanningSession<V>& session = *session_;
  session.note_map_changes(changes);
  if (handoffs_.goals->update()) {
    const Goal& goal = handoffs_.goals->read_buffer();
    session.cycle().set_goal(goal);  // a goal ends exploration
    exploring_ = false;
    heading_x_m_ = goal.x_m();
    heading_y_m_ = goal.y_m();
  }
  if (exploring_) {
    if (driver_->update(session.cycle(), session.grid(), session.plan_start_ns(), changes,
                        session.lockstep())) {
      target_wanted_.signal();
    }
    if (driver_->has_target()) {
      heading_x_m_ = driver_->target_x_m();
      heading_y_m_ = driver_->target_y_m();
    }
  }
  const auto now = [] { return platform::now_ns(); };
  const auto choose = [this, &session](const Planner<V>& planner) {
    return exploring_ ? driver_->choose_plan_end(planner, session.cycle().cycle_steps(),
                                                 session.cycle().committed())
                      : planner.best_state();
  };
  const auto announce_plan = [this] {
    handoffs_.plan_coming.store(true, std::memory_order_release);
    publish_wakeup_.signal();
  };
  const std::int64_t prepared = platform::now_ns();
  CycleOutcome out = session.run(now, deadline_ns, choose, announce_plan);
  out.prepare_ns = prepared - start_ns;
  const auto& start = session.cycle().plan_start();
  out.start_x_m = state_x(start);
  out.start_y_m = state_y(start);
  out.start_theta = state_theta(start);
  if (exploring_) out.exploration = driver_->record();
  hand_over_plan(out);
  hand_over_status(out, start_ns);
  publish_wakeup_.signal();
  return out;
}

template <VehicleModel V>
void PlanningSide<V>::hand_over_plan(const CycleOutcome& outcome) noexcept {
  const SentPlan<V> sent = session_->send_plan(outcome);
  PlanSlot& slot = handoffs_.plans->write_buffer();
  slot.cycle = sent.cycle;
  slot.start_time_ns = sent.start_ns;
  link::state_to_wire<V>(sent.from, slot.start_state.data(), slot.state_dim);
  slot.state_sequence = sent.state_sequence;
  slot.steps = static_cast<std::uint32_t>(sent.steps.size());
  for (std::uint32_t i = 0; i < slot.steps; ++i) {
    slot.step[i].control[0] = sent.steps[i].control[0];
    slot.step[i].control[1] = sent.steps[i].control[1];
    slot.step[i].duration_s = sent.steps[i].duration_s;
  }
  slot.committed_monotonic_ns = static_cast<std::uint64_t>(platform::now_ns());
  slot.vehicle_incarnation = vehicle_incarnation_;
  handoffs_.plans->publish();
}

template <VehicleModel V>
void PlanningSide<V>::hand_over_status(const CycleOutcome& outcome,
                                       std::int64_t start_ns) noexcept {
  const ReplanningSession<V>& session = *session_;
  CycleStatus& status = handoffs_.statuses->write_buffer();
  status.cycle = session.cycles();
  status.exploring = exploring_;
  status.exploration_complete = driver_->explored();
  status.frontier_groups = driver_->groups();
  status.frontier_groups_given_up = driver_->groups_given_up();
  status.frontier_groups_unreachable = driver_->groups_unreachable();
  status.target_x_m = heading_x_m_;
  status.target_y_m = heading_y_m_;
  status.misses = session.misses();
  status.tree_edges = outcome.tree_edges;
  status.edges_added = outcome.edges_added;
  status.cycle_time_s = static_cast<double>(platform::now_ns() - start_ns) * 1e-9;
  status.map_sequence = map_sequence_;
  status.map_checksum = map_checksum_;
  status.map_in_sync = map_in_sync_;
  status.vehicle_incarnation = vehicle_incarnation_;
  handoffs_.statuses->publish();
}

template <VehicleModel V>
void PlanningSide<V>::fill_report(PlannerParticipantReport& report) const {
  if (!session_) return;
  report.plans_committed = session_->plans_committed();
  report.map_sequence = map_sequence_;
  report.explored = driver_ && driver_->explored();
  report.resyncs = session_->resyncs();
  report.map_checksum = link::map_checksum(session_->grid());
}

template <VehicleModel V>
PlannerTreePicture PlanningSide<V>::tree_picture() const {
  PlannerTreePicture picture;
  if (!session_ || !session_->has_cycle()) return picture;
  const Planner<V>& planner = session_->planner();
  const auto& tree = planner.tree();
  planner.visit_edges([&](EdgeHandle, const Edge& edge) {
    auto& line = picture.edges.emplace_back();
    for (int k = edge.first; k <= edge.last; ++k) {
      const auto& q = tree.state(edge.trajectory, static_cast<std::uint32_t>(k));
      line.push_back({state_x(q), state_y(q)});
    }
  });
  planner.visit_path(session_->cycle().committed(), [&](const typename V::State& q) {
    picture.plan.push_back({state_x(q), state_y(q)});
  });
  return picture;
}

template class PlanningSide<DdVelocity>;
template class PlanningSide<DdAcceleration>;
template class PlanningSide<Car>;

}  // namespace grip::rt::dds
