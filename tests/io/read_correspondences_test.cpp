// SPDX-License-Identifier: MIT
#include "genflow/io/read_correspondences.h"

#include <gtest/gtest.h>

#include "genflow/exceptions.h"
#include "genflow/io/write_correspondences.h"
#include "genflow/mesh/primitives.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// What write_correspondences() writes is read back: the faces, the barycentric coordinates to
// its nine digits, and the points they make on the target.
TEST(ReadCorrespondences, ReadsBackWhatIsWritten) {
    const test::TemporaryDirectory directory;
    const TriangleMesh target = make_icosphere(1);
    std::vector<SurfacePoint> written;
    for (Eigen::Index f = 0; f < 5; ++f) {
        written.push_back({f * 7, Eigen::Vector3d(0.2, 0.3, 0.5), Eigen::Vector3d::Zero(), 0.25});
    }
    write_correspondences(directory / "map.txt", written);
    const std::vector<SurfacePoint> read = read_correspondences(directory / "map.txt", target, 5);
    ASSERT_EQ(read.size(), 5U);
    for (std::size_t k = 0; k < read.size(); ++k) {
        EXPECT_EQ(read[k].face, written[k].face);
        EXPECT_NEAR((read[k].barycentric - written[k].barycentric).norm(), 0, 1e-9);
        const Eigen::Vector3d expected = 0.2 * target.V.row(target.F(read[k].face, 0)) +
                                         0.3 * target.V.row(target.F(read[k].face, 1)) +
                                         0.5 * target.V.row(target.F(read[k].face, 2));
        EXPECT_NEAR((read[k].point - expected).norm(), 0, 1e-9);
    }
}

TEST(ReadCorrespondences, RefusesABadLineOrCountNamingIt) {
    const test::TemporaryDirectory directory;
    const TriangleMesh target = make_icosphere(0);  // 20 faces
    for (const auto& [text, says] : {
             std::pair{"# header\n0 0.2 0.3 0.5 0\n20 1 0 0 0\n", "line 3: face 20 outside 0..19"},
             {"0 0.2 0.3 0.6 0\n", "line 1: barycentric coordinates"},
             {"0 inf 0 0 0\n", "line 1: barycentric coordinates"},
             {"0 1 0 0 -1\n", "line 1: the distance"},
             {"0 1 0\n", "line 1: expected 'face b0 b1 b2 distance'"},
             {"0 1 0 0 0\n", "1 correspondences for the template's 2 vertices"},
             {"0 1 0 0 0\n0 1 0 0 0\n0 1 0 0 0\n", "line 3: more lines than the template's 2"},
         }) {
        test::write_bytes(directory / "map.txt", text);
        try {
            (void)read_correspondences(directory / "map.txt", target, 2);
            ADD_FAILURE() << text;
        } catch (const IoError& e) {
            EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
        }
    }
}

}  // namespace
}  // namespace genflow
