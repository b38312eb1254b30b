#pragma once
// A small, stable, dependency-free hash for identifying configurations in provenance blocks.
#include <string>
#include <string_view>

namespace uhpc {

// 64-bit FNV-1a of the bytes, as 16 lowercase hex digits.
std::string fnv1a64_hex(std::string_view bytes);

}  // namespace uhpc
