#include "uhpc/hash.hpp"

#include <cstdint>
#include <cstdio>

namespace uhpc {

namespace {

constexpr std::uint64_t kOffsetBasis = 0xcbf29ce484222325ULL;
constexpr std::uint64_t kPrime = 0x100000001b3ULL;

std::uint64_t fnv1a64_bytes(std::uint64_t h, std::string_view bytes) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= kPrime;
  }
  return h;
}

std::string hex(std::uint64_t h) {
  char out[17];
  std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h));
  return out;
}

}  // namespace

std::string fnv1a64_hex(std::string_view bytes) { return hex(fnv1a64_bytes(kOffsetBasis, bytes)); }

std::string fnv1a64_words_hex(std::string_view bytes) {
  std::uint64_t h = kOffsetBasis;
  const std::size_t words = bytes.size() / 8;
  for (std::size_t i = 0; i < words; ++i) {
    std::uint64_t w = 0;
    for (int b = 7; b >= 0; --b) w = (w << 8) | static_cast<unsigned char>(bytes[8 * i + static_cast<std::size_t>(b)]);
    h ^= w;
    h *= kPrime;
  }
  return hex(fnv1a64_bytes(h, bytes.substr(8 * words)));
}

}  // namespace uhpc
