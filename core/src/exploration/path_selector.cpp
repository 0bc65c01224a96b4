#include "grip/exploration/path_selector.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

#include "../world/validation.hpp"

namespace grip {

Status PathSelectionConfig::validate() const {
  const auto bad = [](const char* name, double value, const char* rule) -> Status {
    return invalid_argument(std::string("path selection: ") + name + " must be " + rule + " (got " +
                            detail::format_number(value) + ")");
  };
  if (!(std::isfinite(sensing_radius_m) && sensing_radius_m > 0.0)) {
    return bad("sensing_radius_m", sensing_radius_m, "finite and > 0");
  }
  if (!(std::isfinite(length_weight_per_m) && length_weight_per_m >= 0.0)) {
    return bad("length_weight_per_m", length_weight_per_m, "finite and >= 0");
  }
  if (!(std::isfinite(reference_speed_m_s) && reference_speed_m_s >= 0.0)) {
    return bad("reference_speed_m_s", reference_speed_m_s, "finite and >= 0");
  }
  if (!(std::isfinite(course_change_m) && course_change_m >= 0.0)) {
    return bad("course_change_m", course_change_m, "finite and >= 0");
  }
  if (!(std::isfinite(sample_step_s) && sample_step_s > 0.0)) {
    return bad("sample_step_s", sample_step_s, "finite and > 0");
  }
  return Ok{};
}

Result<PathSelector> PathSelector::create(int width_cells, int height_cells, double resolution_m,
                                          std::uint32_t max_edges,
                                          const PathSelectionConfig& config) {
  if (auto error =
          detail::check_grid_size("PathSelector", width_cells, height_cells, resolution_m)) {
    return *std::move(error);
  }
  if (auto s = config.validate(); !s) return s.error();
  if (max_edges == 0) return invalid_argument("PathSelector: max_edges must be > 0 (got 0)");
  return PathSelector(width_cells, height_cells, resolution_m, max_edges, config);
}

PathSelector::PathSelector(int width_cells, int height_cells, double resolution_m,
                           std::uint32_t max_edges, const PathSelectionConfig& config)
    : width_(width_cells),
      height_(height_cells),
      resolution_(resolution_m),
      max_edges_(max_edges),
      config_(config),
      d_(static_cast<std::size_t>(max_edges) * kMaxTargetCells),
      length_(max_edges),
      stack_(max_edges),
      course_(max_edges) {
  for (std::size_t i = 0; i < d_.capacity(); ++i) GRIP_ASSERT(d_.push_back(0.0F));
  for (std::size_t e = 0; e < length_.capacity(); ++e) GRIP_ASSERT(length_.push_back(0.0));
  for (std::size_t e = 0; e < course_.capacity(); ++e) GRIP_ASSERT(course_.push_back(kOffCourse));
}

Result<TargetSight> PathSelector::create_sight() const {
  return TargetSight::create(width_, height_, resolution_, config_.sensing_radius_m);
}

template <VehicleModel V>
PathChoice PathSelector::select(const Planner<V>& planner, const TargetSight& sight,
                                std::uint32_t min_step, TreeState course) noexcept {
  const auto& tree = planner.tree();
  GRIP_ASSERT(tree.edge_capacity() <= max_edges_);
  GRIP_ASSERT(planner.rho_field().width() == width_ && planner.rho_field().height() == height_);
  GRIP_ASSERT(sight.width() == width_ && sight.height() == height_ &&
              sight.sensing_radius_m() == config_.sensing_radius_m);
  const auto targets = static_cast<std::uint32_t>(sight.target_cells().size());
  const auto d_max = static_cast<float>(config_.sensing_radius_m);
  const double lambda = config_.length_weight_per_m;
  const auto stride = std::max<int>(
      1, static_cast<int>(std::lround(config_.sample_step_s / planner.config().record_step_s())));

  const TreeState root = planner.root_state();
  const auto& root_state = tree.edge_state(root.edge, root.index);
  const double root_rho = planner.rho_m(root_state);

  // Both candidates are tracked in one pass; which one counts is known only at its end.
  PathChoice by_sight;
  PathChoice by_rho;
  bool seen_any = false;

  // The course: the edges from the root to the last plan's end are marked for this call (and
  // unmarked at its end); the pass marks the edges below the plan's end. A state keeps the
  // course when its edge is marked either way.
  course = config_.course_change_m > 0.0 ? resolve(tree, course) : TreeState{};
  if (course.edge == tree.root()) course = TreeState{};
  const auto mark_course = [&](std::uint8_t mark) {
    for (EdgeHandle e = course.edge; e != kNoHandle; e = tree.edge(e).parent) course_[e] = mark;
  };
  mark_course(kOnCourse);
  const double leave_growth = std::exp(lambda * config_.course_change_m);
  // l(tr) as the distance covered at the reference speed in tr's duration, when there is one.
  const bool by_duration = config_.reference_speed_m_s > 0.0;
  const double duration_cost_m_per_step =
      config_.reference_speed_m_s * planner.config().integration_step_s;

  // Folds the state at (x, y) into the vector d and its sum. Most states see nothing (one mask
  // read); a seen target costs a squared distance, and a square root only when it improves.
  const auto fold = [&](float* d, double& d_sum, std::uint32_t& unseen, double x, double y) {
    std::uint32_t mask = sight.seen_at(x, y);
    seen_any = seen_any || mask != 0;
    for (; mask != 0; mask &= mask - 1) {
      const auto i = static_cast<std::uint32_t>(std::countr_zero(mask));
      const double dx = x - sight.target_x_m(i);
      const double dy = y - sight.target_y_m(i);
      const double old = static_cast<double>(d[i]);
      if (dx * dx + dy * dy >= old * old) continue;
      const auto distance = static_cast<float>(std::sqrt(dx * dx + dy * dy));
      if (!(d[i] < d_max)) --unseen;  // first seen on this trajectory
      d_sum += static_cast<double>(distance) - old;
      d[i] = distance;
    }
  };
  // Without sight of the target: rho at the end, length weighed at most as at d_max (the file
  // comment).
  const auto by_rho_weight_of = [&](double rho, double growth) {
    return rho + std::min(rho, static_cast<double>(d_max)) * (growth - 1.0);
  };
  // One exponential per state serves both candidates: w = d exp(lambda l).
  const auto offer = [&](EdgeHandle e, std::uint16_t k, const auto& q, double d_sum,
                         std::uint32_t unseen, double l_m, bool kept) {
    if (tree.step_of(e, k) < min_step) return;
    const double growth = std::exp(lambda * l_m) * (kept ? 1.0 : leave_growth);
    // rho_A* bounds rho from below: a state that loses to both candidates even with it needs
    // no more than that lookup.
    const double rho_bound = planner.rho_a_star_m(q);
    if ((d_sum + static_cast<double>(unseen) * rho_bound) * growth >= by_sight.weight &&
        !(rho_bound < root_rho && by_rho_weight_of(rho_bound, growth) < by_rho.weight)) {
      return;
    }
    const double rho_end = planner.rho_m(q);
    // A cell tr does not see lies d_max beyond the sensing disk of wherever tr ends: d_max plus
    // rho_A* from its end to F. With d_max alone, a trajectory seeing a few cells would lose to
    // standing still (its length costs more than the few cells gain) and the robot stalls
    // where the frontier is barely in sight; rho makes every step toward it count.
    const double d_all = d_sum + static_cast<double>(unseen) * rho_end;
    const double by_sight_weight = d_all * growth;
    if (by_sight_weight < by_sight.weight) {
      by_sight = PathChoice{TreeState{e, k}, d_all, l_m, by_sight_weight, true};
    }
    const double by_rho_weight = by_rho_weight_of(rho_end, growth);
    // Without sight of the target, only a trajectory that ends closer to F than the root is a
    // candidate (see the file comment of path_selector.hpp: no creeping at a dead end).
    if (rho_end < root_rho && by_rho_weight < by_rho.weight) {
      by_rho = PathChoice{TreeState{e, k}, rho_end, l_m, by_rho_weight, false};
    }
  };

  stack_.clear();
  GRIP_ASSERT(stack_.push_back(tree.root()));
  while (!stack_.empty()) {
    const EdgeHandle e = stack_.back();
    stack_.pop_back();
    for (EdgeHandle c = tree.edge(e).first_child; c != kNoHandle; c = tree.edge(c).next_sibling) {
      GRIP_ASSERT(stack_.push_back(c));  // every edge once: at most the edge pool
    }
    const Edge& edge = tree.edge(e);
    if (course_[e] != kOnCourse) {
      course_[e] = course.edge != kNoHandle && edge.parent != kNoHandle &&
                           (edge.parent == course.edge || course_[edge.parent] == kBelowCourse)
                       ? kBelowCourse
                       : kOffCourse;
    }
    const bool kept = course.edge == kNoHandle || course_[e] != kOffCourse;
    float* d = d_.data() + static_cast<std::size_t>(e) * kMaxTargetCells;
    double length = 0.0;
    if (edge.parent == kNoHandle) {
      std::fill(d, d + targets, d_max);
    } else {
      const float* from = d_.data() + static_cast<std::size_t>(edge.parent) * kMaxTargetCells;
      std::copy(from, from + targets, d);
      length = length_[edge.parent];
    }
    double d_sum = 0.0;
    std::uint32_t unseen = 0;
    for (std::uint32_t i = 0; i < targets; ++i) {
      d_sum += static_cast<double>(d[i]);
      unseen += d[i] < d_max ? 0U : 1U;
    }
    // The root edge holds one state; any other edge's first state is its parent's last.
    const auto& first = tree.edge_state(e, edge.first);
    double px = state_x(first);
    double py = state_y(first);
    int k = edge.parent == kNoHandle ? edge.last : std::min<int>(edge.first + stride, edge.last);
    for (;;) {
      const auto& q = tree.edge_state(e, static_cast<std::uint16_t>(k));
      const double x = state_x(q);
      const double y = state_y(q);
      length += std::sqrt((x - px) * (x - px) + (y - py) * (y - py));
      px = x;
      py = y;
      fold(d, d_sum, unseen, x, y);
      const double l_m =
          by_duration ? duration_cost_m_per_step * tree.step_of(e, static_cast<std::uint16_t>(k))
                      : length;
      offer(e, static_cast<std::uint16_t>(k), q, d_sum, unseen, l_m, kept);
      if (k == edge.last) break;
      k = std::min<int>(k + stride, edge.last);
    }
    length_[e] = length;
  }
  mark_course(kOffCourse);
  PathChoice chosen = seen_any ? by_sight : by_rho;
  chosen.root_rho_m = root_rho;
  return chosen;
}

template PathChoice PathSelector::select(const Planner<DdVelocity>&, const TargetSight&,
                                         std::uint32_t, TreeState) noexcept;
template PathChoice PathSelector::select(const Planner<DdAcceleration>&, const TargetSight&,
                                         std::uint32_t, TreeState) noexcept;
template PathChoice PathSelector::select(const Planner<Car>&, const TargetSight&, std::uint32_t,
                                         TreeState) noexcept;

}  // namespace grip
