// `grip echo TOPIC`: the samples of one of the contract's topics as JSON lines, one per sample,
// what `ros2 topic echo` is to ROS users. TOPIC is the unprefixed name; with --topic-prefix P
// it listens to P_TOPIC, the name each line carries. It only listens: its reader asks for no
// deadline and accepts any liveliness lease, so it matches every writer of the topic and disturbs
// none.

#include <chrono>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.hpp"
#include "dds_config.hpp"
#include "grip/link/topics.hpp"
#include "grip/platform/dds/reader.hpp"
#include "grip/platform/dds/waitset.hpp"
#include "message_json.hpp"
#include "stop_signal.hpp"

namespace grip::tools {

namespace {

namespace pdds = platform::dds;
using std::chrono::steady_clock;

struct EchoOptions {
  std::string topic;
  std::uint32_t domain = 0;
  std::string dds_config;
  std::string topic_prefix;
  std::string security_dir;
  std::uint64_t count = 0;  // 0: until Ctrl-C or the timeout
  double timeout_s = 0.0;   // 0: no timeout
};

// The topic's own QoS (history, durability), without a deadline and with a lease no writer
// exceeds, so that the request is compatible with whatever a writer offers.
pdds::Qos listening(pdds::Qos qos) {
  qos.deadline.reset();
  qos.liveliness_lease = std::chrono::hours(24);
  return qos;
}

template <typename T>
int echo(const EchoOptions& o, const pdds::Participant& participant,
         const dds_topic_descriptor_t* descriptor, const char* topic, const pdds::Qos& qos) {
  auto reader = pdds::Reader<T>::create(participant, descriptor, topic, listening(qos));
  auto waitset = pdds::WaitSet::create(participant);
  if (!reader || !waitset || !waitset->attach_data_available(reader->get())) {
    std::cerr << "grip echo: cannot subscribe to " << topic << "\n";
    return 1;
  }
  auto buffer = std::make_unique<pdds::SampleBuffer<T, 16>>(descriptor);
  const steady_clock::time_point end =
      steady_clock::now() + std::chrono::duration_cast<steady_clock::duration>(
                                std::chrono::duration<double>(o.timeout_s));
  std::uint64_t printed = 0;
  while (!stop_flag().load() && (o.count == 0 || printed < o.count)) {
    if (o.timeout_s > 0.0 && steady_clock::now() >= end) {
      std::cerr << "grip echo: " << printed << " samples of " << topic << " in " << o.timeout_s
                << " s\n";
      return 3;
    }
    // Short waits, so that Ctrl-C (a flag) ends the loop promptly.
    if (!waitset->wait(std::chrono::milliseconds(100))) return 1;
    const Result<std::size_t> taken = reader->take(*buffer);
    if (!taken) {
      std::cerr << "grip echo: " << taken.error().message << "\n";
      return 1;
    }
    for (std::size_t i = 0; i < *taken && (o.count == 0 || printed < o.count); ++i, ++printed) {
      const nlohmann::json line = {{"topic", topic},
                                   {"source_timestamp_ns", buffer->info(i).source_timestamp},
                                   {"sample", to_json((*buffer)[i])}};
      std::cout << line.dump() << std::endl;  // a line at a time, for pipes
    }
  }
  return 0;
}

int run_echo(const EchoOptions& o) {
  auto topics = link::TopicNames::create(o.topic_prefix);
  if (!topics) {
    std::cerr << "grip echo: " << topics.error().message << "\n";
    return 2;
  }
  auto participant = join_domain(o.domain, o.dds_config, o.security_dir);
  if (!participant) {
    std::cerr << "grip echo: " << participant.error().message << "\n";
    return participant.error().code == ErrorCode::kInvalidArgument ? 2 : 1;
  }
  stop_on_signals();
  const link::LinkTiming timing;
  const std::string& t = o.topic;
  const std::string name = topics->of(t);
  if (t == link::kVehicleStateTopic) {
    return echo<grip_msg_VehicleState>(o, *participant, &grip_msg_VehicleState_desc, name.c_str(),
                                       link::vehicle_state_qos(timing, link::Endpoint::kReader));
  }
  if (t == link::kPlanTopic) {
    return echo<grip_msg_Plan>(o, *participant, &grip_msg_Plan_desc, name.c_str(),
                               link::plan_qos(timing, link::Endpoint::kReader));
  }
  if (t == link::kMapUpdateTopic) {
    return echo<grip_msg_MapUpdate>(o, *participant, &grip_msg_MapUpdate_desc, name.c_str(),
                                    link::map_update_qos(timing));
  }
  if (t == link::kMapRequestTopic) {
    return echo<grip_msg_MapRequest>(o, *participant, &grip_msg_MapRequest_desc, name.c_str(),
                                     link::map_request_qos(timing));
  }
  if (t == link::kGoalTopic) {
    return echo<grip_msg_Goal>(o, *participant, &grip_msg_Goal_desc, name.c_str(),
                               link::goal_qos(timing));
  }
  if (t == link::kVehicleDescriptionTopic) {
    return echo<grip_msg_VehicleDescription>(o, *participant, &grip_msg_VehicleDescription_desc,
                                             name.c_str(), link::vehicle_description_qos(timing));
  }
  return echo<grip_msg_PlannerStatus>(o, *participant, &grip_msg_PlannerStatus_desc, name.c_str(),
                                      link::planner_status_qos(timing));
}

}  // namespace

void register_echo_command(CLI::App& app) {
  auto o = std::make_shared<EchoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "echo", "Print the samples of a grip topic as JSON lines (Ctrl-C ends it)");
  cmd->add_option("topic", o->topic, "The topic")
      ->required()
      ->check(CLI::IsMember({link::kVehicleStateTopic, link::kPlanTopic, link::kMapUpdateTopic,
                             link::kMapRequestTopic, link::kGoalTopic, link::kPlannerStatusTopic,
                             link::kVehicleDescriptionTopic}));
  add_link_options(*cmd, o->domain, o->dds_config);
  add_topic_prefix_option(*cmd, o->topic_prefix, "none");
  add_security_option(*cmd, o->security_dir, "none: unauthenticated");
  cmd->add_option("--count", o->count, "Exit after this many samples (0: no limit)")
      ->capture_default_str();
  cmd->add_option("--timeout", o->timeout_s,
                  "Exit with status 3 when --count samples have not come in this many seconds "
                  "(0: wait)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->callback([o]() {
    const int rc = run_echo(*o);
    if (rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace grip::tools
