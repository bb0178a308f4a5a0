// SPDX-License-Identifier: MIT
// The genflow command-line tool. No algorithm code lives here: each subcommand parses its
// arguments, calls the library and reports. Errors become one line on stderr and an exit code.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <new>
#include <string>

#include "cli_support.h"
#include "commands.h"
#include "genflow/exceptions.h"
#include "genflow/io/atomic_file.h"
#include "genflow/threads.h"
#include "genflow/version.h"
#include "memory_policy.h"
#include "number_checks.h"
#include "reports.h"

namespace {

// A parse error as one line: a command that is not one named as such, and the help to read that
// of the command given.
std::string parse_error_message(const CLI::App& app, const CLI::ParseError& error, int argc,
                                char** argv) {
    std::string command = "genflow";
    for (const CLI::App* subcommand : app.get_subcommands()) {
        command += " " + subcommand->get_name();
    }
    if (command == "genflow" && argc > 1 && argv[1][0] != '-') {
        std::string names;
        for (const CLI::App* subcommand : app.get_subcommands({})) {
            names += (names.empty() ? "" : ", ") + subcommand->get_name();
        }
        return "unknown command '" + genflow::cli::printable(argv[1]) + "' (commands: " + names +
               ")";
    }
    std::string problem = error.what();
    // The number checks let through what CLI11 then cannot store: a count given as 1.5, or too
    // large for its type. Said as the checks say it.
    const std::string not_converted = "Could not convert: ";
    if (const auto equals = problem.find(" = ");
        dynamic_cast<const CLI::ConversionError*>(&error) != nullptr &&
        problem.starts_with(not_converted) && equals != std::string::npos) {
        problem = problem.substr(not_converted.size(), equals - not_converted.size()) +
                  ": must be a whole number in range, got " + problem.substr(equals + 3);
    }
    return genflow::cli::printable(problem) + " (run '" + command + " --help')";
}

}  // namespace

int main(int argc, char** argv) {
    using namespace genflow::cli;
    ask_for_huge_pages(argv);
    keep_freed_memory();
    CLI::App app{
        "genflow: generalized gradient flows of triangle meshes (Eckstein et al., SGP 2007)",
        "genflow"};
    app.set_version_flag("--version", "genflow " + std::string(genflow::kVersion));
    genflow::remove_temporaries_on_signals();
    set_command_line(argc, argv);
    app.require_subcommand(1);
    // --threads anywhere on the line (fallthrough: after the command's own options too), set
    // before the command runs.
    app.fallthrough();
    app.add_option_function<int>(
           "--threads", [](int count) { genflow::set_thread_count(count); },
           "Threads of the parallel sums (default: OMP_NUM_THREADS, else every core); results "
           "do not depend on it")
        ->check(positive_number());
    register_info_command(app);
    register_smooth_command(app);
    register_distance_command(app);
    register_match_command(app);
    register_transfer_command(app);
    register_batch_command(app);
    register_eval_command(app);
    register_benchmark_command(app);
    register_demo_command(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) {  // --help, --version
            return app.exit(e);
        }
        std::cerr << "genflow: " << parse_error_message(app, e, argc, argv) << '\n';
        return kBadInput;
    } catch (const genflow::OutputError& e) {
        std::cerr << "genflow: " << printable(e.what()) << '\n';
        return kFailure;
    } catch (const SomeWorkFailed&) {
        return kFailure;
    } catch (const genflow::IoError& e) {
        std::cerr << "genflow: " << printable(e.what()) << '\n';
        return kBadInput;
    } catch (const genflow::InvalidInput& e) {
        std::cerr << "genflow: " << printable(e.what()) << '\n';
        return kBadInput;
    } catch (const std::bad_alloc&) {
        std::cerr << "genflow: out of memory (the input is larger than this machine can hold)\n";
        return kFailure;
    } catch (const std::exception& e) {
        std::cerr << "genflow: " << printable(e.what()) << '\n';
        return kFailure;
    }
    return kSuccess;
}
