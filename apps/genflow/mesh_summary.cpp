// SPDX-License-Identifier: MIT
#include "mesh_summary.h"

#include <sstream>

#include "genflow/operators/area.h"
#include "genflow/operators/mesh_size.h"
#include "genflow/operators/volume.h"

namespace genflow::cli {

namespace {

struct Measures {
    double area;
    double volume;
    double bbox_diagonal;
    double mean_edge;
    Eigen::RowVector3d bbox_min;
    Eigen::RowVector3d bbox_max;
};

Measures measure(const TriangleMesh& mesh) {
    return {surface_area(mesh),     enclosed_volume(mesh),       bounding_box_diagonal(mesh),
            mean_edge_length(mesh), mesh.V.colwise().minCoeff(), mesh.V.colwise().maxCoeff()};
}

std::string topology_words(const ValidationReport& r) {
    std::string words = r.closed() ? "closed" : "open";
    words += r.manifold() ? " manifold" : " non-manifold";
    if (r.inconsistent_orientation_edges > 0) {
        words += ", inconsistently oriented";
    }
    return words;
}

// Where the file's texture coordinates are: "per vertex", "per corner" or null.
nlohmann::json texture_json(const VertexAttributes& attributes) {
    if (attributes.corner_uv_faces.rows() > 0) {
        return "per corner";
    }
    return attributes.uvs.rows() > 0 ? nlohmann::json("per vertex") : nlohmann::json(nullptr);
}

// What the file gives per vertex: {"normals", "colors", "values": [names],
// "texture_coordinates"}.
nlohmann::json attributes_json(const VertexAttributes& attributes) {
    nlohmann::json names = nlohmann::json::array();
    for (const auto& [name, values] : attributes.scalars) {
        names.push_back(name);
    }
    return {{"normals", attributes.normals.rows() > 0},
            {"colors", attributes.colors.rows() > 0},
            {"values", names},
            {"texture_coordinates", texture_json(attributes)}};
}

// The same as words: "normals, colours, quality".
std::string attribute_words(const VertexAttributes& attributes) {
    std::string words;
    const auto add = [&](const std::string& word) { words += (words.empty() ? "" : ", ") + word; };
    if (attributes.normals.rows() > 0) {
        add("normals");
    }
    if (attributes.colors.rows() > 0) {
        add("colours");
    }
    for (const auto& [name, values] : attributes.scalars) {
        add(name);
    }
    if (attributes.uvs.rows() > 0) {
        add("texture coordinates");
    }
    return words;
}

}  // namespace

nlohmann::json mesh_summary_json(const LoadedMesh& loaded) {
    const auto& r = loaded.report;
    const Measures m = measure(loaded.mesh);
    nlohmann::json issues = nlohmann::json::array();
    for (const auto& issue : r.issues) {
        issues.push_back({{"severity", issue.severity == Severity::Error ? "error" : "warning"},
                          {"message", issue.message}});
    }
    return {
        {"file", loaded.path.string()},
        {"vertices", r.num_vertices},
        {"faces", r.num_faces},
        {"edges", r.num_edges},
        {"components", r.components},
        {"boundary_loops", r.boundary_loops},
        {"euler_characteristic", r.euler_characteristic},
        {"genus", r.genus ? nlohmann::json(*r.genus) : nlohmann::json(nullptr)},
        {"closed", r.closed()},
        {"manifold", r.manifold()},
        {"consistently_oriented", r.inconsistent_orientation_edges == 0},
        {"inward_oriented", r.inward_oriented},
        {"area", m.area},
        {"volume", m.volume},
        {"bbox_min", {m.bbox_min[0], m.bbox_min[1], m.bbox_min[2]}},
        {"bbox_max", {m.bbox_max[0], m.bbox_max[1], m.bbox_max[2]}},
        {"bbox_diagonal", m.bbox_diagonal},
        {"mean_edge_length", m.mean_edge},
        {"validation",
         {{"non_finite_vertices", r.non_finite_vertices},
          {"out_of_range_faces", r.out_of_range_faces},
          {"repeated_index_faces", r.repeated_index_faces},
          {"zero_area_faces", r.zero_area_faces},
          {"sliver_faces", r.sliver_faces},
          {"duplicate_faces", r.duplicate_faces},
          {"non_manifold_edges", r.non_manifold_edges},
          {"non_manifold_vertices", r.non_manifold_vertices},
          {"boundary_edges", r.boundary_edges},
          {"inconsistent_orientation_edges", r.inconsistent_orientation_edges},
          {"unreferenced_vertices", r.unreferenced_vertices},
          {"issues", issues}}},
        {"read_warnings", loaded.read_warnings},
        {"vertex_attributes", attributes_json(loaded.attributes)},
    };
}

std::string mesh_summary_text(const LoadedMesh& loaded) {
    const auto& r = loaded.report;
    const Measures m = measure(loaded.mesh);
    std::ostringstream out;
    out.precision(6);
    out << loaded.path.string() << '\n'
        << "  vertices " << r.num_vertices << ", faces " << r.num_faces << ", edges " << r.num_edges
        << '\n'
        << "  " << topology_words(r) << ", " << r.components << " component(s), "
        << r.boundary_loops << " boundary loop(s), genus "
        << (r.genus ? std::to_string(*r.genus) : std::string("undefined")) << '\n'
        << "  area " << m.area << ", volume " << m.volume
        << (r.closed() ? "" : " (open surface: not a volume)") << '\n'
        << "  bbox diagonal " << m.bbox_diagonal << ", mean edge length " << m.mean_edge << '\n';
    if (const std::string words = attribute_words(loaded.attributes); !words.empty()) {
        out << "  per vertex: " << words << '\n';
    }
    if (loaded.attributes.corner_uv_faces.rows() > 0) {
        out << "  per face corner: texture coordinates\n";
    }
    return out.str();
}

}  // namespace genflow::cli
