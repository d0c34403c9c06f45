// Progress of slow CPU steps (core/progress.h): a quick step says nothing; one that runs past a
// second says what it is, how far it got and, at its end, how long it took.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "core/progress.h"

namespace sl::test {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(ProgressDeathTest, AQuickStepSaysNothing) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_EXIT(
        {
            {
                Progress progress("quick step", 3);
                for (int i = 0; i < 3; ++i) {
                    progress.advance();
                }
            }
            std::fprintf(stderr, "end\n");
            std::exit(0);
        },
        ::testing::ExitedWithCode(0), Not(HasSubstr("quick step")));
}

TEST(ProgressDeathTest, ASlowStepSaysHowFarItGotAndHowLongItTook) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_EXIT(
        {
            {
                Progress progress("slow step", 2);
                std::this_thread::sleep_for(std::chrono::milliseconds(1100));
                progress.advance();
                progress.advance();
            }
            std::exit(0);
        },
        ::testing::ExitedWithCode(0), HasSubstr("slow step: 2 of 2 done in 1."));
}

}  // namespace
}  // namespace sl::test
