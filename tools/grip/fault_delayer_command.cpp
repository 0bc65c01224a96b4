// `grip fault-delayer` (hidden; `grip bench faults` starts it inside a network namespace): holds
// every packet netfilter queues to it (an iptables NFQUEUE rule) for delay +- jitter (uniform),
// then lets it through. The stand-in for netem's delay on a kernel without netem. Runs until
// SIGTERM; a packet's delay is drawn when it arrives, so packets can overtake each other, as with
// netem's jitter.

#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "fault_profile.hpp"
#include "stop_signal.hpp"

#ifdef GRIP_HAVE_NFQUEUE
#include <arpa/inet.h>
#include <linux/netfilter.h>
#include <poll.h>
#include <sys/socket.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <queue>
#include <random>
#include <utility>
#include <vector>

extern "C" {
#include <libnetfilter_queue/libnetfilter_queue.h>
}
#endif

namespace grip::tools {

namespace {

struct DelayerOptions {
  unsigned queue = kFaultQueue;
  double delay_ms = 50.0;
  double jitter_ms = 10.0;
  std::uint64_t seed = 1;
};

#ifdef GRIP_HAVE_NFQUEUE

std::int64_t now_ns() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return std::int64_t{t.tv_sec} * 1'000'000'000 + t.tv_nsec;
}

// The packets held: (when to let it through [ns], its queue id), the earliest first.
using Held = std::pair<std::int64_t, std::uint32_t>;

struct Delayer {
  std::priority_queue<Held, std::vector<Held>, std::greater<>> held;
  std::mt19937_64 random;
  std::uniform_real_distribution<double> delay_ms;
};

int on_packet(nfq_q_handle*, nfgenmsg*, nfq_data* packet, void* data) {
  auto* d = static_cast<Delayer*>(data);
  const nfqnl_msg_packet_hdr* header = nfq_get_msg_packet_hdr(packet);
  if (header == nullptr) return 0;
  const auto hold_ns = static_cast<std::int64_t>(d->delay_ms(d->random) * 1e6);
  d->held.push({now_ns() + hold_ns, ntohl(header->packet_id)});
  return 0;
}

int run_delayer(const DelayerOptions& o) {
  stop_on_signals();
  nfq_handle* handle = nfq_open();
  if (handle == nullptr) {
    std::cerr << "grip fault-delayer: cannot open the netfilter queue interface (root?)\n";
    return 1;
  }
  const std::unique_ptr<nfq_handle, int (*)(nfq_handle*)> closer(handle, nfq_close);
  Delayer d{
      {},
      std::mt19937_64(o.seed),
      std::uniform_real_distribution<double>(o.delay_ms - o.jitter_ms, o.delay_ms + o.jitter_ms)};
  nfq_q_handle* queue =
      nfq_create_queue(handle, static_cast<std::uint16_t>(o.queue), on_packet, &d);
  if (queue == nullptr) {
    std::cerr << "grip fault-delayer: cannot bind netfilter queue " << o.queue << "\n";
    return 1;
  }
  const std::unique_ptr<nfq_q_handle, int (*)(nfq_q_handle*)> destroyer(queue, nfq_destroy_queue);
  if (nfq_set_mode(queue, NFQNL_COPY_META, 0) < 0 || nfq_set_queue_maxlen(queue, 16384) < 0) {
    std::cerr << "grip fault-delayer: cannot configure netfilter queue " << o.queue << "\n";
    return 1;
  }
  const int fd = nfq_fd(handle);
  const int buffer_bytes = 8 << 20;
  setsockopt(fd, SOL_SOCKET, SO_RCVBUFFORCE, &buffer_bytes, sizeof buffer_bytes);
  std::vector<char> buffer(1 << 16);
  while (!stop_flag().load()) {
    int timeout_ms = 100;
    if (!d.held.empty()) {
      const std::int64_t wait_ns = d.held.top().first - now_ns();
      timeout_ms =
          wait_ns <= 0 ? 0 : static_cast<int>(std::min<std::int64_t>(100, wait_ns / 1'000'000 + 1));
    }
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, timeout_ms) > 0) {
      for (;;) {
        const ssize_t n = recv(fd, buffer.data(), buffer.size(), MSG_DONTWAIT);
        if (n < 0 && errno == ENOBUFS) continue;  // the kernel dropped some: as a full link does
        if (n <= 0) break;
        nfq_handle_packet(handle, buffer.data(), static_cast<int>(n));
      }
    }
    for (const std::int64_t now = now_ns(); !d.held.empty() && d.held.top().first <= now;) {
      nfq_set_verdict(queue, d.held.top().second, NF_ACCEPT, 0, nullptr);
      d.held.pop();
    }
  }
  return 0;
}

#else

int run_delayer(const DelayerOptions&) {
  std::cerr << "grip fault-delayer: this grip was built without libnetfilter_queue "
               "(libnetfilter-queue-dev)\n";
  return 1;
}

#endif

}  // namespace

void register_fault_delayer_command(CLI::App& app) {
  auto o = std::make_shared<DelayerOptions>();
  CLI::App* cmd = app.add_subcommand(
      "fault-delayer", "Hold the packets of a netfilter queue (for `grip bench faults`)");
  cmd->group("");  // hidden: a part of `grip bench faults`, not a command of its own
  cmd->add_option("--queue", o->queue, "Netfilter queue number")->capture_default_str();
  cmd->add_option("--delay-ms", o->delay_ms, "Mean delay [ms]")
      ->check(CLI::Range(0.0, 10'000.0))
      ->capture_default_str();
  cmd->add_option("--jitter-ms", o->jitter_ms, "Uniform spread around it [ms]")
      ->check(CLI::Range(0.0, 10'000.0))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed of the delays")->capture_default_str();
  cmd->callback([o]() {
    if (o->jitter_ms > o->delay_ms) throw CLI::ValidationError("--jitter-ms", "exceeds --delay-ms");
    if (const int rc = run_delayer(*o); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace grip::tools
