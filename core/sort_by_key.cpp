#include "core/sort_by_key.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.h"

namespace sl {

void sort_by_key(std::vector<std::pair<double, uint32_t>>& pairs) {
    const size_t n = pairs.size();
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (const auto& pair : pairs) {
        SL_CHECK(!std::isnan(pair.first));  // neither sort orders a NaN
        lo = std::min(lo, pair.first);
        hi = std::max(hi, pair.first);
    }
    // n buckets of equal width over [lo, hi]: a key's bucket never decreases as the key grows
    // (subtraction, a positive factor and truncation are monotone in floating point), so bucket
    // by bucket, each bucket sorted, is the order std::sort gives.
    const size_t buckets = n;
    const double scale = hi > lo ? double(buckets) / (hi - lo) : 0.0;
    if (n < kBucketsFrom || !std::isfinite(hi - lo) || !std::isfinite(scale)) {
        std::sort(pairs.begin(), pairs.end());  // few, an infinite key, or a denormal range
        return;
    }
    // end[b] counts bucket b, then (summed before it) is where the bucket starts, then (each of
    // its pairs placed there and it moved on) where it ends: the scatter leaves the ends.
    thread_local std::vector<uint32_t> end, bucket;
    thread_local std::vector<std::pair<double, uint32_t>> scratch;
    end.assign(buckets, 0);
    bucket.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const double t = (pairs[i].first - lo) * scale;
        bucket[i] = uint32_t(t < double(buckets) ? size_t(t) : buckets - 1);
        ++end[bucket[i]];
    }
    uint32_t start = 0;
    for (uint32_t& e : end) {
        const uint32_t count = e;
        e = start;
        start += count;
    }
    scratch.resize(n);
    for (size_t i = 0; i < n; ++i) {
        scratch[end[bucket[i]]++] = pairs[i];
    }
    for (size_t b = 0; b < buckets; ++b) {
        const uint32_t begin = b == 0 ? 0 : end[b - 1];
        if (end[b] - begin > 1) {
            std::sort(scratch.begin() + begin, scratch.begin() + end[b]);
        }
    }
    pairs.swap(scratch);
}

}  // namespace sl
