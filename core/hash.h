#pragma once
// FNV-1a (64 bit): the content hash behind shaftlab's cache keys. Feed `hash` back in to hash a
// sequence of pieces (a file read in chunks).

#include <cstdint>
#include <string_view>

namespace sl {

constexpr uint64_t kFnv1aOffset = 0xCBF29CE484222325ull;

constexpr uint64_t fnv1a(std::string_view bytes, uint64_t hash = kFnv1aOffset) {
    for (const char c : bytes) {
        hash = (hash ^ uint8_t(c)) * 0x100000001B3ull;
    }
    return hash;
}

}  // namespace sl
