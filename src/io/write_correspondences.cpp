// SPDX-License-Identifier: MIT
#include "genflow/io/write_correspondences.h"

#include <cstdio>
#include <string>

#include "genflow/io/atomic_file.h"

namespace genflow {

void write_correspondences(const std::filesystem::path& path,
                           const std::vector<SurfacePoint>& correspondences) {
    std::string text =
        "# genflow correspondences: line i = template vertex i (0-based)\n"
        "# columns: target_face b0 b1 b2 distance (barycentric on the face's corners 0, 1, 2)\n";
    text.reserve(text.size() + 80 * correspondences.size());
    char line[160];
    for (const SurfacePoint& p : correspondences) {
        const int length =
            std::snprintf(line, sizeof line, "%ld %.9g %.9g %.9g %.9g\n", static_cast<long>(p.face),
                          p.barycentric[0], p.barycentric[1], p.barycentric[2], p.distance);
        text.append(line, static_cast<std::size_t>(length));
    }
    write_file_atomically(path, text);
}

}  // namespace genflow
