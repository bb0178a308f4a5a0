// SPDX-License-Identifier: MIT
#include "cli_support.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "genflow/exceptions.h"
#include "genflow/io/atomic_file.h"
#include "genflow/io/read_mesh.h"
#include "genflow/io/read_points.h"
#include "genflow/io/write_mesh.h"
#include "genflow/matching/correspondence.h"
#include "genflow/mesh/repair.h"
#include "genflow/spatial/point_cloud_surface.h"
#include "number_checks.h"

namespace genflow::cli {

namespace {

// Validates the mesh read into `loaded`; throws IoError "<path>: <first validation error>".
void check_loaded(LoadedMesh& loaded) {
    loaded.report = validate(loaded.mesh);
    if (!loaded.report.ok()) {
        throw IoError(loaded.path.string() + ": " + loaded.report.first_error());
    }
}

}  // namespace

LoadedMesh load_mesh(const std::filesystem::path& path) {
    LoadedMesh loaded;
    loaded.path = path;
    loaded.mesh = read_mesh(path, &loaded.read_warnings, &loaded.attributes);
    check_loaded(loaded);
    return loaded;
}

VertexAttributes carried_attributes(const LoadedMesh& loaded, bool quiet) {
    VertexAttributes carried = loaded.attributes;
    if (carried.normals.rows() > 0) {
        carried.normals.resize(0, 3);
        if (!quiet) {
            std::cerr << "warning: " << printable(loaded.path.string())
                      << ": its vertex normals are left out (they describe the surface before "
                         "it moved)\n";
        }
    }
    return carried;
}

void write_mesh_with(const std::filesystem::path& path, const TriangleMesh& mesh,
                     const VertexAttributes& attributes, bool quiet) {
    std::vector<std::string> warnings;
    write_mesh(path, mesh, attributes, {}, &warnings);
    for (const std::string& warning : quiet ? std::vector<std::string>{} : warnings) {
        std::cerr << "warning: " << printable(warning) << '\n';
    }
}

LoadedMesh load_target(const std::filesystem::path& path) {
    LoadedMesh loaded;
    loaded.path = path;
    PointCloud cloud;
    if (is_xyz_file(path)) {
        cloud = read_points(path);
    } else {
        loaded.mesh = read_mesh(path, &loaded.read_warnings);
        if (loaded.mesh.F.rows() == 0) {
            cloud = read_points(path);  // again, for the normals a PLY may give its points
        }
    }
    if (cloud.points.rows() > 0) {
        loaded.points = cloud.points.rows();
        loaded.normals = cloud.normals.rows() > 0;
        try {
            loaded.mesh = point_cloud_surface(cloud.points, cloud.normals);
        } catch (const InvalidInput& error) {
            std::string problem = error.what();
            problem.erase(0, problem.find(": ") + 2);  // the function's name
            throw IoError(path.string() + ": a point cloud, but " + problem);
        }
        return loaded;  // a surface of our making: its oddities are not the file's
    }
    check_loaded(loaded);
    return loaded;
}

std::function<void(const MatchStage&)> stage_errors(const TriangleMesh& template_mesh,
                                                    const Eigen::MatrixX3d& truth, double diagonal,
                                                    nlohmann::json& stages) {
    // The stages' vertices are those of the template as match() repairs it (the input itself
    // unless it needed a repair); each stands for an input vertex, whose place `truth` gives.
    auto input_vertex = std::make_shared<const std::vector<Eigen::Index>>(
        repair_surface(template_mesh).source_vertex);
    return [input_vertex, &truth, diagonal, &stages](const MatchStage& stage) {
        const Eigen::MatrixX3d& V = stage.mesh->V;
        double sum = 0;
        for (Eigen::Index v = 0; v < V.rows(); ++v) {
            const Eigen::Index repaired = (*stage.template_vertex)[static_cast<std::size_t>(v)];
            sum +=
                (V.row(v) - truth.row((*input_vertex)[static_cast<std::size_t>(repaired)])).norm();
        }
        const double mean = V.rows() > 0 ? sum / static_cast<double>(V.rows()) : 0;
        stages.push_back({{"level", stage.level},
                          {"stage", std::string(stage.stage)},
                          {"vertices", V.rows()},
                          {"mean", mean / diagonal}});
    };
}

std::vector<std::pair<std::string, Eigen::VectorXd>> result_values(
    const TriangleMesh& deformed, const TriangleMesh& target,
    const Eigen::MatrixX3d* ground_truth) {
    const std::vector<SurfacePoint> nearest = closest_points(deformed.V, target);
    Eigen::VectorXd distance(deformed.V.rows());
    for (Eigen::Index i = 0; i < distance.size(); ++i) {
        distance[i] = nearest[static_cast<std::size_t>(i)].distance;
    }
    std::vector<std::pair<std::string, Eigen::VectorXd>> values{{"distance", distance}};
    if (ground_truth != nullptr) {
        values.emplace_back("error", (deformed.V - *ground_truth).rowwise().norm());
    }
    return values;
}

bool has_extension(const std::filesystem::path& path, std::string_view extension) {
    const std::string given = path.extension().string();
    return std::equal(given.begin(), given.end(), extension.begin(), extension.end(),
                      [](char a, char b) {
                          return std::tolower(static_cast<unsigned char>(a)) ==
                                 std::tolower(static_cast<unsigned char>(b));
                      });
}

void check_mesh_output(const std::string& path) {
    if (!is_writable_mesh_path(path)) {
        throw IoError(path +
                      ": cannot write this format (expected .obj, .ply, .off, .stl or .glb)");
    }
    check_output_path(path);
}

std::string printable(std::string_view text) {
    std::string result;
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (c == '\n') {
            result += "\\n";
        } else if (c == '\t') {
            result += "\\t";
        } else if (c == '\r') {
            result += "\\r";
        } else if (c == '\\') {
            result += "\\\\";
        } else if (byte < 0x20 || byte == 0x7f) {
            char escaped[5];
            std::snprintf(escaped, sizeof escaped, "\\x%02x", static_cast<unsigned>(byte));
            result += escaped;
        } else {
            result += c;
        }
    }
    return result;
}

void print_warnings(const LoadedMesh& loaded) {
    for (const auto& warning : loaded.read_warnings) {
        std::cerr << "warning: " << printable(warning) << '\n';
    }
    for (const auto& issue : loaded.report.issues) {
        if (issue.severity == Severity::Warning) {
            std::cerr << "warning: " << printable(loaded.path.string()) << ": " << issue.message
                      << '\n';
        }
    }
}

void create_output_directory(const std::filesystem::path& directory) {
    std::error_code error;
    std::filesystem::create_directories(directory, error);
    if (error) {
        throw OutputError(directory.string() + ": cannot create directory (" + error.message() +
                          ")");
    }
}

void add_second_opinion_option(CLI::App& command, double& threshold) {
    command
        .add_option("--second-opinion-above", threshold,
                    "Match the coarsest level also from an intrinsic start (extremities "
                    "matched by geodesic distances) and keep the result that disagrees less "
                    "with the target: 0 = always, side by side with the rigid starts; above 0, "
                    "only when the result's intrinsic disagreement is above this, after them "
                    "(0.35: the doubtful ones); inf = never")
        ->check(non_negative_or_infinity())
        ->capture_default_str();
}

namespace {

template <typename Number>
nlohmann::json number_or_null(const std::optional<Number>& value) {
    return value ? nlohmann::json(*value) : nlohmann::json();
}

}  // namespace

nlohmann::json match_choices(const MatchResult& result) {
    return {{"partial_target", result.partial_target},
            {"stretch_weight", result.stretch_weight},
            {"eigenfunction_guidance", result.eigenfunction_guidance},
            {"signature_fallback", result.signature_fallback},
            {"refinement_guidance", result.refinement_guidance},
            {"turned_parts", result.turned_parts},
            {"map_fits", result.map_fits},
            {"intrinsic_disagreement", number_or_null(result.intrinsic_disagreement)},
            {"doubtful", result.doubtful()},
            {"second_opinion", result.second_opinion},
            {"second_opinion_disagreement", number_or_null(result.second_opinion_disagreement)},
            {"alternative_starts", result.alternative_starts},
            {"alternative_start", result.alternative_start},
            {"swapped_limbs", result.swapped_limbs},
            {"signatures_reading", result.signatures_reading},
            {"first_commutativity", number_or_null(result.first_commutativity)},
            {"signatures_commutativity", number_or_null(result.signatures_commutativity)},
            {"first_orientation", number_or_null(result.first_orientation)},
            {"signatures_orientation", number_or_null(result.signatures_orientation)},
            {"counterparts_moved", number_or_null(result.counterparts_moved)},
            {"landmark_distance_over_diagonal", number_or_null(result.landmark_distance)}};
}

nlohmann::json stage_times_json(const MatchResult& result) {
    nlohmann::json times = nlohmann::json::array();
    for (const MatchStageTime& time : result.stage_times) {
        times.push_back({{"stage", time.stage},
                         {"seconds", time.seconds},
                         {"processor_seconds", time.processor_seconds}});
    }
    return times;
}

}  // namespace genflow::cli
