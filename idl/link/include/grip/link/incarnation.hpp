#pragma once
// Incarnations (idl/README.md, "Incarnations"): each participant draws a random, non-zero
// number when it starts and stamps its messages with it, so that the other end tells a
// restarted peer (a new incarnation) and a second peer (another incarnation, while the one it
// follows still speaks) from the peer it follows. Pure: the caller passes the time.

#include <cstdint>

namespace grip::link {

// How far ahead of the last accepted state a vehicle state's stamp may be: kMaxStampLeadNs plus
// the wall-clock time since, at the largest time scale (1000). A stamp further ahead is
// rejected (kStampInFuture): accepted, it would make every later state "not increasing" and
// lock the vehicle out. last_stamp_ns 0: no state yet, any stamp sets the mark.
inline constexpr std::int64_t kMaxStampLeadNs = 10'000'000'000;
bool stamp_lead_allowed(std::uint64_t stamp_ns, std::uint64_t last_stamp_ns,
                        std::int64_t wall_since_ns) noexcept;

// A random, non-zero incarnation, different for every call in practice (64 random bits).
std::uint64_t new_incarnation() noexcept;

enum class Peer : std::uint8_t {
  kNone,  // incarnation 0: not a valid sender
  kSame,  // the incarnation followed
  kNew,   // the first one, or a new one replacing a peer silent for the takeover time
  kOther  // another incarnation while the followed one still speaks: not to be followed
};

// Follows one peer incarnation. Another is taken over only when the one followed has been
// silent (nothing observed from it) for `takeover_ns` and is gone: a restarted peer after its
// old incarnation's liveliness lease, a standby planner after the active one died. A peer the
// caller knows is still alive (followed_alive: DDS holds its writer alive) is only slow, and is
// replaced only after `hung_ns` of silence: a live but hung peer.
class IncarnationTracker {
 public:
  IncarnationTracker(std::int64_t takeover_ns, std::int64_t hung_ns) noexcept
      : takeover_ns_(takeover_ns), hung_ns_(hung_ns < takeover_ns ? takeover_ns : hung_ns) {}

  // A message from `incarnation` arrived at now_ns; kNew switches to it.
  Peer observe(std::uint64_t incarnation, std::int64_t now_ns,
               bool followed_alive = false) noexcept;
  // What observe() would say, changing nothing.
  Peer classify(std::uint64_t incarnation, std::int64_t now_ns,
                bool followed_alive = false) const noexcept;

  std::uint64_t followed() const noexcept { return followed_; }  // 0: none yet
  std::uint64_t switches() const noexcept { return switches_; }  // kNew after the first
  std::uint64_t others() const noexcept { return others_; }      // kOther observed

 private:
  std::int64_t takeover_ns_;
  std::int64_t hung_ns_;
  std::uint64_t followed_ = 0;
  std::int64_t last_heard_ns_ = 0;
  std::uint64_t switches_ = 0;
  std::uint64_t others_ = 0;
};

}  // namespace grip::link
