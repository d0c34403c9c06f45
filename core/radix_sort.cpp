#include "core/radix_sort.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include "core/check.h"

namespace sl {
namespace {

// An unsigned integer that orders as the double does: negative numbers' bits flipped (they
// order backwards), the sign bit set on the others.
uint64_t ordered_bits(double key) {
    const uint64_t bits = std::bit_cast<uint64_t>(key + 0.0);  // -0.0 + 0.0 is 0.0
    return bits >> 63 ? ~bits : bits | (uint64_t(1) << 63);
}

}  // namespace

void sort_by_key(std::vector<std::pair<double, uint32_t>>& pairs) {
    constexpr int kBytes = 8;
    const size_t n = pairs.size();
    for (const auto& pair : pairs) {
        SL_CHECK(!std::isnan(pair.first));  // neither sort orders a NaN
    }
    if (n < kRadixFrom) {
        std::sort(pairs.begin(), pairs.end());
        return;
    }
    std::array<std::array<uint32_t, 256>, kBytes> counts{};
    for (const auto& [key, index] : pairs) {
        const uint64_t bits = ordered_bits(key);
        for (int b = 0; b < kBytes; ++b) {
            ++counts[size_t(b)][(bits >> (8 * b)) & 0xff];
        }
    }
    thread_local std::vector<std::pair<double, uint32_t>> scratch;
    scratch.resize(n);
    for (int b = 0; b < kBytes; ++b) {
        std::array<uint32_t, 256>& count = counts[size_t(b)];
        const uint64_t first = (ordered_bits(pairs.front().first) >> (8 * b)) & 0xff;
        if (count[first] == n) {
            continue;  // every key has this byte: the pass would not move a pair
        }
        uint32_t start = 0;  // each byte value's first place
        for (uint32_t& c : count) {
            const uint32_t here = c;
            c = start;
            start += here;
        }
        for (const auto& pair : pairs) {
            scratch[count[(ordered_bits(pair.first) >> (8 * b)) & 0xff]++] = pair;
        }
        pairs.swap(scratch);
    }
}

}  // namespace sl
