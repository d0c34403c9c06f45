// User bytes in messages (core/text.h): escaped, truncated, and every sl::Error one printable
// line whatever went into it.

#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "core/text.h"

namespace sl::test {
namespace {

// Control bytes, DEL and invalid UTF-8 are escaped; printable ASCII and valid UTF-8 are kept.
TEST(Text, PrintableEscapesWhatATerminalWouldActOn) {
    EXPECT_EQ(printable("plain text"), "plain text");
    EXPECT_EQ(printable("σs ≥ 0, m²"), "σs ≥ 0, m²");
    EXPECT_EQ(printable("a\nb\r\tc"), "a\\nb\\r\\tc");
    EXPECT_EQ(printable(std::string("\x1b[31m\x7f\x00z", 8)), "\\x1b[31m\\x7f\\x00z");
    EXPECT_EQ(printable("\xff\xc3(\xe2\x82"), "\\xff\\xc3(\\xe2\\x82");  // not UTF-8
    EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");             // a surrogate
    EXPECT_EQ(printable("\xc0\xaf"), "\\xc0\\xaf");                      // overlong
}

// quote() cuts long input at a UTF-8 boundary and says how long it was; clipped() the same
// without quotes.
TEST(Text, QuoteTruncatesAndNamesTheSize) {
    EXPECT_EQ(quote("sphre"), "'sphre'");
    EXPECT_EQ(quote(std::string(100, 'x'), 10), "'xxxxxxxxxx…' (100 bytes)");
    EXPECT_EQ(quote("ααααα", 3), "'α…' (10 bytes)");
    EXPECT_EQ(clipped("key\n", 64), "key\\n");
    EXPECT_EQ(clipped(std::string(70, 'k'), 4), "kkkk… (70 bytes)");
}

// Every error is one printable line, even when its message was built from raw bytes.
TEST(Text, ErrorsAreOnePrintableLine) {
    const Error e(std::string("file:3: bad \x1b[2J value\nsecond line"));
    EXPECT_STREQ(e.what(), "file:3: bad \\x1b[2J value\\nsecond line");
}

}  // namespace
}  // namespace sl::test
