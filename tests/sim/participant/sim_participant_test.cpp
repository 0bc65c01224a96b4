// The simulator is the vehicle of its configuration (SimRunConfig::vehicle): it describes itself
// with those parameters, refuses plans beyond that vehicle's limits (a plan within the paper
// car's is refused by a slower car) and collides with that vehicle's chassis (a wider one
// touches a shelf the paper's passes). A planner is played by hand over DDS, on loopback. The
// verdict is the figures': a planner that says it is done short of the coverage is `done-early`,
// a vehicle that never moved says so.

#include "grip/sim/sim_participant.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <optional>
#include <thread>

#include "grip/link/messages.hpp"
#include "grip/link/topics.hpp"
#include "grip/link/vehicle_description.hpp"
#include "grip/platform/dds/participant.hpp"
#include "grip/platform/dds/reader.hpp"
#include "grip/platform/dds/writer.hpp"
#include "private_topics.hpp"

namespace grip::sim {
namespace {

namespace pdds = platform::dds;
using namespace std::chrono_literals;

// A planner that answers every vehicle state of a lockstep simulator with one plan holding
// `control` for a cycle from that state, and the status that goes with it. It keeps the
// vehicle's description. From cycle `done_from` on (0: never) its status says exploration is
// complete.
class HandPlanner {
 public:
  HandPlanner(pdds::DomainId domain, VehicleKind kind, std::array<double, 2> control,
              std::uint64_t done_from = 0)
      : kind_(kind),
        control_(control),
        done_from_(done_from),
        participant_(pdds::Participant::create(domain).value()) {
    const link::TopicNames topics =
        link::TopicNames::create(::grip::testing::private_topic_prefix()).value();
    const link::LinkTiming timing;
    states_.emplace(pdds::Reader<grip_msg_VehicleState>::create(
                        participant_, &grip_msg_VehicleState_desc, topics.vehicle_state,
                        link::vehicle_state_qos(timing, link::Endpoint::kReader))
                        .value());
    descriptions_.emplace(pdds::Reader<grip_msg_VehicleDescription>::create(
                              participant_, &grip_msg_VehicleDescription_desc,
                              topics.vehicle_description, link::vehicle_description_qos(timing))
                              .value());
    plans_.emplace(
        pdds::Writer<grip_msg_Plan>::create(participant_, &grip_msg_Plan_desc, topics.plan,
                                            link::plan_qos(timing, link::Endpoint::kWriter))
            .value());
    status_.emplace(pdds::Writer<grip_msg_PlannerStatus>::create(
                        participant_, &grip_msg_PlannerStatus_desc, topics.planner_status,
                        link::planner_status_qos(timing))
                        .value());
  }

  // Answers states until `done`.
  void run(const std::atomic<bool>& done) {
    auto states =
        std::make_unique<pdds::SampleBuffer<grip_msg_VehicleState, 8>>(&grip_msg_VehicleState_desc);
    auto descriptions = std::make_unique<pdds::SampleBuffer<grip_msg_VehicleDescription, 2>>(
        &grip_msg_VehicleDescription_desc);
    std::uint64_t answered = 0;
    while (!done.load()) {
      std::this_thread::sleep_for(2ms);
      if (auto n = descriptions_->take(*descriptions); n.ok() && *n > 0) {
        description_ = (*descriptions)[*n - 1];
      }
      auto n = states_->take(*states);
      if (!n.ok() || *n == 0) continue;
      const grip_msg_VehicleState& state = (*states)[*n - 1];
      if (state.sequence_number <= answered) continue;  // a lockstep repeat
      answered = state.sequence_number;
      answer(state);
    }
  }

  const std::optional<grip_msg_VehicleDescription>& description() const { return description_; }

 private:
  void answer(const grip_msg_VehicleState& state) {
    ++cycle_;
    grip_msg_PlanStep step{{control_[0], control_[1]}, 0.05};
    grip_msg_Plan plan{};
    plan.cycle = cycle_;
    plan.start_time_ns = state.stamp_ns;  // lockstep: the plan for the state it waits on
    std::copy(std::begin(state.state), std::end(state.state), std::begin(plan.start_state));
    plan.state_dim = state.state_dim;
    plan.state_sequence = state.sequence_number;
    plan.kind = link::to_wire(kind_);
    plan.steps._buffer = &step;
    plan.steps._length = 1;
    plan.steps._maximum = 1;
    plan.contingency = link::contingency_of(kind_);
    plan.incarnation = kIncarnation;
    plan.vehicle_incarnation = state.incarnation;
    ASSERT_TRUE(plans_->write(plan).ok());
    grip_msg_PlannerStatus status{};
    status.cycle = cycle_;
    status.incarnation = kIncarnation;
    status.vehicle_incarnation = state.incarnation;
    status.exploration_complete = done_from_ != 0 && cycle_ >= done_from_;
    ASSERT_TRUE(status_->write(status).ok());
  }

  static constexpr std::uint64_t kIncarnation = 42;
  VehicleKind kind_;
  std::array<double, 2> control_;
  std::uint64_t done_from_;
  pdds::Participant participant_;
  std::optional<pdds::Reader<grip_msg_VehicleState>> states_;
  std::optional<pdds::Reader<grip_msg_VehicleDescription>> descriptions_;
  std::optional<pdds::Writer<grip_msg_Plan>> plans_;
  std::optional<pdds::Writer<grip_msg_PlannerStatus>> status_;
  std::optional<grip_msg_VehicleDescription> description_;
  std::uint64_t cycle_ = 0;
};

// A free 10 m x 10 m room walled at its border, with a shelf (obstacle cells from x 3 m to 4 m,
// y 5.3 m to 5.4 m) beside the line y = 5 m the vehicle drives along from (2, 5).
OccupancyGrid room_with_shelf() {
  OccupancyGrid grid = OccupancyGrid::create(100, 100, 0.1, 0.0, 0.0, Cell::kFree).value();
  for (int i = 0; i < 100; ++i) {
    grid.set(i, 0, Cell::kObstacle);
    grid.set(i, 99, Cell::kObstacle);
    grid.set(0, i, Cell::kObstacle);
    grid.set(99, i, Cell::kObstacle);
  }
  for (int x = 30; x < 40; ++x) grid.set(x, 53, Cell::kObstacle);
  return grid;
}

// A lockstep run of `sim_time_s` with the hand planner sending `control` for every cycle.
SimRunReport run_with_hand_planner(pdds::DomainId domain, const VehicleParams& vehicle,
                                   std::array<double, 2> control, double sim_time_s,
                                   std::optional<grip_msg_VehicleDescription>* described,
                                   std::uint64_t done_from = 0) {
  SimRunConfig config;
  config.domain = domain;
  config.topic_prefix = ::grip::testing::private_topic_prefix();
  config.vehicle = vehicle;
  config.world = "room with a shelf";
  config.start_x_m = 2.0;
  config.start_y_m = 5.0;
  config.lockstep = true;
  config.max_sim_time_s = sim_time_s;
  config.planner_wait = 20s;
  const OccupancyGrid truth = room_with_shelf();
  HandPlanner planner(domain, vehicle_kind(vehicle), control, done_from);
  std::atomic<bool> done{false};
  std::thread planning([&] { planner.run(done); });
  const std::atomic<bool> stop{false};
  Result<SimRunReport> report = run_simulation(config, truth, stop);
  done.store(true);
  planning.join();
  EXPECT_TRUE(report.ok()) << report.error().message;
  if (described != nullptr) *described = planner.description();
  return report.ok() ? *report : SimRunReport{};
}

TEST(SimParticipant, APlanWithinThePaperCarsLimitsIsRefusedByASlowerCar) {
  constexpr pdds::DomainId kDomain = 95;
  const std::array<double, 2> half_g_forward{0.5, 0.0};  // [m/s^2], [rad/s]; the paper: 0.6
  CarParams slow;
  slow.max_accel_m_s2 = 0.3;
  slow.braking_decel_m_s2 = 0.3;

  // GIVEN the paper's car, THEN every plan is executed.
  const SimRunReport paper =
      run_with_hand_planner(kDomain, CarParams{}, half_g_forward, 1.0, nullptr);
  EXPECT_EQ(paper.result, "timeout") << paper.reason;
  EXPECT_GE(paper.plans_received, 19U);
  EXPECT_EQ(paper.plans_rejected, 0U);
  EXPECT_GT(paper.distance_m, 0.1);

  // GIVEN the slower car, THEN every plan is refused, the car stays where it was (and the
  // verdict says so), and it told the planner what it is.
  std::optional<grip_msg_VehicleDescription> described;
  const SimRunReport slower = run_with_hand_planner(kDomain, slow, half_g_forward, 1.0, &described);
  EXPECT_EQ(slower.result, "never-moved") << slower.reason;
  EXPECT_NE(slower.reason.find("timeout"), std::string::npos) << slower.reason;
  EXPECT_EQ(slower.plans_received, 0U);
  EXPECT_GE(slower.plans_rejected, 19U);
  EXPECT_EQ(slower.distance_m, 0.0);
  ASSERT_TRUE(described.has_value()) << "the simulator did not describe itself";
  EXPECT_TRUE(link::check_vehicle_description(slow, *described).ok());
  EXPECT_FALSE(link::check_vehicle_description(CarParams{}, *described).ok());
}

TEST(SimParticipant, AWiderChassisTouchesAShelfThePapersPasses) {
  constexpr pdds::DomainId kDomain = 96;
  const std::array<double, 2> straight_on{1.0, 1.0};  // both wheels at 1 m/s
  DdVelocityParams wide;
  wide.footprint.half_width_m = 0.4;

  const SimRunReport paper =
      run_with_hand_planner(kDomain, DdVelocityParams{}, straight_on, 2.0, nullptr);
  EXPECT_GT(paper.distance_m, 1.9) << "the vehicle did not drive past the shelf";
  EXPECT_EQ(paper.collisions, 0U);

  const SimRunReport wider = run_with_hand_planner(kDomain, wide, straight_on, 2.0, nullptr);
  EXPECT_GT(wider.distance_m, 1.9);
  EXPECT_EQ(wider.collisions, 1U);
  ASSERT_FALSE(wider.collision_events.empty());
  // It touched where the chassis, 0.25 m ahead of the axle, reached the shelf's start at 3 m.
  EXPECT_NEAR(wider.collision_events.front().x_m, 2.75, 0.05 + 1e-9);
}

// A planner that says it is done after two seconds of driving: the room is far from sensed.
TEST(SimParticipant, APlannerDoneShortOfTheCoverageMakesTheRunDoneEarlyNotComplete) {
  constexpr pdds::DomainId kDomain = 190;
  const SimRunReport r =
      run_with_hand_planner(kDomain, DdVelocityParams{}, {0.5, 0.5}, 60.0, nullptr, 40);
  EXPECT_EQ(r.result, "done-early") << r.reason;
  EXPECT_LT(r.coverage, kCompleteCoverage);
  EXPECT_GT(r.distance_m, kNeverMovedM);
  EXPECT_NE(r.reason.find("coverage"), std::string::npos) << r.reason;
}

// A planner that says it is done while the vehicle stands still: never moved, not complete.
TEST(SimParticipant, AVehicleThatNeverMovedSaysSo) {
  constexpr pdds::DomainId kDomain = 191;
  const SimRunReport r =
      run_with_hand_planner(kDomain, DdVelocityParams{}, {0.0, 0.0}, 60.0, nullptr, 5);
  EXPECT_EQ(r.result, "never-moved") << r.reason;
  EXPECT_EQ(r.distance_m, 0.0);
  EXPECT_NE(r.reason.find("done-early"), std::string::npos) << r.reason;
}

TEST(SimParticipant, WithoutAPlannerTheRunEndsAtTheFirstPlansWaitAndSaysSo) {
  constexpr pdds::DomainId kDomain = 192;
  const OccupancyGrid truth = room_with_shelf();
  for (const bool lockstep : {true, false}) {
    SCOPED_TRACE(lockstep ? "lockstep" : "real time");
    // GIVEN no planner on the domain, and a first plan's wait of 1 s (each later plan's: 30 s)
    SimRunConfig config;
    config.domain = kDomain;
    config.topic_prefix = ::grip::testing::private_topic_prefix();
    config.world = "room with a shelf";
    config.start_x_m = 2.0;
    config.start_y_m = 5.0;
    config.lockstep = lockstep;
    config.first_plan_wait = 1s;
    const std::atomic<bool> stop{false};
    // WHEN the vehicle waits THEN the run ends as an error naming the first plan's wait
    const Result<SimRunReport> report = run_simulation(config, truth, stop);
    ASSERT_TRUE(report.ok()) << report.error().message;
    EXPECT_EQ(report->result, "error");
    EXPECT_EQ(report->reason, "no plan from a planner within 1 s");
    EXPECT_EQ(report->distance_m, 0.0);
  }
}

}  // namespace
}  // namespace grip::sim
