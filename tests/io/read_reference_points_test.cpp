// SPDX-License-Identifier: MIT
#include "genflow/io/read_reference_points.h"

#include <gtest/gtest.h>

#include "genflow/exceptions.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

TEST(ReadReferencePoints, ReadsOneBasedIndicesAsZeroBased) {
    const test::TemporaryDirectory directory;
    test::write_bytes(directory / "a.vts", "# reference points\n3\n1\r\n\n3\n10");
    const std::vector<Eigen::Index> expected{2, 0, 2, 9};
    EXPECT_EQ(read_reference_points(directory / "a.vts", 10), expected);
}

// The message names the file and the line, and says what is wrong.
void expect_refused(const std::string& text, const std::string& says) {
    const test::TemporaryDirectory directory;
    test::write_bytes(directory / "bad.vts", text);
    try {
        (void)read_reference_points(directory / "bad.vts", 10);
        ADD_FAILURE() << "accepted: " << text;
    } catch (const IoError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("bad.vts: "), std::string::npos) << message;
        EXPECT_NE(message.find(says), std::string::npos) << message;
    }
}

TEST(ReadReferencePoints, RefusesBadLinesNamingFileAndLine) {
    expect_refused("1\n0\n", "line 2: vertex index 0 outside 1..10");
    expect_refused("1\n2\n11\n", "line 3: vertex index 11 outside 1..10");
    expect_refused("1\n2.5\n", "line 2: expected one vertex index");
    expect_refused("1 2\n", "line 1: expected one vertex index");
    expect_refused("# nothing\n\n", "no reference point");
    EXPECT_THROW((void)read_reference_points("/nonexistent/x.vts", 10), IoError);
}

}  // namespace
}  // namespace genflow
