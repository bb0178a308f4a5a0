// SPDX-License-Identifier: MIT
#include "genflow/io/read_landmarks.h"

#include <gtest/gtest.h>

#include "genflow/exceptions.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// (The file starts with a UTF-8 byte order mark, as some editors write one.)
TEST(ReadLandmarks, ReadsPointsAndTargetVerticesWithComments) {
    const test::TemporaryDirectory directory;
    const TriangleMesh target = test::noisy_icosphere(1);
    test::write_bytes(directory / "marks.txt",
                      "\xEF\xBB\xBF# template vertex, then a point or a target vertex\n"
                      "3 0.5 -1 2e-1\r\n"
                      "\n"
                      "0 7   # the tip\n"
                      "  9\t1 2 3\n");
    const std::vector<Landmark> landmarks = read_landmarks(directory / "marks.txt", 10, target);
    ASSERT_EQ(landmarks.size(), 3U);
    EXPECT_EQ(landmarks[0].vertex, 3);
    EXPECT_EQ(landmarks[0].target_point, Eigen::Vector3d(0.5, -1, 0.2));
    EXPECT_EQ(landmarks[1].vertex, 0);
    EXPECT_EQ(landmarks[1].target_point, target.V.row(7).transpose());
    EXPECT_EQ(landmarks[2].vertex, 9);
    EXPECT_EQ(landmarks[2].target_point, Eigen::Vector3d(1, 2, 3));
    for (const Landmark& landmark : landmarks) {
        EXPECT_EQ(landmark.weight, 1);
    }
}

// A last, odd token is the landmark's weight: three tokens name a target vertex, five a point.
TEST(ReadLandmarks, ReadsAnOptionalWeight) {
    const test::TemporaryDirectory directory;
    const TriangleMesh target = test::noisy_icosphere(1);
    test::write_bytes(directory / "marks.txt", "3 0.5 -1 2e-1 4\n0 7 0.25  # less sure\n");
    const std::vector<Landmark> landmarks = read_landmarks(directory / "marks.txt", 10, target);
    ASSERT_EQ(landmarks.size(), 2U);
    EXPECT_EQ(landmarks[0].target_point, Eigen::Vector3d(0.5, -1, 0.2));
    EXPECT_EQ(landmarks[0].weight, 4);
    EXPECT_EQ(landmarks[1].target_point, target.V.row(7).transpose());
    EXPECT_EQ(landmarks[1].weight, 0.25);
}

// The message names the file and the line, and says what is wrong.
void expect_landmarks_refused(const std::string& text, const std::string& says) {
    const test::TemporaryDirectory directory;
    test::write_bytes(directory / "bad.txt", text);
    const TriangleMesh target = test::noisy_icosphere(0);  // 12 vertices
    try {
        (void)read_landmarks(directory / "bad.txt", 10, target);
        ADD_FAILURE() << "accepted: " << text;
    } catch (const IoError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("bad.txt: "), std::string::npos) << message;
        EXPECT_NE(message.find(says), std::string::npos) << message;
    }
}

TEST(ReadLandmarks, RefusesBadLinesNamingFileAndLine) {
    expect_landmarks_refused("1 2\n10 2\n", "line 2: template vertex index 10 outside 0..9");
    expect_landmarks_refused("-1 2\n", "line 1: template vertex index -1 outside 0..9");
    expect_landmarks_refused("1 12\n", "line 1: target vertex index 12 outside 0..11");
    expect_landmarks_refused("1\n", "line 1: expected 'i x y z'");
    expect_landmarks_refused("1 2 3 4 5 6\n", "line 1: expected 'i x y z'");
    expect_landmarks_refused("1 2 0\n", "line 1: expected a positive weight, got '0'");
    expect_landmarks_refused("1 2 3 4 -1\n", "line 1: expected a positive weight, got '-1'");
    expect_landmarks_refused("1 2 inf\n", "line 1: expected a positive weight, got 'inf'");
    expect_landmarks_refused("1 2 3 4 w\n", "line 1: expected a positive weight, got 'w'");
    expect_landmarks_refused("1.5 2\n", "line 1: expected a template vertex index, got '1.5'");
    expect_landmarks_refused("# a\n1 2 nan 4\n", "line 2: expected a finite coordinate, got 'nan'");
    expect_landmarks_refused("1 x 3 4\n", "line 1: expected a finite coordinate, got 'x'");
    expect_landmarks_refused("# nothing\n\n", "no landmark");
    EXPECT_THROW((void)read_landmarks("/nonexistent/x.txt", 10, test::noisy_icosphere(0)), IoError);
}

}  // namespace
}  // namespace genflow
