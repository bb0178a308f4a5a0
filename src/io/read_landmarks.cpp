// SPDX-License-Identifier: MIT
#include "genflow/io/read_landmarks.h"

#include <cmath>
#include <functional>
#include <string>

#include "genflow/exceptions.h"
#include "genflow/io/read_file.h"
#include "io/parse_context.h"

namespace genflow {

namespace {

// The line without its comment.
std::string_view without_comment(std::string_view line) {
    return line.substr(0, line.find('#'));
}

// The index `token` names in [0, count), or an error naming `what`.
Eigen::Index parse_index(std::string_view token, Eigen::Index count, const char* what,
                         const std::function<void(const std::string&)>& fail) {
    std::int64_t index = 0;
    if (!detail::parse_integer(token, index)) {
        fail(std::string("expected a ") + what + " index, got '" + std::string(token) + "'");
    }
    if (index < 0 || index >= count) {
        fail(std::string(what) + " index " + std::to_string(index) + " outside 0.." +
             std::to_string(count - 1) + " (the indices are 0-based)");
    }
    return static_cast<Eigen::Index>(index);
}

}  // namespace

std::vector<Landmark> read_landmarks(const std::filesystem::path& path,
                                     Eigen::Index template_vertices, const TriangleMesh& target) {
    const std::string text = read_file(path);
    detail::TextScanner scanner(text);
    std::vector<std::string_view> tokens;
    std::vector<Landmark> landmarks;
    std::size_t line = 1;
    const std::function<void(const std::string&)> fail = [&](const std::string& problem) {
        throw IoError(path.string() + ": line " + std::to_string(line) + ": " + problem);
    };
    for (; !scanner.at_end(); ++line) {
        detail::split_tokens(without_comment(scanner.next_line()), tokens);
        if (tokens.empty()) {
            continue;
        }
        if (tokens.size() < 2 || tokens.size() > 5) {
            fail(
                "expected 'i x y z' (a template vertex and a point) or 'i j' (a template "
                "vertex and a target vertex), each with an optional weight");
        }
        // Two or three tokens name a target vertex, four or five a point; an odd count ends
        // with the weight.
        const bool to_vertex = tokens.size() <= 3;
        const bool weighted = tokens.size() == 3 || tokens.size() == 5;
        Landmark landmark;
        landmark.vertex = parse_index(tokens[0], template_vertices, "template vertex", fail);
        if (to_vertex) {
            landmark.target_point =
                target.V.row(parse_index(tokens[1], target.V.rows(), "target vertex", fail))
                    .transpose();
        } else {
            for (int c = 0; c < 3; ++c) {
                double& value = landmark.target_point[c];
                const std::string_view token = tokens[static_cast<std::size_t>(c) + 1];
                if (!detail::parse_double(token, value) || !std::isfinite(value)) {
                    fail("expected a finite coordinate, got '" + std::string(token) + "'");
                }
            }
        }
        if (weighted && (!detail::parse_double(tokens.back(), landmark.weight) ||
                         !std::isfinite(landmark.weight) || !(landmark.weight > 0))) {
            fail("expected a positive weight, got '" + std::string(tokens.back()) + "'");
        }
        landmarks.push_back(landmark);
    }
    if (landmarks.empty()) {
        throw IoError(path.string() + ": no landmark");
    }
    return landmarks;
}

}  // namespace genflow
