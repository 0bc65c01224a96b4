// One end of the DDS Security tests (tests/platform/dds/security_test.cpp), in a process of its
// own: Cyclone 0.10 neither enforces access control between participants of one process nor
// gives them different identities, so every enforcement check needs two processes.
//
//   grip_dds_security_probe DOMAIN KEYS|- write|read TOPIC... SECONDS
// KEYS: a security folder (platform/dds/security.hpp), or "-" for an unauthenticated
// participant. write: writes a sample on each of the grip TOPICs (grip_plan,
// grip_vehicle_state, grip_map_update, grip_goal; prefixed names allowed) every 20 ms, as a
// hostile participant would (a plan of full speed ahead, a state stamped far in the future, a
// map update, a goal; an unauthenticated writer marks its samples); read: takes what arrives,
// not counting the marked samples (an unauthenticated reader hears an unauthenticated writer).
// Prints one line per topic, "TOPIC wrote N" or "TOPIC received N" (or "TOPIC refused: why" for a
// writer or reader it may not create), and exits 0; 3 when the participant cannot be created.

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "goal.h"
#include "grip/link/topics.hpp"
#include "grip/platform/dds/participant.hpp"
#include "grip/platform/dds/reader.hpp"
#include "grip/platform/dds/security.hpp"
#include "grip/platform/dds/writer.hpp"
#include "map_update.h"
#include "plan.h"
#include "vehicle_state.h"

namespace {

using namespace grip;
using namespace grip::platform::dds;
using namespace std::chrono_literals;

bool ends_with(const std::string& s, const char* tail) {
  const std::size_t n = std::strlen(tail);
  return s.size() >= n && s.compare(s.size() - n, n, tail) == 0;
}

// Set in the sequence numbers (a plan's cycle) of what an unauthenticated writer sends.
constexpr std::uint64_t kMarked = 1ULL << 60;
std::uint64_t g_mark = 0;  // kMarked in an unauthenticated writer

bool marked(const grip_msg_Plan& plan) { return (plan.cycle & kMarked) != 0; }
bool marked(const grip_msg_VehicleState& state) { return (state.sequence_number & kMarked) != 0; }
bool marked(const grip_msg_MapUpdate& update) { return (update.sequence_number & kMarked) != 0; }
bool marked(const grip_msg_Goal& goal) { return (goal.sequence_number & kMarked) != 0; }

// The samples a hostile participant sends, valid-looking on their own.
std::vector<grip_msg_PlanStep> g_steps(100, grip_msg_PlanStep{{1.0, 0.0}, 0.05});

void fill(grip_msg_Plan& plan, std::uint64_t n) {
  plan = grip_msg_Plan{};
  plan.cycle = n | g_mark;
  plan.kind = grip_msg_DD_VELOCITY;
  plan.contingency = grip_msg_BRAKE_STRAIGHT;
  plan.steps._buffer = g_steps.data();
  plan.steps._length = static_cast<std::uint32_t>(g_steps.size());
  plan.steps._maximum = plan.steps._length;
}
void fill(grip_msg_VehicleState& state, std::uint64_t n) {
  state = grip_msg_VehicleState{};
  state.stamp_ns = 1ULL << 62;  // far in the future
  state.sequence_number = n | g_mark;
  state.kind = grip_msg_DD_VELOCITY;
  state.state_dim = 3;
  state.time_scale = 1.0;
}
std::vector<std::uint8_t> g_cells(16, 0);
void fill(grip_msg_MapUpdate& update, std::uint64_t n) {
  update = grip_msg_MapUpdate{};
  update.sequence_number = n | g_mark;
  update.map_width_cells = 300;
  update.map_height_cells = 300;
  update.resolution_m = 0.1;
  update.width_cells = 4;
  update.height_cells = 4;
  update.cells._buffer = g_cells.data();
  update.cells._length = static_cast<std::uint32_t>(g_cells.size());
  update.cells._maximum = update.cells._length;
}
void fill(grip_msg_Goal& goal, std::uint64_t n) {
  goal = grip_msg_Goal{};
  goal.sequence_number = n | g_mark;
  goal.x_m = 1.0;
  goal.y_m = 1.0;
  goal.radius_m = 0.5;
}

// One topic's endpoint and its count.
class TopicEnd {
 public:
  virtual ~TopicEnd() = default;
  virtual void step(std::uint64_t n) = 0;
  std::uint64_t count = 0;
};

template <typename T>
class TopicWriter : public TopicEnd {
 public:
  explicit TopicWriter(Writer<T> writer) : writer_(std::move(writer)) {}
  void step(std::uint64_t n) override {
    T sample;
    fill(sample, n);
    if (writer_.write(sample).ok()) ++count;
  }

 private:
  Writer<T> writer_;
};

template <typename T>
class TopicReader : public TopicEnd {
 public:
  TopicReader(Reader<T> reader, const dds_topic_descriptor_t* descriptor)
      : reader_(std::move(reader)), buffer_(std::make_unique<SampleBuffer<T, 16>>(descriptor)) {}
  void step(std::uint64_t) override {
    const Result<std::size_t> taken = reader_.take(*buffer_);
    for (std::size_t i = 0; taken && i < *taken; ++i) {
      if (!marked((*buffer_)[i])) ++count;
    }
  }

 private:
  Reader<T> reader_;
  std::unique_ptr<SampleBuffer<T, 16>> buffer_;
};

template <typename T>
Result<std::unique_ptr<TopicEnd>> make(const Participant& participant, bool write,
                                       const dds_topic_descriptor_t* descriptor,
                                       const std::string& topic, const Qos& qos) {
  if (write) {
    auto writer = Writer<T>::create(participant, descriptor, topic, qos);
    if (!writer) return writer.error();
    return std::unique_ptr<TopicEnd>(std::make_unique<TopicWriter<T>>(std::move(writer).value()));
  }
  auto reader = Reader<T>::create(participant, descriptor, topic, qos);
  if (!reader) return reader.error();
  return std::unique_ptr<TopicEnd>(
      std::make_unique<TopicReader<T>>(std::move(reader).value(), descriptor));
}

Result<std::unique_ptr<TopicEnd>> make_endpoint(const Participant& participant, bool write,
                                                const std::string& topic) {
  const link::LinkTiming timing;
  const link::Endpoint side = write ? link::Endpoint::kWriter : link::Endpoint::kReader;
  if (ends_with(topic, link::kPlanTopic)) {
    return make<grip_msg_Plan>(participant, write, &grip_msg_Plan_desc, topic,
                               link::plan_qos(timing, side));
  }
  if (ends_with(topic, link::kVehicleStateTopic)) {
    return make<grip_msg_VehicleState>(participant, write, &grip_msg_VehicleState_desc, topic,
                                       link::vehicle_state_qos(timing, side));
  }
  if (ends_with(topic, link::kMapUpdateTopic)) {
    return make<grip_msg_MapUpdate>(participant, write, &grip_msg_MapUpdate_desc, topic,
                                    link::map_update_qos(timing));
  }
  if (ends_with(topic, link::kGoalTopic)) {
    return make<grip_msg_Goal>(participant, write, &grip_msg_Goal_desc, topic,
                               link::goal_qos(timing));
  }
  return invalid_argument("unknown topic " + topic);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(stderr, "usage: %s DOMAIN KEYS|- write|read TOPIC... SECONDS\n", argv[0]);
    return 2;
  }
  const auto domain = static_cast<DomainId>(std::atoi(argv[1]));
  const std::string keys = argv[2];
  const bool write = std::strcmp(argv[3], "write") == 0;
  const double seconds = std::atof(argv[argc - 1]);
  std::optional<SecurityFiles> security;
  if (keys != "-") security = SecurityFiles::from_directory(keys);
  if (!security) g_mark = kMarked;
  auto participant = Participant::create(domain, {}, security);
  if (!participant) {
    std::printf("participant refused: %s\n", participant.error().message.c_str());
    return 3;
  }
  std::vector<std::pair<std::string, std::unique_ptr<TopicEnd>>> endpoints;
  for (int i = 4; i < argc - 1; ++i) {
    auto endpoint = make_endpoint(*participant, write, argv[i]);
    if (!endpoint) {
      std::printf("%s refused: %s\n", argv[i], endpoint.error().message.c_str());
      continue;
    }
    endpoints.emplace_back(argv[i], std::move(endpoint).value());
  }
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  for (std::uint64_t n = 1; std::chrono::steady_clock::now() < until; ++n) {
    for (auto& [topic, endpoint] : endpoints) endpoint->step(n);
    std::this_thread::sleep_for(20ms);
  }
  for (const auto& [topic, endpoint] : endpoints) {
    std::printf("%s %s %llu\n", topic.c_str(), write ? "wrote" : "received",
                static_cast<unsigned long long>(endpoint->count));
  }
  return 0;
}
