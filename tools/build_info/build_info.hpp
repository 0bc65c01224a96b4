#pragma once
// What built this grip: the project's version and the git revision of its sources, for
// `grip --version` and for every report, so that a figure can be traced to the code behind it.

#include <string_view>

namespace grip::tools {

// The version of the project (CMake's project version), e.g. "0.1.0".
std::string_view grip_version() noexcept;
// `git describe --always --dirty` of the sources at build time ("unknown" outside git).
std::string_view grip_revision() noexcept;

}  // namespace grip::tools
