#pragma once
// Every JSON report of the grip command is written here, and says what produced it: grip's
// version and git revision and the machine (kernel, CPUs), so that a figure can be traced to
// the code and the computer behind it.

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace grip::tools {

// {"grip": {"version", "revision"}, "machine": {"hostname", "kernel", ...}}.
nlohmann::json produced_by_json();

// Writes `report` to `path` (with `indent`), a JSON object gaining the "produced_by" section,
// whole or not at all (a temporary file renamed into place). On failure says
// "<command>: cannot write '<path>': <why>" on stderr and returns false.
bool write_report(std::string_view command, const std::string& path, nlohmann::json report,
                  int indent = 2);

}  // namespace grip::tools
