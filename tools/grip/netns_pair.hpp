#pragma once
// Two network namespaces joined by a veth pair, for `grip bench faults`: the planner in one, the
// vehicle in the other, so that the link between them is a real network link on which faults can
// be made without touching the machine's own. Each end has a loopback-range address
// (127.1.0.1 and 127.1.0.2, with route_localnet), so nothing can leave the namespaces. Created
// with iproute2's `ip`, and deleted (the veth pair with them) when the object goes out of scope.

#include <string>
#include <vector>

#include "grip/common/result.hpp"

namespace grip::tools {

// Runs a system tool (`ip`, `iptables`) and waits for it; an error names the command and its exit
// status, with its first line of output.
Status run_tool(const std::vector<std::string>& args);

class NetnsPair {
 public:
  struct End {
    std::string netns;      // grip-<tag>p or grip-<tag>v
    std::string interface;  // its end of the veth pair
    std::string address;    // its own
    std::string peer;       // the other end's
  };

  // `tag` makes the names unique (the bench's pid); it must be short (interface names have 15
  // characters). Refuses names that exist already: another run's, never touched.
  static Result<NetnsPair> create(const std::string& tag);
  NetnsPair(NetnsPair&& other) noexcept;
  NetnsPair& operator=(NetnsPair&&) = delete;
  ~NetnsPair();

  const End& planner() const { return planner_; }
  const End& vehicle() const { return vehicle_; }

  // The argument list that runs `command` inside `end`'s namespace, killed when the process that
  // spawned it (its thread) ends: nothing outlives the bench.
  static std::vector<std::string> in_namespace(const End& end, std::vector<std::string> command);
  // A Cyclone DDS configuration for a participant at `end`: its interface only, no multicast,
  // the other end as its one peer.
  static std::string cyclone_config(const End& end);

 private:
  NetnsPair(End planner, End vehicle)
      : planner_(std::move(planner)), vehicle_(std::move(vehicle)) {}
  void remove() noexcept;
  End planner_;
  End vehicle_;
  bool owned_ = true;
};

}  // namespace grip::tools
