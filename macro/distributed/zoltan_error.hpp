#pragma once
// Zoltan's return codes as exceptions: a failed partition or send is a numerical failure of the run.
#include <stdexcept>
#include <string>

#include <zoltan_types.h>

namespace uhpc::macro::distributed {

inline void check_zoltan(int code, const char* what) {
  if (code != ZOLTAN_OK && code != ZOLTAN_WARN)
    throw std::runtime_error(std::string(what) + " failed (Zoltan code " + std::to_string(code) + ")");
}

}  // namespace uhpc::macro::distributed
