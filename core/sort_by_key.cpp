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
    thread_local std::vector<uint32_t> start, bucket;
    thread_local std::vector<std::pair<double, uint32_t>> scratch;
    start.assign(buckets + 1, 0);
    bucket.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const double t = (pairs[i].first - lo) * scale;
        bucket[i] = uint32_t(t < double(buckets) ? size_t(t) : buckets - 1);
        ++start[bucket[i] + 1];
    }
    for (size_t b = 0; b < buckets; ++b) {
        start[b + 1] += start[b];
    }
    scratch.resize(n);
    {
        thread_local std::vector<uint32_t> next;
        next.assign(start.begin(), start.end() - 1);
        for (size_t i = 0; i < n; ++i) {
            scratch[next[bucket[i]]++] = pairs[i];
        }
    }
    for (size_t b = 0; b < buckets; ++b) {
        if (start[b + 1] - start[b] > 1) {
            std::sort(scratch.begin() + start[b], scratch.begin() + start[b + 1]);
        }
    }
    pairs.swap(scratch);
}

}  // namespace sl
