// SPDX-License-Identifier: MIT
// Writes copies of the pairs of a pairs.json whose targets are moved by random similarities, so
// that `genflow eval` can check issue 5's "inputs may differ by any rigid motion and scale":
// each copy's remeshed (or simplified) target and its ground truth are turned by a uniformly
// random rotation, scaled by a log-uniform factor (10^-3 to 10^3 unless --scales says
// otherwise) and moved; the template is left as it is. The meshes go to OUT_DIR, with
// OUT_DIR/pairs.json naming them by absolute paths (the templates and part files too), so the
// data directory is only read, never copied into. A scanned target is also noisy and may be
// sampled more sparsely than the template: --noise moves each target vertex along its normal by
// a Gaussian of that standard deviation (a fraction of the diagonal), and --share takes as the
// target the ground truth simplified to that share of its vertices (as "target_simplified"
// does in `genflow eval`); the ground truth stays clean, so the error is still to the true
// places.
//
// Usage: similar_pairs PAIRS.json OUT_DIR [--copies K] [--seed S] [--scales LOG10_SPREAD]
//                      [--noise SIGMA] [--share SHARE] [--pairs NAME,NAME...]
// Then: genflow eval OUT_DIR/pairs.json --priors h1 --json
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>

#include "genflow/io/read_mesh.h"
#include "genflow/io/write_mesh.h"
#include "genflow/matching/multiresolution.h"
#include "genflow/matching/rigid_alignment.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/operators/normals.h"

namespace {

namespace fs = std::filesystem;

// A rotation drawn uniformly (a normalized Gaussian quaternion), a scale 10^u with u uniform in
// [-spread, spread], and a translation of up to the scaled diagonal.
genflow::Similarity random_similarity(std::mt19937_64& generator, double spread, double diagonal) {
    std::normal_distribution<double> gaussian;
    Eigen::Quaterniond turn(gaussian(generator), gaussian(generator), gaussian(generator),
                            gaussian(generator));
    turn.normalize();
    std::uniform_real_distribution<double> exponent(-spread, spread);
    std::uniform_real_distribution<double> offset(-1, 1);
    genflow::Similarity motion;
    motion.rotation = turn.toRotationMatrix();
    motion.scale = std::pow(10.0, exponent(generator));
    motion.translation = motion.scale * diagonal *
                         Eigen::Vector3d(offset(generator), offset(generator), offset(generator));
    return motion;
}

// The pair's target before it is moved: the ground truth simplified to `share` of its vertices
// when that is given (else to the pair's own "target_simplified"), else its remeshed target.
// Empty when the pair's file names no target and no share is given (eval simplifies it then).
std::optional<genflow::TriangleMesh> unmoved_target(const nlohmann::json& pair,
                                                    const fs::path& base,
                                                    const genflow::TriangleMesh& truth,
                                                    std::optional<double> share) {
    if (!share && pair.contains("target_simplified")) {
        share = pair.at("target_simplified").get<double>();
    }
    if (share) {
        return genflow::coarsen_to_share(truth, *share).mesh;
    }
    if (pair.contains("target_remeshed")) {
        return genflow::read_mesh(base / pair.at("target_remeshed").get<std::string>());
    }
    return std::nullopt;
}

// `mesh` with each vertex moved along its normal by a Gaussian of deviation `sigma`.
genflow::TriangleMesh with_noise(genflow::TriangleMesh mesh, double sigma,
                                 std::mt19937_64& generator) {
    std::normal_distribution<double> gaussian(0, sigma);
    const Eigen::MatrixX3d normals = genflow::vertex_normals(mesh);
    for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
        mesh.V.row(v) += gaussian(generator) * normals.row(v);
    }
    return mesh;
}

std::set<std::string> split(const std::string& list) {
    std::set<std::string> names;
    std::stringstream stream(list);
    for (std::string name; std::getline(stream, name, ',');) {
        names.insert(name);
    }
    return names;
}

int run(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr,
                     "usage: similar_pairs PAIRS.json OUT_DIR [--copies K] [--seed S] "
                     "[--scales LOG10_SPREAD] [--noise SIGMA] [--share SHARE] "
                     "[--pairs NAME,...]\n");
        return 2;
    }
    const fs::path pairs_file = fs::absolute(argv[1]);
    const fs::path out = fs::absolute(argv[2]);
    int copies = 3;
    unsigned long long seed = 1;
    double spread = 3;
    double noise = 0;
    std::optional<double> share;
    std::set<std::string> only;
    for (int i = 3; i + 1 < argc; i += 2) {
        const std::string flag = argv[i];
        if (flag == "--copies") {
            copies = std::stoi(argv[i + 1]);
        } else if (flag == "--seed") {
            seed = std::stoull(argv[i + 1]);
        } else if (flag == "--scales") {
            spread = std::stod(argv[i + 1]);
        } else if (flag == "--noise") {
            noise = std::stod(argv[i + 1]);
            if (!(noise >= 0)) {
                std::fprintf(stderr, "similar_pairs: --noise must be at least 0\n");
                return 2;
            }
        } else if (flag == "--share") {
            share = std::stod(argv[i + 1]);
            if (!(*share > 0 && *share <= 1)) {
                std::fprintf(stderr, "similar_pairs: --share must be in (0, 1]\n");
                return 2;
            }
        } else if (flag == "--pairs") {
            only = split(argv[i + 1]);
        } else {
            std::fprintf(stderr, "similar_pairs: unknown option %s\n", flag.c_str());
            return 2;
        }
    }
    std::ifstream stream(pairs_file);
    if (!stream) {
        std::fprintf(stderr, "similar_pairs: cannot open %s\n", pairs_file.c_str());
        return 2;
    }
    const nlohmann::json pairs = nlohmann::json::parse(stream);
    const fs::path base = pairs_file.parent_path();
    fs::create_directories(out);
    std::mt19937_64 generator(seed);
    nlohmann::json written = nlohmann::json::array();
    for (const auto& pair : pairs) {
        const auto name = pair.at("name").get<std::string>();
        if (!only.empty() && only.count(name) == 0) {
            continue;
        }
        const genflow::TriangleMesh truth =
            genflow::read_mesh(base / pair.at("target_ground_truth").get<std::string>());
        const double diagonal = genflow::bounding_box_diagonal(truth);
        // Written as the copy's own target when it differs from what eval would make of it.
        const bool own_target = share || noise > 0 || pair.contains("target_remeshed");
        const std::optional<genflow::TriangleMesh> target =
            own_target ? unmoved_target(pair, base, truth, share) : std::nullopt;
        for (int copy = 0; copy < copies; ++copy) {
            const genflow::Similarity motion = random_similarity(generator, spread, diagonal);
            const std::string stem = name + "_similar" + std::to_string(copy);
            nlohmann::json entry = pair;
            entry["name"] = stem;
            for (const char* key : {"template", "template_parts", "template_parts_pose",
                                    "template_part_labels", "template_part_weights"}) {
                if (pair.contains(key)) {
                    entry[key] = (base / pair.at(key).get<std::string>()).string();
                }
            }
            genflow::TriangleMesh moved = truth;
            moved.V = motion.apply(truth.V);
            entry["target_ground_truth"] = (out / (stem + "_truth.ply")).string();
            genflow::write_mesh(entry["target_ground_truth"].get<std::string>(), moved);
            if (target) {
                moved = noise > 0 ? with_noise(*target, noise * diagonal, generator) : *target;
                moved.V = motion.apply(moved.V);
                entry.erase("target_simplified");
                entry["target_remeshed"] = (out / (stem + "_target.ply")).string();
                genflow::write_mesh(entry["target_remeshed"].get<std::string>(), moved);
            }
            const double degrees =
                Eigen::AngleAxisd(motion.rotation).angle() * 180 / std::numbers::pi;
            const Eigen::Quaterniond turn(motion.rotation);
            entry["similarity"] = {
                {"scale", motion.scale},
                {"rotation_degrees", degrees},
                {"rotation_quaternion_wxyz", {turn.w(), turn.x(), turn.y(), turn.z()}},
                {"translation",
                 {motion.translation.x(), motion.translation.y(), motion.translation.z()}}};
            if (noise > 0) {
                entry["target_noise"] = noise;
            }
            if (share) {
                entry["target_share"] = *share;
            }
            written.push_back(entry);
            std::printf("%s: scale %.4g, turned %.1f degrees\n", stem.c_str(), motion.scale,
                        degrees);
        }
    }
    std::ofstream(out / "pairs.json") << written.dump(1) << "\n";
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "similar_pairs: %s\n", error.what());
        return 1;
    }
}
