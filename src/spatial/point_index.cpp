// SPDX-License-Identifier: MIT
#include "spatial/point_index.h"

#include <limits>
#include <nanoflann.hpp>

namespace genflow::detail {

namespace {

// nanoflann's dataset interface over a row-major copy of the points.
struct PointCloud {
    std::vector<double> xyz;
    [[nodiscard]] std::size_t kdtree_get_point_count() const { return xyz.size() / 3; }
    [[nodiscard]] double kdtree_get_pt(std::size_t index, std::size_t dim) const {
        return xyz[3 * index + dim];
    }
    template <class BoundingBox>
    bool kdtree_get_bbox(BoundingBox& /*unused*/) const {
        return false;
    }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloud>,
                                                   PointCloud, 3, std::uint32_t>;

}  // namespace

struct PointIndex::Impl {
    PointCloud cloud;
    std::unique_ptr<KdTree> tree;
};

PointIndex::PointIndex(const Eigen::MatrixX3d& points) : impl_(std::make_unique<Impl>()) {
    impl_->cloud.xyz.resize(static_cast<std::size_t>(3 * points.rows()));
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
        for (int c = 0; c < 3; ++c) {
            impl_->cloud.xyz[static_cast<std::size_t>(3 * i + c)] = points(i, c);
        }
    }
    if (points.rows() > 0) {
        impl_->tree = std::make_unique<KdTree>(3, impl_->cloud,
                                               nanoflann::KDTreeSingleIndexAdaptorParams(16));
    }
}

PointIndex::~PointIndex() = default;
PointIndex::PointIndex(PointIndex&&) noexcept = default;
PointIndex& PointIndex::operator=(PointIndex&&) noexcept = default;

Eigen::Index PointIndex::size() const {
    return static_cast<Eigen::Index>(impl_->cloud.kdtree_get_point_count());
}

std::pair<std::int64_t, double> PointIndex::nearest(const Eigen::Vector3d& query) const {
    if (!impl_->tree) {
        return {-1, std::numeric_limits<double>::infinity()};
    }
    std::uint32_t index = 0;
    double distance_squared = 0;
    impl_->tree->knnSearch(query.data(), 1, &index, &distance_squared);
    return {index, distance_squared};
}

void PointIndex::nearest(const Eigen::Vector3d& query, std::size_t count,
                         std::vector<std::pair<std::uint32_t, double>>& found) const {
    found.clear();
    if (!impl_->tree || count == 0) {
        return;
    }
    std::vector<std::uint32_t> indices(count);
    std::vector<double> distances_squared(count);
    const std::size_t kept =
        impl_->tree->knnSearch(query.data(), count, indices.data(), distances_squared.data());
    for (std::size_t k = 0; k < kept; ++k) {
        found.emplace_back(indices[k], distances_squared[k]);
    }
}

void PointIndex::within(const Eigen::Vector3d& query, double radius_squared,
                        std::vector<std::pair<std::uint32_t, double>>& found) const {
    found.clear();
    if (impl_->tree) {
        impl_->tree->radiusSearch(query.data(), radius_squared, found,
                                  nanoflann::SearchParams(32, 0, false));
    }
}

}  // namespace genflow::detail
