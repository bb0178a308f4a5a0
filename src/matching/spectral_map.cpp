// SPDX-License-Identifier: MIT
#include "genflow/matching/spectral_map.h"

#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "genflow/exceptions.h"
#include "genflow/matching/multiresolution.h"
#include "genflow/operators/laplacian_eigenbasis.h"
#include "genflow/operators/wave_kernel_signature.h"
#include "matching/functional_map.h"
#include "matching/functional_operators.h"
#include "operators/triangle.h"

namespace genflow {

namespace {

// One shape's spectral view at unit area: the eigenbasis (λ·A, φ·√A, m/A: M-orthonormal with
// total mass 1), its wave kernel signatures and the signed descriptors of their pairs, each of
// unit M-norm (so that every one weighs alike in the estimate).
struct Spectrum {
    LaplacianEigenbasis basis;
    Eigen::MatrixXd signatures;
    Eigen::MatrixXd descriptors;  // the signatures, then the signed descriptors
};

void normalize_columns(Eigen::MatrixXd& columns, const Eigen::VectorXd& masses) {
    for (Eigen::Index s = 0; s < columns.cols(); ++s) {
        const double norm = std::sqrt((masses.array() * columns.col(s).array().square()).sum());
        columns.col(s) /= norm > 0 ? norm : 1;
    }
}

Spectrum spectrum_of(const TriangleMesh& mesh, const SpectralMapOptions& options) {
    Spectrum spectrum{laplacian_eigenbasis(mesh, options.refined_size), {}, {}};
    LaplacianEigenbasis& basis = spectrum.basis;
    const double area = basis.masses.sum();
    basis.values *= area;
    basis.functions *= std::sqrt(area);
    basis.masses /= area;
    spectrum.signatures = wave_kernel_signature(basis, options.descriptors);
    normalize_columns(spectrum.signatures, basis.masses);
    const Eigen::MatrixXd smoothing =
        basis.functions.leftCols(std::min(options.smoothing_size, basis.functions.cols()));
    std::vector<Eigen::VectorXd> signed_descriptors;
    const std::vector<Eigen::Index>& bands = options.signed_bands;
    for (std::size_t a = 0; a < bands.size(); ++a) {
        for (std::size_t b = a + 1; b < bands.size(); ++b) {
            signed_descriptors.push_back(detail::signed_descriptor(
                mesh, smoothing, basis.masses, spectrum.signatures.col(bands[a]),
                spectrum.signatures.col(bands[b])));
        }
    }
    spectrum.descriptors.resize(
        mesh.V.rows(),
        spectrum.signatures.cols() + static_cast<Eigen::Index>(signed_descriptors.size()));
    spectrum.descriptors.leftCols(spectrum.signatures.cols()) = spectrum.signatures;
    for (std::size_t d = 0; d < signed_descriptors.size(); ++d) {
        spectrum.descriptors.col(spectrum.signatures.cols() + static_cast<Eigen::Index>(d)) =
            signed_descriptors[d];
    }
    normalize_columns(spectrum.descriptors, basis.masses);
    return spectrum;
}

// A pair of operators P (on `to`) and Q (on `from`) that the map C (pulling functions on `to`
// back to `from`) should commute with: C P = Q C.
struct OperatorPair {
    Eigen::MatrixXd to;
    Eigen::MatrixXd from;
};

// Both divided by the larger Frobenius norm, so that every pair weighs alike.
OperatorPair normalized(OperatorPair pair) {
    const double scale = std::max(pair.to.norm(), pair.from.norm());
    if (scale > 0) {
        pair.to /= scale;
        pair.from /= scale;
    }
    return pair;
}

// A functional map's energy as a quadratic form on vec(C) (column-major, k × k):
// vec(C)ᵀ H vec(C) − 2 gᵀ vec(C) + const. (X ⊗ Y) acts as vec(C) ↦ vec(Y C Xᵀ).
class MapEnergy {
public:
    explicit MapEnergy(Eigen::Index k)
        : k_(k), H_(Eigen::MatrixXd::Zero(k * k, k * k)), g_(Eigen::VectorXd::Zero(k * k)) {}

    // w ‖C B − A‖²: descriptors B (on `to`) pulled back onto A (on `from`).
    void add_descriptors(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double w) {
        add_kronecker(B * B.transpose(), Eigen::MatrixXd::Identity(k_, k_), w);
        g_ += w *
              Eigen::Map<const Eigen::VectorXd>(Eigen::MatrixXd(A * B.transpose()).data(), k_ * k_);
    }

    // w ‖C P − Q C‖² = w vec(C)ᵀ [(P Pᵀ ⊗ I) − (P ⊗ Q) − (Pᵀ ⊗ Qᵀ) + (I ⊗ QᵀQ)] vec(C).
    void add_commutator(const OperatorPair& pair, double w) {
        const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(k_, k_);
        add_kronecker(pair.to * pair.to.transpose(), I, w);
        add_kronecker(pair.to, pair.from, -w);
        add_kronecker(pair.to.transpose(), pair.from.transpose(), -w);
        add_kronecker(I, pair.from.transpose() * pair.from, w);
    }

    // w Σ mask_ij C_ij².
    void add_mask(const Eigen::MatrixXd& mask, double w) {
        for (Eigen::Index j = 0; j < k_; ++j) {
            for (Eigen::Index i = 0; i < k_; ++i) {
                H_(i + k_ * j, i + k_ * j) += w * mask(i, j);
            }
        }
    }

    // The minimizer with the first column of C fixed to `first_column` (a map takes the
    // constant function to the constant function).
    [[nodiscard]] Eigen::MatrixXd minimizer(const Eigen::VectorXd& first_column) const {
        const Eigen::Index n = k_ * k_;
        const Eigen::Index free = n - k_;
        const Eigen::VectorXd rhs = g_.tail(free) - H_.bottomLeftCorner(free, k_) * first_column;
        const Eigen::LDLT<Eigen::MatrixXd> solver(H_.bottomRightCorner(free, free));
        if (solver.info() != Eigen::Success || solver.isNegative()) {
            throw SolverError("spectral_map: the functional map's system is not positive definite");
        }
        Eigen::VectorXd c(n);
        c << first_column, solver.solve(rhs);
        return Eigen::Map<const Eigen::MatrixXd>(c.data(), k_, k_);
    }

private:
    void add_kronecker(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y, double w) {
        for (Eigen::Index j2 = 0; j2 < k_; ++j2) {
            for (Eigen::Index j1 = 0; j1 < k_; ++j1) {
                const double x = w * X(j1, j2);
                if (x != 0) {
                    H_.block(k_ * j1, k_ * j2, k_, k_) += x * Y;
                }
            }
        }
    }

    Eigen::Index k_;
    Eigen::MatrixXd H_;
    Eigen::VectorXd g_;
};

// Which of `count` descriptors enter the commutativity terms: `wanted` of them, evenly spread.
std::vector<Eigen::Index> operator_descriptors(Eigen::Index count, Eigen::Index wanted) {
    std::vector<Eigen::Index> chosen;
    wanted = std::min(wanted, count);
    for (Eigen::Index i = 0; i < wanted; ++i) {
        chosen.push_back(wanted > 1 ? i * (count - 1) / (wanted - 1) : count / 2);
    }
    return chosen;
}

// The functional map of the k lowest eigenfunctions that best preserves the descriptors and
// commutes with the Laplacian and the signatures' multiplication operators (Nogneng &
// Ovsjanikov 2017). Orientation operators stay out of this estimate: their commutators vanish
// at C = 0 as well, and weighted enough to matter they shrank the map instead of turning it
// (FAUST_r: 15 → 25 mean error × 100 at 10× Ren et al.'s balance); the signed descriptors
// carry the orientation into it instead.
Eigen::MatrixXd descriptor_map(const Spectrum& from, const Spectrum& to, Eigen::Index k,
                               const SpectralMapOptions& options) {
    const Eigen::MatrixXd phi = from.basis.functions.leftCols(k);
    const Eigen::MatrixXd psi = to.basis.functions.leftCols(k);
    const Eigen::MatrixXd A = phi.transpose() * from.basis.masses.asDiagonal() * from.descriptors;
    const Eigen::MatrixXd B = psi.transpose() * to.basis.masses.asDiagonal() * to.descriptors;
    MapEnergy energy(k);
    energy.add_descriptors(A, B, options.descriptor_weight);
    for (const Eigen::Index s :
         operator_descriptors(from.signatures.cols(), options.operator_descriptors)) {
        energy.add_commutator(
            normalized(
                {detail::multiplication_operator(psi, to.basis.masses, to.signatures.col(s)),
                 detail::multiplication_operator(phi, from.basis.masses, from.signatures.col(s))}),
            options.commutativity_weight);
    }
    Eigen::MatrixXd mask(k, k);
    for (Eigen::Index j = 0; j < k; ++j) {
        for (Eigen::Index i = 0; i < k; ++i) {
            mask(i, j) = std::pow(from.basis.values(i) - to.basis.values(j), 2);
        }
    }
    energy.add_mask(mask / std::max(mask.norm(), 1e-300), options.laplacian_weight);
    Eigen::VectorXd constant = Eigen::VectorXd::Zero(k);
    constant(0) = phi(0, 0) * psi(0, 0) > 0 ? 1 : -1;
    return energy.minimizer(constant);
}

// The orientation operators of the signatures, on both shapes, in the lowest k functions.
std::vector<OperatorPair> orientation_operators(const TriangleMesh& from_mesh, const Spectrum& from,
                                                const TriangleMesh& to_mesh, const Spectrum& to,
                                                Eigen::Index k, const SpectralMapOptions& options) {
    std::vector<OperatorPair> pairs;
    for (const Eigen::Index s :
         operator_descriptors(from.signatures.cols(), options.operator_descriptors)) {
        pairs.push_back(
            normalized({detail::orientation_operator(to_mesh, to.basis.functions.leftCols(k),
                                                     to.signatures.col(s)),
                        detail::orientation_operator(from_mesh, from.basis.functions.leftCols(k),
                                                     from.signatures.col(s))}));
    }
    return pairs;
}

// Σ‖C P − Q C‖² / Σ‖C P + Q C‖² (SpectralMap::orientation_ratio) for the map C fitted to
// `correspondence` in the operators' basis.
double orientation_ratio(const Spectrum& from, const Spectrum& to,
                         const std::vector<Eigen::Index>& correspondence,
                         const std::vector<OperatorPair>& operators) {
    const Eigen::Index k = operators.front().to.rows();
    const Eigen::MatrixXd C = detail::fitted_functional_map(from.basis.functions, from.basis.masses,
                                                            to.basis.functions, correspondence, k);
    double preserving = 0;
    double reversing = 0;
    for (const OperatorPair& pair : operators) {
        preserving += (C * pair.to - pair.from * C).squaredNorm();
        reversing += (C * pair.to + pair.from * C).squaredNorm();
    }
    return reversing > 0 ? preserving / reversing : 1;
}

void check_options(const SpectralMapOptions& options) {
    bool valid = !options.basis_sizes.empty() && options.descriptors >= 1 &&
                 options.operator_descriptors >= 1 && options.smoothing_size >= 1 &&
                 options.orientation_size >= 2 && options.vertices >= 100 &&
                 options.samples >= options.refined_size && options.descriptor_weight >= 0 &&
                 options.commutativity_weight >= 0 && options.laplacian_weight >= 0;
    for (const Eigen::Index k : options.basis_sizes) {
        valid = valid && k >= 2 && k <= options.refined_size;
    }
    for (const Eigen::Index band : options.signed_bands) {
        valid = valid && band >= 0 && band < options.descriptors;
    }
    if (!valid) {
        throw InvalidInput(
            "spectral_map: need basis_sizes in [2, refined_size], descriptors >= 1, "
            "operator_descriptors >= 1, signed_bands in [0, descriptors), smoothing_size >= 1, "
            "orientation_size >= 2, vertices >= 100, samples >= refined_size and weights >= 0");
    }
}

}  // namespace

namespace {

// Up to `count` vertices of `mesh`, spread over it (those its coarsening keeps), or all.
std::vector<Eigen::Index> spread_vertices(const TriangleMesh& mesh, Eigen::Index count) {
    if (mesh.V.rows() <= count) {
        std::vector<Eigen::Index> all(static_cast<std::size_t>(mesh.V.rows()));
        std::iota(all.begin(), all.end(), 0);
        return all;
    }
    return coarsen(mesh, count).fine_vertex;
}

// The orthogonal map nearest to the one fitted to `correspondence` (rows `samples` of `from`
// with the target vertices they map to), in the lowest `size` functions.
Eigen::MatrixXd orthogonal_fit(const Spectrum& from, const Spectrum& to,
                               const std::vector<Eigen::Index>& samples,
                               const std::vector<Eigen::Index>& correspondence, Eigen::Index size) {
    return detail::fitted_orthogonal_map(from.basis.functions(samples, Eigen::all),
                                         from.basis.masses(samples), to.basis.functions,
                                         correspondence, size);
}

// ZoomOut (Melzi et al. 2019) from the map C of the lowest k functions up to `refined`: its
// nearest-neighbour searches run from the template rows `samples` only (a few per function fit
// the map as well as all of them, at a fraction of the #V_from × #V_to cost), then the last map
// places every template vertex.
std::vector<Eigen::Index> zoomed_out(const Spectrum& from, const Spectrum& to,
                                     const Eigen::MatrixXd& C, Eigen::Index refined,
                                     const std::vector<Eigen::Index>& samples) {
    const Eigen::Index k = C.rows();
    const Eigen::MatrixXd sampled = from.basis.functions(samples, Eigen::seqN(0, refined));
    std::vector<Eigen::Index> correspondence =
        detail::nearest_rows(sampled.leftCols(k) * C, to.basis.functions.leftCols(k));
    correspondence = detail::zoom_out(
        sampled, from.basis.masses(samples), to.basis.functions.leftCols(refined),
        Eigen::RowVectorXd::Ones(refined), std::move(correspondence), k, refined, 5);
    return detail::nearest_rows(from.basis.functions.leftCols(refined) *
                                    orthogonal_fit(from, to, samples, correspondence, refined),
                                to.basis.functions.leftCols(refined));
}

// The map between the meshes as given (spectral_map() without the coarsening).
SpectralMap map_as_given(const TriangleMesh& from, const TriangleMesh& to,
                         const SpectralMapOptions& options) {
    const Spectrum from_spectrum = spectrum_of(from, options);
    const Spectrum to_spectrum = spectrum_of(to, options);
    const Eigen::Index refined =
        std::min(from_spectrum.basis.functions.cols(), to_spectrum.basis.functions.cols());
    const std::vector<OperatorPair> orientation = orientation_operators(
        from, from_spectrum, to, to_spectrum, std::min(options.orientation_size, refined), options);
    const std::vector<Eigen::Index> samples = spread_vertices(from, options.samples);
    SpectralMap best;
    best.orientation_ratio = std::numeric_limits<double>::infinity();
    for (const Eigen::Index size : options.basis_sizes) {
        const Eigen::Index k = std::min(size, refined);
        std::vector<Eigen::Index> correspondence =
            zoomed_out(from_spectrum, to_spectrum,
                       descriptor_map(from_spectrum, to_spectrum, k, options), refined, samples);
        const double ratio =
            orientation_ratio(from_spectrum, to_spectrum, correspondence, orientation);
        if (ratio < best.orientation_ratio) {
            best.target_vertex = std::move(correspondence);
            best.orientation_ratio = ratio;
            best.basis_size = k;
        }
        if (best.orientation_ratio < 1) {
            break;  // the first that preserves the orientation
        }
    }
    best.functional_map =
        detail::fitted_functional_map(from_spectrum.basis.functions, from_spectrum.basis.masses,
                                      to_spectrum.basis.functions, best.target_vertex, refined);
    return best;
}

// `mesh` coarsened to about `vertices` if it has more, else as it is (with the identity as
// its vertices' fine vertices).
CoarseMesh analysed(const TriangleMesh& mesh, Eigen::Index vertices) {
    if (mesh.V.rows() > vertices) {
        return coarsen(mesh, vertices);
    }
    CoarseMesh same{mesh, std::vector<Eigen::Index>(static_cast<std::size_t>(mesh.V.rows()))};
    std::iota(same.fine_vertex.begin(), same.fine_vertex.end(), 0);
    return same;
}

}  // namespace

SpectralMap spectral_map(const TriangleMesh& from, const TriangleMesh& to,
                         const SpectralMapOptions& options) {
    check_options(options);
    detail::require_valid_mesh(from, "spectral_map");
    detail::require_valid_mesh(to, "spectral_map");
    const CoarseMesh coarse_from = analysed(from, options.vertices);
    const CoarseMesh coarse_to = analysed(to, options.vertices);
    SpectralMap map = map_as_given(coarse_from.mesh, coarse_to.mesh, options);
    for (Eigen::Index& v : map.target_vertex) {
        v = coarse_to.fine_vertex[static_cast<std::size_t>(v)];
    }
    if (coarse_from.mesh.V.rows() == from.V.rows()) {
        return map;
    }
    const Embedding embedding = embed(from, coarse_from);
    std::vector<Eigen::Index> fine_map(static_cast<std::size_t>(from.V.rows()));
    for (Eigen::Index v = 0; v < from.V.rows(); ++v) {
        Eigen::Index corner = 0;
        embedding.barycentric.row(v).maxCoeff(&corner);
        fine_map[static_cast<std::size_t>(v)] = map.target_vertex[static_cast<std::size_t>(
            coarse_from.mesh.F(embedding.face(v), corner))];
    }
    map.target_vertex = std::move(fine_map);
    return map;
}

struct MapOrientation::Impl {
    Eigen::Index from_vertices;
    Eigen::Index to_vertices;
    Spectrum from;
    Spectrum to;
    std::vector<OperatorPair> operators;
};

MapOrientation::MapOrientation(const TriangleMesh& from, const TriangleMesh& to,
                               const SpectralMapOptions& options) {
    check_options(options);
    detail::require_valid_mesh(from, "orientation_ratio");
    detail::require_valid_mesh(to, "orientation_ratio");
    impl_ = std::make_unique<Impl>(
        Impl{from.V.rows(), to.V.rows(), spectrum_of(from, options), spectrum_of(to, options), {}});
    const Eigen::Index k = std::min({options.orientation_size, impl_->from.basis.functions.cols(),
                                     impl_->to.basis.functions.cols()});
    impl_->operators = orientation_operators(from, impl_->from, to, impl_->to, k, options);
}

MapOrientation::~MapOrientation() = default;
MapOrientation::MapOrientation(MapOrientation&&) noexcept = default;
MapOrientation& MapOrientation::operator=(MapOrientation&&) noexcept = default;

namespace {

// Refuses a `target_vertex` that is not a vertex of `to` (of `to_vertices`) per vertex of `from`.
void check_vertex_map(const std::vector<Eigen::Index>& target_vertex, Eigen::Index from_vertices,
                      Eigen::Index to_vertices) {
    if (static_cast<Eigen::Index>(target_vertex.size()) != from_vertices ||
        std::any_of(target_vertex.begin(), target_vertex.end(),
                    [&](Eigen::Index v) { return v < 0 || v >= to_vertices; })) {
        throw InvalidInput("orientation_ratio: need a vertex of `to` for each vertex of `from`");
    }
}

}  // namespace

double MapOrientation::ratio(const std::vector<Eigen::Index>& target_vertex) const {
    check_vertex_map(target_vertex, impl_->from_vertices, impl_->to_vertices);
    return orientation_ratio(impl_->from, impl_->to, target_vertex, impl_->operators);
}

double orientation_ratio(const TriangleMesh& from, const TriangleMesh& to,
                         const std::vector<Eigen::Index>& target_vertex,
                         const SpectralMapOptions& options) {
    check_vertex_map(target_vertex, from.V.rows(), to.V.rows());  // before the eigen-solves
    return MapOrientation(from, to, options).ratio(target_vertex);
}

}  // namespace genflow
