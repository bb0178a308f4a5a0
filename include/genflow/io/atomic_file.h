// SPDX-License-Identifier: MIT
#pragma once

#include <filesystem>
#include <string_view>

namespace genflow {

/// Writes `bytes` to `path` atomically: into a temporary file next to `path`, flushed to disk,
/// then renamed over `path`. Readers see either the old file or the complete new one, and a
/// failure leaves no temporary file behind. Every genflow output goes through this.
///
/// An existing file keeps its permissions. A symbolic link is written through: the file it
/// points to is replaced, and the link stays. A hard link is not: `path` becomes a new file and
/// the other names keep the old content (the price of never showing a half-written file).
/// Inside an OutputTransaction the rename waits for its commit().
///
/// \throws OutputError "<path>: <problem>" if the directory does not exist or is not writable,
///         or the write fails (a full disk).
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

/// Checks, before any work, that `path` can be written as an output: it names a file, is not a
/// directory, and its directory exists and is writable.
/// \throws OutputError "<path>: <problem>".
void check_output_path(const std::filesystem::path& path);

/// A run's outputs, written all or none. While one is alive, write_file_atomically() leaves
/// each finished file as its temporary, and commit() renames them all into place; destroyed
/// without commit() (the run failed), it removes them, so a failed run changes none of its
/// outputs. One opened while another is (a step of a larger run) joins it: its commit() and
/// destruction leave the files to the outer one.
class OutputTransaction {
public:
    OutputTransaction();
    ~OutputTransaction();
    OutputTransaction(const OutputTransaction&) = delete;
    OutputTransaction& operator=(const OutputTransaction&) = delete;

    /// Moves every file written since construction into place, in the order written.
    /// \throws OutputError if a rename fails (those before it are in place).
    void commit();

private:
    bool outermost_ = true;
};

/// From now on, SIGINT, SIGTERM and SIGHUP first remove the temporaries of unfinished writes
/// (and of an uncommitted transaction), then end the process as the signal would have. Called
/// once by the tool; a library user decides for their own process.
void remove_temporaries_on_signals();

}  // namespace genflow
