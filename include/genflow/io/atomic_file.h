// SPDX-License-Identifier: MIT
#pragma once

#include <filesystem>
#include <string_view>

namespace genflow {

/// Writes `bytes` to `path` atomically: into a temporary file next to `path`, flushed to disk,
/// then renamed over `path`. Readers see either the old file or the complete new one, and a
/// failure leaves no temporary file behind. Every genflow output goes through this.
///
/// \throws IoError "<path>: <problem>" if the directory does not exist or is not writable.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace genflow
