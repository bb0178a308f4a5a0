// SPDX-License-Identifier: MIT
// Runs the genflow executable the way a user would and captures what it prints.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "support/test_meshes.h"

namespace genflow::test {

struct CliResult {
    int exit_code = -1;
    std::string out;
    std::string err;
};

inline std::string read_text(const std::filesystem::path& path) {
    std::ifstream file(path);
    std::stringstream buffer;
    buffer << file.rdbuf();
    return buffer.str();
}

/// Runs `genflow <arguments>` (arguments are passed to the shell as written) with no input,
/// after `prefix` (shell text such as "cd DIR && " or "NAME=value ").
inline CliResult run_genflow_after(const std::string& prefix, const std::string& arguments) {
    const TemporaryDirectory capture;
    const std::string command = prefix + "'" + GENFLOW_CLI_PATH + "' " + arguments + " >'" +
                                (capture / "out").string() + "' 2>'" + (capture / "err").string() +
                                "' </dev/null";
    const int status = std::system(command.c_str());
    CliResult result;
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    result.out = read_text(capture / "out");
    result.err = read_text(capture / "err");
    return result;
}

/// Runs `genflow <arguments>` (arguments are passed to the shell as written) with no input.
inline CliResult run_genflow(const std::string& arguments) {
    return run_genflow_after("", arguments);
}

/// The path in single quotes for the shell. Built by appending: `"'" + string` trips a GCC 12
/// -Wrestrict false positive.
inline std::string quoted(const std::filesystem::path& path) {
    std::string text = "'";
    text += path.string();
    text += "'";
    return text;
}

}  // namespace genflow::test
