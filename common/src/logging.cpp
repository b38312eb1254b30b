#include "uhpc/logging.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>

namespace uhpc {

void init_logging(const std::string& program, Verbosity verbosity) {
  auto logger = spdlog::get(program);
  if (!logger) logger = spdlog::stderr_color_mt(program);
  logger->set_pattern("[%H:%M:%S] %n %^%l%$: %v");
  switch (verbosity) {
    case Verbosity::Quiet: logger->set_level(spdlog::level::warn); break;
    case Verbosity::Normal: logger->set_level(spdlog::level::info); break;
    case Verbosity::Verbose: logger->set_level(spdlog::level::debug); break;
  }
  spdlog::set_default_logger(logger);
}

}  // namespace uhpc
