#pragma once
// Logging for every program: spdlog to stderr with one pattern, so that stdout stays free for
// results a user may pipe.
#include <string>

#include <spdlog/spdlog.h>

namespace uhpc {

enum class Verbosity { Quiet, Normal, Verbose };

// Installs the stderr logger named after the program. Quiet shows warnings and errors only,
// Verbose adds debug messages.
void init_logging(const std::string& program, Verbosity verbosity = Verbosity::Normal);

}  // namespace uhpc
