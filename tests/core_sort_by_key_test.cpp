// sort_by_key (core/sort_by_key.h) against std::sort on the same pairs: spread keys, keys
// crowded into a few of its buckets, and the keys it leaves to std::sort.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <random>

#include "core/sort_by_key.h"

namespace sl::test {
namespace {

using Pairs = std::vector<std::pair<double, uint32_t>>;

Pairs numbered(const std::vector<double>& keys) {
    Pairs pairs;
    for (size_t i = 0; i < keys.size(); ++i) {
        pairs.emplace_back(keys[i], uint32_t(i));
    }
    return pairs;
}

// The order std::sort gives (by key, then by index), which the beam tree's offer had.
void expect_as_std_sort(const std::vector<double>& keys, const char* what) {
    Pairs expected = numbered(keys), sorted = numbered(keys);
    std::sort(expected.begin(), expected.end());
    sort_by_key(sorted);
    ASSERT_EQ(sorted.size(), expected.size()) << what;
    size_t differ = 0;
    for (size_t i = 0; i < sorted.size(); ++i) {
        // -0.0 and 0.0 compare equal, so std::sort may keep either first; the index decides.
        differ += sorted[i].second != expected[i].second || !(sorted[i].first == expected[i].first);
    }
    EXPECT_EQ(differ, 0u) << what;
}

TEST(SortByKey, OrdersAsStdSortByKeyThenIndex) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> metres(0.0, 60.0);
    std::vector<double> distances(20000);
    for (double& d : distances) {
        d = metres(rng);
    }
    expect_as_std_sort(distances, "distances in [0, 60) m");
    expect_as_std_sort(std::vector<double>(distances.begin(), distances.begin() + 2 * kBucketsFrom),
                       "a few hundred distances");

    // Ties (whole centimetres), signs, both zeros, magnitudes from denormal to huge, infinities.
    std::vector<double> mixed;
    std::uniform_int_distribution<int> centimetres(-300, 300);
    std::uniform_real_distribution<double> exponent(-320.0, 300.0);
    for (int i = 0; i < 5000; ++i) {
        mixed.push_back(0.01 * centimetres(rng));
        const double magnitude = std::pow(10.0, exponent(rng));
        mixed.push_back(i % 2 ? magnitude : -magnitude);
    }
    for (double special :
         {0.0, -0.0, std::numeric_limits<double>::denorm_min(),
          -std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max(),
          std::numeric_limits<double>::lowest(), std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity()}) {
        mixed.push_back(special);
        mixed.push_back(special);
    }
    std::shuffle(mixed.begin(), mixed.end(), rng);
    // Without the infinities and the extremes their range is finite: the buckets sort them,
    // nearly all of them crowded into the two buckets about zero.
    std::vector<double> finite;
    std::copy_if(mixed.begin(), mixed.end(), std::back_inserter(finite),
                 [](double key) { return std::abs(key) < 1e305; });
    ASSERT_GE(finite.size(), kBucketsFrom);
    expect_as_std_sort(finite, "ties, signs, zeros, denormals to 1e300");
    expect_as_std_sort(mixed, "ties, signs, zeros, extremes, infinities");

    // Distances crowded near one end of their range by a single far one: one bucket holds all
    // but it; and both zeros mixed in a bucket of their own.
    std::vector<double> crowded(8000);
    for (double& d : crowded) {
        d = 1e-6 * metres(rng);
    }
    crowded.push_back(1e6);
    for (int i = 0; i < 100; ++i) {
        crowded.push_back(i % 2 ? 0.0 : -0.0);
    }
    std::shuffle(crowded.begin(), crowded.end(), rng);
    expect_as_std_sort(crowded, "crowded into one bucket");

    // A range so narrow that its buckets' width is denormal: left to std::sort.
    std::vector<double> narrow(kBucketsFrom);
    for (size_t i = 0; i < narrow.size(); ++i) {
        narrow[i] = std::numeric_limits<double>::denorm_min() * double(i % 7);
    }
    expect_as_std_sort(narrow, "a denormal range");

    expect_as_std_sort({}, "none");
    expect_as_std_sort({1.0}, "one");
    expect_as_std_sort(std::vector<double>(kBucketsFrom, 2.5), "all equal: one bucket");
    expect_as_std_sort({3.0, 1.0, 2.0, 1.0}, "a few (std::sort)");
}

TEST(SortByKeyDeathTest, RefusesANanKey) {
    Pairs few = numbered({1.0, std::nan(""), 0.5});
    EXPECT_DEATH(sort_by_key(few), "isnan");
    std::vector<double> keys(kBucketsFrom, 1.0);
    keys[7] = std::nan("");
    Pairs many = numbered(keys);
    EXPECT_DEATH(sort_by_key(many), "isnan");
}

}  // namespace
}  // namespace sl::test
