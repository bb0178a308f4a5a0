// SPDX-License-Identifier: MIT
#include "genflow/io/read_reference_points.h"

#include <string>

#include "genflow/exceptions.h"
#include "io/parse_context.h"

namespace genflow {

std::vector<Eigen::Index> read_reference_points(const std::filesystem::path& path,
                                                Eigen::Index vertex_count) {
    std::vector<Eigen::Index> vertices;
    detail::for_each_data_line(path, [&](const detail::DataLine& line) {
        std::int64_t index = 0;
        if (line.tokens.size() != 1 || !detail::parse_integer(line.tokens.front(), index)) {
            line.fail("expected one vertex index (1-based)");
        }
        if (index < 1 || index > vertex_count) {
            line.fail("vertex index " + std::to_string(index) + " outside 1.." +
                      std::to_string(vertex_count) + " (the file's indices are 1-based)");
        }
        vertices.push_back(static_cast<Eigen::Index>(index - 1));
    });
    if (vertices.empty()) {
        throw IoError(path.string() + ": no reference point");
    }
    return vertices;
}

}  // namespace genflow
