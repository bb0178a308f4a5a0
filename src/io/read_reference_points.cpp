// SPDX-License-Identifier: MIT
#include "genflow/io/read_reference_points.h"

#include <string>

#include "genflow/exceptions.h"
#include "genflow/io/read_file.h"
#include "io/parse_context.h"

namespace genflow {

std::vector<Eigen::Index> read_reference_points(const std::filesystem::path& path,
                                                Eigen::Index vertex_count) {
    const std::string text = read_file(path);
    detail::TextScanner scanner(text);
    std::vector<std::string_view> tokens;
    std::vector<Eigen::Index> vertices;
    const auto fail = [&](std::size_t line, const std::string& problem) {
        throw IoError(path.string() + ": line " + std::to_string(line) + ": " + problem);
    };
    for (std::size_t line = 1; !scanner.at_end(); ++line) {
        detail::split_tokens(scanner.next_line(), tokens);
        if (tokens.empty() || tokens.front().front() == '#') {
            continue;
        }
        std::int64_t index = 0;
        if (tokens.size() != 1 || !detail::parse_integer(tokens.front(), index)) {
            fail(line, "expected one vertex index (1-based)");
        }
        if (index < 1 || index > vertex_count) {
            fail(line, "vertex index " + std::to_string(index) + " outside 1.." +
                           std::to_string(vertex_count) + " (the file's indices are 1-based)");
        }
        vertices.push_back(static_cast<Eigen::Index>(index - 1));
    }
    if (vertices.empty()) {
        throw IoError(path.string() + ": no reference point");
    }
    return vertices;
}

}  // namespace genflow
