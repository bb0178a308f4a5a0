// SPDX-License-Identifier: MIT
#include "genflow/evaluation/reference_landmarks.h"

#include <algorithm>
#include <limits>

#include "genflow/exceptions.h"

namespace genflow {

namespace {

void check_references(const TriangleMesh& mesh, const std::vector<Eigen::Index>& reference) {
    for (const Eigen::Index v : reference) {
        if (v < 0 || v >= mesh.V.rows()) {
            throw InvalidInput("reference_landmarks: a reference vertex outside its mesh");
        }
    }
}

}  // namespace

std::vector<Landmark> reference_landmarks(const TriangleMesh& from,
                                          const std::vector<Eigen::Index>& from_reference,
                                          const TriangleMesh& to,
                                          const std::vector<Eigen::Index>& to_reference,
                                          int count) {
    if (count < 1 || from_reference.size() != to_reference.size() ||
        from_reference.size() < static_cast<std::size_t>(count)) {
        throw InvalidInput(
            "reference_landmarks: need as many reference points on both shapes, at least the "
            "landmarks asked for (and one)");
    }
    check_references(from, from_reference);
    check_references(to, to_reference);
    const std::size_t points = from_reference.size();
    std::vector<double> distance(points, std::numeric_limits<double>::infinity());
    std::vector<Landmark> landmarks;
    std::size_t next = 0;
    for (int k = 0; k < count; ++k) {
        landmarks.push_back({from_reference[next], to.V.row(to_reference[next]).transpose()});
        const Eigen::RowVector3d chosen = from.V.row(from_reference[next]);
        for (std::size_t r = 0; r < points; ++r) {
            distance[r] =
                std::min(distance[r], (from.V.row(from_reference[r]) - chosen).squaredNorm());
        }
        next = static_cast<std::size_t>(std::max_element(distance.begin(), distance.end()) -
                                        distance.begin());
    }
    return landmarks;
}

}  // namespace genflow
