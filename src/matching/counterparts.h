// SPDX-License-Identifier: MIT
// Each template vertex's counterpart on the target (MatchOptions::counterparts): among the
// target's points near where the match put the vertex, the one an intrinsic map agrees with.
//
// The closest point of the target is the counterpart only where one part of the target is
// near: where two parts touch or pass close (a finger beside the next, a hand on a thigh) a
// vertex that lies a little off its own part is nearer to the other one, and d_H cannot tell.
// The Laplacian eigenfunctions can (the two parts are far apart along the surface). So the
// correspondence is refined as in ZoomOut (Melzi et al. 2019), each vertex's counterpart being
// its nearest neighbour in the eigenfunctions and the positions together: a functional map C is
// fitted to the current correspondence, and each vertex goes to the target vertex closest to
// (φ C, w p) among (ψ, w y), p where the match put it and y the target's vertices.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "genflow/matching/match.h"
#include "genflow/mesh.h"
#include "genflow/operators/laplacian_eigenbasis.h"
#include "spatial/point_index.h"

namespace genflow::detail {

/// The counterparts where the stage does not run: per row of `deformed`, the closest point of
/// `target`'s surface.
[[nodiscard]] Eigen::MatrixX3d closest_counterparts(const Eigen::MatrixX3d& deformed,
                                                    const TriangleMesh& target);

/// Points of a joint embedding (f, w x): functions f (a row per point) and positions x, whose
/// weight w the search takes.
struct JointEmbedding {
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> functions;
    const Eigen::MatrixX3d& positions;
};

/// Per row of `queries`, the nearest row of `targets` in the joint embedding (the first of
/// equals), as a search of every target row finds it, but looking only near the query's
/// position: `index` holds `targets.positions`, and `previous` (a target row per query, any)
/// bounds the search.
/// \throws InvalidInput if `weight` is not positive and finite.
[[nodiscard]] std::vector<Eigen::Index> nearest_in_joint_embedding(
    const JointEmbedding& queries, const JointEmbedding& targets, double weight,
    const PointIndex& index, const std::vector<Eigen::Index>& previous);

struct Counterparts {
    Eigen::MatrixX3d points;  ///< per template vertex, its counterpart: a vertex of the target
    Eigen::Index moved = 0;   ///< how many are not the corner nearest to the closest point
};

/// The counterparts of the template's vertices on `target`, per row of `deformed` (the template
/// as the match put it). `template_basis` and `target_basis` are the two surfaces' lowest
/// eigenpairs, the same count, at least 2.
/// \throws InvalidInput if the bases do not fit the meshes or `options.reach` is not positive.
[[nodiscard]] Counterparts intrinsic_counterparts(const LaplacianEigenbasis& template_basis,
                                                  const LaplacianEigenbasis& target_basis,
                                                  const TriangleMesh& target,
                                                  const Eigen::MatrixX3d& deformed,
                                                  const CounterpartOptions& options);

}  // namespace genflow::detail
