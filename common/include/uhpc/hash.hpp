#pragma once
// A small, stable, dependency-free hash for identifying configurations in provenance blocks.
#include <string>
#include <string_view>

namespace uhpc {

// 64-bit FNV-1a of the bytes, as 16 lowercase hex digits.
std::string fnv1a64_hex(std::string_view bytes);

// The same scheme over 64-bit little-endian words instead of bytes (the bytes that do not fill a last
// word as in fnv1a64_hex): about 8x faster, for digests of large arrays. Each step (xor a word, multiply
// by the odd FNV prime) is a bijection of the state, so a change confined to one word always changes
// the digest. As 16 lowercase hex digits.
std::string fnv1a64_words_hex(std::string_view bytes);

}  // namespace uhpc
