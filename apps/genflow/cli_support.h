// SPDX-License-Identifier: MIT
// What every genflow subcommand shares: loading a mesh the way the CLI promises (read,
// validate, refuse with one line), and the exception that carries an exit code.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "genflow/io/vertex_attributes.h"
#include "genflow/matching/match.h"
#include "genflow/mesh.h"
#include "genflow/mesh/validate.h"

namespace genflow::cli {

/// Exit codes of the genflow tool (documented in docs/cli.md).
enum ExitCode : int {
    kSuccess = 0,
    kFailure = 1,   ///< the computation failed (solver, output not writable)
    kBadInput = 2,  ///< an input file or an argument was refused
};

/// Thrown by a command that ran to its end but some of whose work failed, as its output has
/// said (a batch with failed targets): main() exits with kFailure and prints nothing more.
struct SomeWorkFailed {};

/// A mesh read by the CLI, with everything that was noticed on the way.
struct LoadedMesh {
    std::filesystem::path path;
    TriangleMesh mesh;
    std::vector<std::string> read_warnings;
    ValidationReport report;
    /// Where the file held points only: how many; `mesh` is then point_cloud_surface()'s.
    Eigen::Index points = 0;
    bool normals = false;  ///< whether the point cloud came with its normals
    /// What the file gives per vertex beside positions (a PLY's normals, colours and values, an
    /// OBJ's colours).
    VertexAttributes attributes;
};

/// Reads and validates `path`. Throws IoError "<path>: <first validation error>" if the mesh
/// has an error that no genflow algorithm can handle.
LoadedMesh load_mesh(const std::filesystem::path& path);

/// A target: a mesh as load_mesh() reads it, or a point cloud (an .xyz file, or a mesh file
/// without faces) made a surface on its points by point_cloud_surface().
LoadedMesh load_target(const std::filesystem::path& path);

/// `text` safe to print on a terminal as one line: control characters (a newline or an escape
/// sequence in a file's name) written as \n, \t, \r, \\ or \xNN; other bytes (UTF-8) kept.
[[nodiscard]] std::string printable(std::string_view text);

/// Prints "warning: <line>" on stderr for each reader warning and each validation warning.
void print_warnings(const LoadedMesh& loaded);

/// A MatchOptions::stages callback that appends to `stages`, per stage of each level, its
/// "level", "stage", "vertices" and "mean": the mean distance of the level's vertices from where
/// `truth` (a row per vertex of `template_mesh`, placed) has them, over `diagonal`.
std::function<void(const MatchStage&)> stage_errors(const TriangleMesh& template_mesh,
                                                    const Eigen::MatrixX3d& truth, double diagonal,
                                                    nlohmann::json& stages);

/// The attributes of `loaded` that go with its vertices wherever they move (colours and
/// values), for the output of a smoothing or a match. Its normals would describe the surface
/// before the move: they are left out, with a warning on stderr unless `quiet`.
[[nodiscard]] VertexAttributes carried_attributes(const LoadedMesh& loaded, bool quiet);

/// write_mesh() with `attributes`, its warnings (what the format cannot hold) on stderr unless
/// `quiet`.
void write_mesh_with(const std::filesystem::path& path, const TriangleMesh& mesh,
                     const VertexAttributes& attributes, bool quiet);

/// A match's values per vertex of its deformed template, written with it: "distance" to the
/// target's surface and, given the ground truth (the template's vertices, placed), "error",
/// the distance from where the vertex belongs; both as lengths.
[[nodiscard]] std::vector<std::pair<std::string, Eigen::VectorXd>> result_values(
    const TriangleMesh& deformed, const TriangleMesh& target, const Eigen::MatrixX3d* ground_truth);

/// Whether `path` ends in `extension` (".glb"), in any case: a file's kind is its extension's,
/// however it is spelled.
[[nodiscard]] bool has_extension(const std::filesystem::path& path, std::string_view extension);

/// Checks a mesh output before any work: a format genflow writes (IoError "<path>: cannot write
/// this format ...") and a place it can be written (check_output_path()).
void check_mesh_output(const std::string& path);

/// Creates `directory` (and its parents) for --frames, --output-dir and the like; throws
/// OutputError naming it on failure.
void create_output_directory(const std::filesystem::path& directory);

/// `--second-opinion-above X` (MatchOptions::second_opinion), shared by match and eval.
void add_second_opinion_option(CLI::App& command, double& threshold);

/// What a match chose on its way (the stiffness, guidances, starts, fits and exchanges kept, and
/// the intrinsic disagreements; null where a measure was not taken), as match, eval and
/// benchmark report it.
[[nodiscard]] nlohmann::json match_choices(const MatchResult& result);

/// MatchResult::stage_times as an array of {stage, seconds, processor_seconds}, in their order.
[[nodiscard]] nlohmann::json stage_times_json(const MatchResult& result);

}  // namespace genflow::cli
