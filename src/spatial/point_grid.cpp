// SPDX-License-Identifier: MIT
#include "spatial/point_grid.h"

namespace genflow::detail {

void PointGrid::rebuild(const Eigen::MatrixX3d& points, const Eigen::VectorXd& weights,
                        const Eigen::VectorXd& factors, double cell_size) {
    const auto count = static_cast<std::size_t>(points.rows());
    x_.resize(count);
    y_.resize(count);
    z_.resize(count);
    weight_.resize(count);
    factor_.resize(count);
    id_.resize(count);
    if (count == 0) {
        cell_ = inverse_cell_ = 1;
        origin_.setZero();
        dims_ = {1, 1, 1};
        start_.assign(2, 0);
        prefix_weight_.assign(8, 0.0);
        return;
    }
    origin_ = points.colwise().minCoeff().transpose();
    const Eigen::Vector3d extent = points.colwise().maxCoeff().transpose() - origin_;
    // Enlarge the cells until the dense table stays linear in the number of points (an
    // elongated or sparse set would otherwise need cubically many empty cells).
    const double limit = 4.0 * static_cast<double>(count) + 64;
    cell_ = std::max(cell_size, 1e-300);
    const auto cells_along = [&](int a) { return std::floor(extent[a] / cell_) + 1; };
    while (cells_along(0) * cells_along(1) * cells_along(2) > limit) {
        cell_ *= 1.25;
    }
    inverse_cell_ = 1 / cell_;
    for (int a = 0; a < 3; ++a) {
        dims_[static_cast<std::size_t>(a)] = static_cast<std::int64_t>(cells_along(a));
    }

    // Counting sort of the points by cell.
    cell_of_.resize(count);
    start_.assign(static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2] + 1), 0);
    for (std::size_t i = 0; i < count; ++i) {
        std::array<std::int64_t, 3> c{};
        for (int a = 0; a < 3; ++a) {
            c[static_cast<std::size_t>(a)] = std::min<std::int64_t>(
                static_cast<std::int64_t>((points(static_cast<Eigen::Index>(i), a) - origin_[a]) *
                                          inverse_cell_),
                dims_[static_cast<std::size_t>(a)] - 1);
        }
        cell_of_[i] = static_cast<std::uint32_t>((c[2] * dims_[1] + c[1]) * dims_[0] + c[0]);
        ++start_[cell_of_[i] + 1];
    }
    for (std::size_t c = 1; c < start_.size(); ++c) {
        start_[c] += start_[c - 1];
    }
    next_slot_.assign(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint32_t slot = next_slot_[cell_of_[i]]++;
        const auto row = static_cast<Eigen::Index>(i);
        x_[slot] = points(row, 0);
        y_[slot] = points(row, 1);
        z_[slot] = points(row, 2);
        weight_[slot] = weights[row];
        factor_[slot] = factors[row];
        id_[slot] = static_cast<std::uint32_t>(i);
    }
    build_prefix_weights(weights);
}

void PointGrid::build_prefix_weights(const Eigen::VectorXd& weights) {
    const auto nx = static_cast<std::size_t>(dims_[0] + 1);
    const auto ny = static_cast<std::size_t>(dims_[1] + 1);
    const auto nz = static_cast<std::size_t>(dims_[2] + 1);
    const auto index = [&](std::size_t x, std::size_t y, std::size_t z) {
        return (z * ny + y) * nx + x;
    };
    prefix_weight_.assign(nx * ny * nz, 0.0);
    const auto cells_x = static_cast<std::uint32_t>(dims_[0]);
    const auto cells_y = static_cast<std::uint32_t>(dims_[1]);
    for (std::size_t i = 0; i < cell_of_.size(); ++i) {
        const std::uint32_t cell = cell_of_[i];
        prefix_weight_[index(cell % cells_x + 1, cell / cells_x % cells_y + 1,
                             cell / (cells_x * cells_y) + 1)] +=
            weights[static_cast<Eigen::Index>(i)];
    }
    // Running sums along x, then y, then z.
    const std::array<std::size_t, 3> stride{1, nx, nx * ny};
    for (const std::size_t step : stride) {
        for (std::size_t z = 1; z < nz; ++z) {
            for (std::size_t y = 1; y < ny; ++y) {
                for (std::size_t x = 1; x < nx; ++x) {
                    const std::size_t here = index(x, y, z);
                    prefix_weight_[here] += prefix_weight_[here - step];
                }
            }
        }
    }
}

}  // namespace genflow::detail
