// SPDX-License-Identifier: MIT
// Nearest-neighbour and radius queries over a fixed set of 3D points (nanoflann's kd-tree,
// hidden behind PImpl so that its API changes never reach other files).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace genflow::detail {

class PointIndex {
public:
    /// Indexes the rows of `points` (#P×3), copied; an empty set is allowed (queries then find
    /// nothing).
    explicit PointIndex(const Eigen::MatrixX3d& points);
    ~PointIndex();
    PointIndex(PointIndex&&) noexcept;
    PointIndex& operator=(PointIndex&&) noexcept;

    /// The nearest point to `query`: (index, squared distance); (-1, inf) when empty.
    [[nodiscard]] std::pair<std::int64_t, double> nearest(const Eigen::Vector3d& query) const;

    /// The `count` nearest points to `query` (fewer if the set is smaller), nearest first, as
    /// (index, squared distance), into `found` (cleared first).
    void nearest(const Eigen::Vector3d& query, std::size_t count,
                 std::vector<std::pair<std::uint32_t, double>>& found) const;

    /// All points with squared distance ≤ `radius_squared`, as (index, squared distance),
    /// unsorted, into `found` (cleared first).
    void within(const Eigen::Vector3d& query, double radius_squared,
                std::vector<std::pair<std::uint32_t, double>>& found) const;

    [[nodiscard]] Eigen::Index size() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace genflow::detail
