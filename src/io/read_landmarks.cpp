// SPDX-License-Identifier: MIT
#include "genflow/io/read_landmarks.h"

#include <cmath>
#include <string>

#include "genflow/exceptions.h"
#include "io/parse_context.h"

namespace genflow {

namespace {

// The index `token` names in [0, count), or an error naming `what`.
Eigen::Index parse_index(std::string_view token, Eigen::Index count, const char* what,
                         const detail::DataLine& line) {
    std::int64_t index = 0;
    if (!detail::parse_integer(token, index)) {
        line.fail(std::string("expected a ") + what + " index, got '" + std::string(token) + "'");
    }
    if (index < 0 || index >= count) {
        line.fail(std::string(what) + " index " + std::to_string(index) + " outside 0.." +
                  std::to_string(count - 1) + " (the indices are 0-based)");
    }
    return static_cast<Eigen::Index>(index);
}

}  // namespace

std::vector<Landmark> read_landmarks(const std::filesystem::path& path,
                                     Eigen::Index template_vertices, const TriangleMesh& target) {
    std::vector<Landmark> landmarks;
    detail::for_each_data_line(path, [&](const detail::DataLine& line) {
        const std::vector<std::string_view>& tokens = line.tokens;
        if (tokens.size() < 2 || tokens.size() > 5) {
            line.fail(
                "expected 'i x y z' (a template vertex and a point) or 'i j' (a template "
                "vertex and a target vertex), each with an optional weight");
        }
        // Two or three tokens name a target vertex, four or five a point; an odd count ends
        // with the weight.
        const bool to_vertex = tokens.size() <= 3;
        const bool weighted = tokens.size() == 3 || tokens.size() == 5;
        Landmark landmark;
        landmark.vertex = parse_index(tokens[0], template_vertices, "template vertex", line);
        if (to_vertex) {
            landmark.target_point =
                target.V.row(parse_index(tokens[1], target.V.rows(), "target vertex", line))
                    .transpose();
        } else {
            for (int c = 0; c < 3; ++c) {
                double& value = landmark.target_point[c];
                const std::string_view token = tokens[static_cast<std::size_t>(c) + 1];
                if (!detail::parse_double(token, value) || !std::isfinite(value)) {
                    line.fail("expected a finite coordinate, got '" + std::string(token) + "'");
                }
            }
        }
        if (weighted && (!detail::parse_double(tokens.back(), landmark.weight) ||
                         !std::isfinite(landmark.weight) || !(landmark.weight > 0))) {
            line.fail("expected a positive weight, got '" + std::string(tokens.back()) + "'");
        }
        landmarks.push_back(landmark);
    });
    if (landmarks.empty()) {
        throw IoError(path.string() + ": no landmark");
    }
    return landmarks;
}

}  // namespace genflow
