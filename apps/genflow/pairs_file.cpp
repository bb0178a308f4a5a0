// SPDX-License-Identifier: MIT
#include "pairs_file.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <set>

#include "genflow/exceptions.h"
#include "genflow/io/read_file.h"

namespace genflow::cli {

namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& problem) {
    throw IoError(file.string() + ": " + problem);
}

std::optional<std::string> optional_string(const std::filesystem::path& file, const json& pair,
                                           const std::string& where, const char* key) {
    const auto value = pair.find(key);
    if (value == pair.end()) {
        return std::nullopt;
    }
    if (!value->is_string()) {
        fail(file, where + ": \"" + key + "\" must be a string");
    }
    return value->get<std::string>();
}

std::string string_field(const std::filesystem::path& file, const json& pair,
                         const std::string& where, const char* key) {
    std::optional<std::string> value = optional_string(file, pair, where, key);
    if (!value) {
        fail(file, where + " lacks the string \"" + key + "\"");
    }
    return *value;
}

// A pair's name names its files in --output-dir and rows of the printed table: a plain file
// name, so that no pairs file can write outside that directory (no "..", no separator, not
// absolute, not hidden) or drive the terminal.
std::string plain_name(const std::filesystem::path& file, const json& pair, std::size_t index) {
    std::string name = string_field(file, pair, "pair " + std::to_string(index + 1), "name");
    const bool control = std::any_of(name.begin(), name.end(), [](char c) {
        return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
    });
    if (name.empty() || name.front() == '.' || name.find('/') != std::string::npos || control) {
        fail(file,
             "a pair's name must be a plain file name (no '/', not starting with '.', no "
             "control character), got \"" +
                 name + "\"");
    }
    return name;
}

std::optional<PartFiles> part_files(const std::filesystem::path& file,
                                    const std::filesystem::path& base, const json& pair,
                                    const std::string& where, const std::string& template_name) {
    const std::optional<std::string> tree = optional_string(file, pair, where, "template_parts");
    if (!tree) {
        return std::nullopt;
    }
    PartFiles files{base / *tree};
    files.template_name = std::filesystem::path(template_name).stem().string();
    files.pose = optional_string(file, pair, where, "template_parts_pose").value_or("");
    if (const auto labels = optional_string(file, pair, where, "template_part_labels")) {
        files.labels = base / *labels;
    }
    if (const auto weights = optional_string(file, pair, where, "template_part_weights")) {
        files.weights = base / *weights;
    }
    return files;
}

EvalPair read_pair(const std::filesystem::path& file, const std::filesystem::path& base,
                   const json& pair, std::size_t index) {
    if (!pair.is_object()) {
        fail(file, "pair " + std::to_string(index + 1) + " is not a JSON object");
    }
    EvalPair result;
    result.name = plain_name(file, pair, index);
    const std::string where = "pair " + result.name;
    const std::string template_name = string_field(file, pair, where, "template");
    result.template_mesh = base / template_name;
    result.ground_truth = base / string_field(file, pair, where, "target_ground_truth");
    if (const auto remeshed = optional_string(file, pair, where, "target_remeshed")) {
        result.target_remeshed = base / *remeshed;
    } else if (const auto share = pair.find("target_simplified"); share != pair.end()) {
        if (!share->is_number() || !(share->get<double>() > 0 && share->get<double>() <= 1)) {
            fail(file, where + ": \"target_simplified\" must be a share of the vertices in (0, 1]");
        }
        result.target_simplified = share->get<double>();
    } else {
        fail(file, where + " has neither \"target_remeshed\" nor \"target_simplified\"");
    }
    result.parts = part_files(file, base, pair, where, template_name);
    return result;
}

}  // namespace

std::vector<EvalPair> read_pairs_file(const std::filesystem::path& file,
                                      const std::filesystem::path& base,
                                      const std::vector<std::string>& only) {
    json document;
    try {
        document = json::parse(read_file(file));
    } catch (const json::exception& e) {
        fail(file, std::string("not valid JSON (") + e.what() + ")");
    }
    if (!document.is_array()) {
        fail(file, "expected a JSON array of pairs");
    }
    std::vector<EvalPair> pairs;
    std::set<std::string> names;
    for (std::size_t index = 0; index < document.size(); ++index) {
        EvalPair pair = read_pair(file, base, document[index], index);
        if (!names.insert(pair.name).second) {
            fail(file, "two pairs are named \"" + pair.name + "\" (a name names the outputs)");
        }
        if (only.empty() || std::find(only.begin(), only.end(), pair.name) != only.end()) {
            pairs.push_back(std::move(pair));
        }
    }
    for (const std::string& name : only) {
        if (names.count(name) == 0) {
            fail(file, "no pair named \"" + name + "\" (--pairs)");
        }
    }
    return pairs;
}

}  // namespace genflow::cli
