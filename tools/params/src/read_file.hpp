#pragma once
// The bytes of a parameter file, from a path a user gave. Private to grip_params.

#include <string>

#include "grip/common/result.hpp"

namespace grip::params::detail {

// The largest parameter file read: far above any real one, and what keeps a wrong path (a
// log, an image) from being read whole.
inline constexpr long kMaxParameterFileBytes = 1L << 20;

// The file's content. Refused (kInvalidArgument, naming the path): a path that cannot be
// opened, a directory, anything but a regular file (a device such as /dev/zero or a FIFO, which
// could be read for ever or block: opened without blocking and checked before a byte is read),
// a file larger than kMaxParameterFileBytes.
Result<std::string> read_parameter_file(const std::string& path);

}  // namespace grip::params::detail
