// SPDX-License-Identifier: MIT
#pragma once

#include <stdexcept>
#include <string>

namespace genflow {

/// A caller passed something the function cannot work with: wrong sizes, indices out of range,
/// non-finite or non-positive parameters, a mesh the algorithm refuses. The message names the
/// function, what was expected and what was given.
class InvalidInput : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

/// A numerical method failed: a matrix that should be positive definite is not, a
/// factorization broke down. The message names the function and the likely cause.
class SolverError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Reading or writing a file failed: it does not exist, cannot be written, or its content is
/// malformed. The message is one line that starts with the file's path.
class IoError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Writing an output failed: its directory is missing or not writable, it is a directory, the
/// disk is full. A failure of the run, not of its input (the tool's exit code 1, not 2).
class OutputError : public IoError {
public:
    using IoError::IoError;
};

}  // namespace genflow
