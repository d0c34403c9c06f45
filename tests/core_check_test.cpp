// Internal invariants (core/check.h): a failed check aborts, naming the condition, where it is
// and the values; debug-only checks cost nothing in Release, where their condition is not even
// evaluated.

#include <gtest/gtest.h>

#include <vector>

#include "core/check.h"

namespace sl::test {
namespace {

int evaluations = 0;
bool counted(bool value) {
    ++evaluations;
    return value;
}

// A failed SL_CHECK writes one line with the condition, this file and its line, then aborts.
TEST(CheckDeathTest, AFailedCheckAbortsNamingTheConditionAndWhere) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const int count = 3;
    EXPECT_DEATH(SL_CHECK(count > 4),
                 "internal error: check failed at .*core_check_test.cpp:[0-9]+: count > 4");
    SL_CHECK(count == 3);  // holds: nothing happens
}

// An index check names the index, the size and their values.
TEST(CheckDeathTest, AnIndexCheckGivesTheIndexAndTheSize) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const std::vector<int> values(5);
    const int index = 5;
    EXPECT_DEATH(SL_CHECK_INDEX(index, values.size()),
                 "0 <= index < values.size\\(\\) \\(index 5, size 5\\)");
    EXPECT_DEATH(SL_CHECK_INDEX(-1, values.size()), "\\(index -1, size 5\\)");
    SL_CHECK_INDEX(4, values.size());
    SL_CHECK_INDEX(0, values.size());
}

// SL_DCHECK is SL_CHECK in a debug build; in Release (NDEBUG) its condition is compiled but
// never evaluated.
TEST(CheckDeathTest, DebugChecksAreFreeInRelease) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    evaluations = 0;
    SL_DCHECK(counted(true));
    SL_DCHECK_INDEX(evaluations, 1000);
#ifdef NDEBUG
    EXPECT_EQ(evaluations, 0);
    SL_DCHECK(counted(false));  // not evaluated, so it cannot fail
    EXPECT_EQ(evaluations, 0);
#else
    EXPECT_EQ(evaluations, 1);
    EXPECT_DEATH(SL_DCHECK(counted(false)), "counted\\(false\\)");
#endif
}

}  // namespace
}  // namespace sl::test
