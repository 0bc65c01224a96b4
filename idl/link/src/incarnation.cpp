#include "grip/link/incarnation.hpp"

#include <chrono>
#include <random>

namespace grip::link {

std::uint64_t new_incarnation() noexcept {
  // random_device alone may be deterministic on some platforms; the clock makes two starts
  // differ there too.
  std::random_device device;
  std::uint64_t value =
      (static_cast<std::uint64_t>(device()) << 32) ^ device() ^
      static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
  std::seed_seq seed{static_cast<std::uint32_t>(value), static_cast<std::uint32_t>(value >> 32)};
  std::mt19937_64 mix(seed);
  do {
    value = mix();
  } while (value == 0);
  return value;
}

bool stamp_lead_allowed(std::uint64_t stamp_ns, std::uint64_t last_stamp_ns,
                        std::int64_t wall_since_ns) noexcept {
  if (last_stamp_ns == 0 || stamp_ns <= last_stamp_ns) return true;
  const double lead = static_cast<double>(stamp_ns - last_stamp_ns);
  const double allowed = static_cast<double>(kMaxStampLeadNs) +
                         1000.0 * static_cast<double>(wall_since_ns > 0 ? wall_since_ns : 0);
  return lead <= allowed;
}

Peer IncarnationTracker::classify(std::uint64_t incarnation, std::int64_t now_ns,
                                  bool followed_alive) const noexcept {
  if (incarnation == 0) return Peer::kNone;
  if (followed_ == 0) return Peer::kNew;
  if (incarnation == followed_) return Peer::kSame;
  const std::int64_t silence = now_ns - last_heard_ns_;
  return silence >= (followed_alive ? hung_ns_ : takeover_ns_) ? Peer::kNew : Peer::kOther;
}

Peer IncarnationTracker::observe(std::uint64_t incarnation, std::int64_t now_ns,
                                 bool followed_alive) noexcept {
  const Peer peer = classify(incarnation, now_ns, followed_alive);
  switch (peer) {
    case Peer::kNew:
      switches_ += followed_ != 0 ? 1 : 0;
      followed_ = incarnation;
      last_heard_ns_ = now_ns;
      break;
    case Peer::kSame:
      last_heard_ns_ = now_ns;
      break;
    case Peer::kOther:
      ++others_;
      break;
    case Peer::kNone:
      break;
  }
  return peer;
}

}  // namespace grip::link
