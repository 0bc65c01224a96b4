// `grip goal X Y`: sends a goal region to the planner on a domain, as a mission side would. The
// goal topic is durable (TRANSIENT_LOCAL) for as long as its writer lives, so the command waits
// until a planner has acknowledged the goal, and with --stay goes on offering it to planners
// that start later, until Ctrl-C.

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <thread>

#include "commands.hpp"
#include "dds_config.hpp"
#include "goal.h"
#include "grip/link/topics.hpp"
#include "grip/platform/clock.hpp"
#include "grip/platform/dds/reader.hpp"
#include "grip/platform/dds/waitset.hpp"
#include "grip/platform/dds/writer.hpp"
#include "stop_signal.hpp"

namespace grip::tools {

namespace {

namespace pdds = platform::dds;

struct GoalOptions {
  double x_m = 0.0;
  double y_m = 0.0;
  double radius_m = 0.5;
  std::uint32_t domain = 0;
  std::string dds_config;
  std::string topic_prefix;
  std::string security_dir;
  double lease_ms = 500.0;
  double wait_s = 10.0;
  bool stay = false;
};

// The goal that is still offered on the topic, if any writer offers one: the new goal's
// sequence number follows it. Discovery on a network takes a moment; a second is allowed.
std::uint64_t last_offered_sequence(const pdds::Participant& participant, const std::string& topic,
                                    const link::LinkTiming& timing) {
  auto reader = pdds::Reader<grip_msg_Goal>::create(participant, &grip_msg_Goal_desc, topic,
                                                    link::goal_qos(timing));
  auto waitset = pdds::WaitSet::create(participant);
  if (!reader || !waitset || !waitset->attach_data_available(reader->get())) return 0;
  if (!reader->wait_for_writers(1, std::chrono::seconds(1))) return 0;
  std::uint64_t last = 0;
  auto buffer = std::make_unique<pdds::SampleBuffer<grip_msg_Goal, 4>>(&grip_msg_Goal_desc);
  const Result<bool> woke = waitset->wait(std::chrono::seconds(1));
  if (!woke || !*woke) return 0;
  const Result<std::size_t> taken = reader->take(*buffer);
  for (std::size_t i = 0; taken && i < *taken; ++i) {
    last = std::max(last, (*buffer)[i].sequence_number);
  }
  return last;
}

int run_goal(const GoalOptions& o) {
  if (!std::isfinite(o.x_m) || !std::isfinite(o.y_m)) {
    std::cerr << "grip goal: X and Y must be finite numbers\n";
    return 2;
  }
  auto topics = link::TopicNames::create(o.topic_prefix);
  if (!topics) {
    std::cerr << "grip goal: " << topics.error().message << "\n";
    return 2;
  }
  auto participant = join_domain(o.domain, o.dds_config, o.security_dir);
  if (!participant) {
    std::cerr << "grip goal: " << participant.error().message << "\n";
    return participant.error().code == ErrorCode::kInvalidArgument ? 2 : 1;
  }
  link::LinkTiming timing;
  timing.liveliness_lease = std::chrono::microseconds(std::llround(o.lease_ms * 1000.0));

  grip_msg_Goal goal{};
  goal.sequence_number = last_offered_sequence(*participant, topics->goal, timing) + 1;
  goal.stamp_ns = static_cast<std::uint64_t>(platform::now_ns());
  goal.x_m = o.x_m;
  goal.y_m = o.y_m;
  goal.radius_m = o.radius_m;
  auto writer = pdds::Writer<grip_msg_Goal>::create(*participant, &grip_msg_Goal_desc, topics->goal,
                                                    link::goal_qos(timing));
  if (!writer) {
    std::cerr << "grip goal: " << writer.error().message << "\n";
    return 1;
  }
  const auto wait = std::chrono::milliseconds(std::llround(o.wait_s * 1000.0));
  if (!writer->wait_for_readers(1, wait)) {
    std::cerr << "grip goal: no planner on DDS domain " << o.domain << " within " << o.wait_s
              << " s\n";
    return 3;
  }
  if (Status s = writer->write(goal); !s) {
    std::cerr << "grip goal: " << s.error().message << "\n";
    return 1;
  }
  if (Status s = writer->wait_for_acks(wait); !s) {
    std::cerr << "grip goal: the planner did not acknowledge the goal within " << o.wait_s << " s ("
              << s.error().message << ")\n";
    return 3;
  }
  std::cout << "grip goal: goal " << goal.sequence_number << " at (" << o.x_m << ", " << o.y_m
            << ") radius " << o.radius_m << " m delivered on DDS domain " << o.domain << "\n";
  if (o.stay) {
    stop_on_signals();
    std::cout << "grip goal: offering it to planners that start later until Ctrl-C\n" << std::flush;
    while (!stop_flag().load()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return 0;
}

}  // namespace

void register_goal_command(CLI::App& app) {
  auto o = std::make_shared<GoalOptions>();
  CLI::App* cmd = app.add_subcommand(
      "goal", "Send a goal region to the planner; exits once a planner acknowledged it");
  cmd->add_option("x", o->x_m, "Goal x [m], in the map's frame")->required();
  cmd->add_option("y", o->y_m, "Goal y [m]")->required();
  cmd->add_option("--radius", o->radius_m, "Goal region radius [m]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  add_link_options(*cmd, o->domain, o->dds_config);
  add_topic_prefix_option(*cmd, o->topic_prefix, "none");
  add_security_option(*cmd, o->security_dir, "none: unauthenticated");
  cmd->add_option("--lease-ms", o->lease_ms,
                  "Liveliness lease [ms]: at most the planner's --lease-ms")
      ->check(CLI::Range(10.0, 3'600'000.0))
      ->capture_default_str();
  cmd->add_option("--wait", o->wait_s, "Seconds to wait for a planner to take the goal")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_flag("--stay", o->stay, "Keep offering the goal to planners that start later");
  cmd->callback([o]() {
    const int rc = run_goal(*o);
    if (rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace grip::tools
