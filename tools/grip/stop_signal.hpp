#pragma once
// Ctrl-C and SIGTERM end a command's run: the handler only sets a flag (async-signal-safe), which
// the command polls. One flag per process: a `grip` process runs one command.

#include <atomic>

namespace grip::tools {

std::atomic<bool>& stop_flag() noexcept;
// From now on SIGINT and SIGTERM set stop_flag().
void stop_on_signals() noexcept;

}  // namespace grip::tools
