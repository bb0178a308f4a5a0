// SPDX-License-Identifier: MIT
#include "report/base64.h"

#include <gtest/gtest.h>

namespace genflow {
namespace {

// RFC 4648, section 10.
TEST(Base64, EncodesTheStandardsTestVectors) {
    EXPECT_EQ(detail::base64(""), "");
    EXPECT_EQ(detail::base64("f"), "Zg==");
    EXPECT_EQ(detail::base64("fo"), "Zm8=");
    EXPECT_EQ(detail::base64("foo"), "Zm9v");
    EXPECT_EQ(detail::base64("foob"), "Zm9vYg==");
    EXPECT_EQ(detail::base64("fooba"), "Zm9vYmE=");
    EXPECT_EQ(detail::base64("foobar"), "Zm9vYmFy");
    EXPECT_EQ(detail::base64(std::string("\xff\xfe\x00", 3)), "//4A");
}

}  // namespace
}  // namespace genflow
