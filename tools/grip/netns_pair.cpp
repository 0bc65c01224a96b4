#include "netns_pair.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "child.hpp"

namespace grip::tools {

Status run_tool(const std::vector<std::string>& args) {
  char path[] = "/tmp/grip-tool-XXXXXX";
  const int fd = mkstemp(path);
  if (fd < 0) return Error{ErrorCode::kIo, "cannot create a temporary file"};
  close(fd);
  auto child = Child::spawn(args, {}, path, true);
  if (!child) {
    std::filesystem::remove(path);
    return child.error();
  }
  const int status = child->wait();
  std::string first_line;
  {
    std::ifstream out(path);
    std::getline(out, first_line);
  }
  std::filesystem::remove(path);
  if (status == 0) return Ok{};
  std::string command;
  for (const auto& a : args) command += (command.empty() ? "" : " ") + a;
  return Error{ErrorCode::kIo, "'" + command + "' failed (exit " + std::to_string(status) + ")" +
                                   (first_line.empty() ? "" : ": " + first_line)};
}

Result<NetnsPair> NetnsPair::create(const std::string& tag) {
  NetnsPair pair(End{"grip-" + tag + "p", "g" + tag + "p", "127.1.0.1", "127.1.0.2"},
                 End{"grip-" + tag + "v", "g" + tag + "v", "127.1.0.2", "127.1.0.1"});
  if (pair.planner_.interface.size() > 15) {
    pair.owned_ = false;
    return invalid_argument("network namespace tag '" + tag + "' too long");
  }
  for (const End* end : {&pair.planner_, &pair.vehicle_}) {
    if (std::filesystem::exists("/run/netns/" + end->netns)) {
      pair.owned_ = false;  // another run's: not ours to delete
      return Error{ErrorCode::kIo, "network namespace " + end->netns + " exists already"};
    }
  }
  // From here on, whatever was made is deleted when `pair` goes out of scope.
  const std::vector<std::vector<std::string>> steps = [&] {
    const End& p = pair.planner_;
    const End& v = pair.vehicle_;
    std::vector<std::vector<std::string>> s{
        {"ip", "netns", "add", p.netns},
        {"ip", "netns", "add", v.netns},
        {"ip", "-n", p.netns, "link", "add", p.interface, "type", "veth", "peer", "name",
         v.interface, "netns", v.netns}};
    for (const End* e : {&p, &v}) {
      const std::vector<std::vector<std::string>> each{
          {"ip", "-n", e->netns, "link", "set", "lo", "up"},
          {"ip", "netns", "exec", e->netns, "sysctl", "-q", "-w",
           "net.ipv4.conf.all.route_localnet=1"},
          {"ip", "netns", "exec", e->netns, "sysctl", "-q", "-w",
           "net.ipv4.conf." + e->interface + ".route_localnet=1"},
          {"ip", "-n", e->netns, "addr", "add", e->address, "peer", e->peer, "dev", e->interface},
          {"ip", "-n", e->netns, "link", "set", e->interface, "up"}};
      s.insert(s.end(), each.begin(), each.end());
    }
    return s;
  }();
  for (const auto& step : steps) {
    if (Status s = run_tool(step); !s) return s.error();
  }
  return pair;
}

NetnsPair::NetnsPair(NetnsPair&& other) noexcept
    : planner_(std::move(other.planner_)),
      vehicle_(std::move(other.vehicle_)),
      owned_(other.owned_) {
  other.owned_ = false;
}

NetnsPair::~NetnsPair() { remove(); }

void NetnsPair::remove() noexcept {
  if (!owned_) return;
  owned_ = false;
  for (const End* end : {&planner_, &vehicle_}) {
    if (std::filesystem::exists("/run/netns/" + end->netns)) {
      (void)run_tool({"ip", "netns", "delete", end->netns});
    }
  }
}

std::vector<std::string> NetnsPair::in_namespace(const End& end, std::vector<std::string> command) {
  std::vector<std::string> args{"setpriv", "--pdeathsig", "KILL", "ip", "netns", "exec", end.netns};
  args.insert(args.end(), std::make_move_iterator(command.begin()),
              std::make_move_iterator(command.end()));
  return args;
}

std::string NetnsPair::cyclone_config(const End& end) {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
         "<!-- grip bench faults: one end of its veth pair, inside its own network namespace. "
         "-->\n"
         "<CycloneDDS>\n"
         "  <Domain id=\"any\">\n"
         "    <General>\n"
         "      <Interfaces><NetworkInterface name=\"" +
         end.interface +
         "\"/></Interfaces>\n"
         "      <AllowMulticast>false</AllowMulticast>\n"
         "    </General>\n"
         "    <Discovery>\n"
         "      <ParticipantIndex>auto</ParticipantIndex>\n"
         "      <MaxAutoParticipantIndex>30</MaxAutoParticipantIndex>\n"
         "      <Peers><Peer address=\"" +
         end.peer +
         "\"/></Peers>\n"
         "    </Discovery>\n"
         "  </Domain>\n"
         "</CycloneDDS>\n";
}

}  // namespace grip::tools
