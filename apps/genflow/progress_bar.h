// SPDX-License-Identifier: MIT
// A one-line progress bar on stderr, shown only when stderr is a terminal and the run has
// lasted over a second; silent otherwise (pipes, CI, --json).
#pragma once

#include <chrono>
#include <string>

namespace genflow::cli {

class ProgressBar {
public:
    /// `enabled` false makes every call a no-op (e.g. for --json).
    explicit ProgressBar(std::string label, bool enabled = true);
    ~ProgressBar();
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    /// Shows `done` of `total` and a short status text.
    void update(int done, int total, const std::string& status);

    /// Clears the bar's line if it was drawn.
    void finish();

private:
    std::string label_;
    bool enabled_;
    bool drawn_ = false;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace genflow::cli
