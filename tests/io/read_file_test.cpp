// SPDX-License-Identifier: MIT
#include "genflow/io/read_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "genflow/exceptions.h"
#include "genflow/io/read_mesh.h"
#include "genflow/io/read_points.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// The message a read of `path` is refused with.
template <typename Read>
std::string refusal(Read read, const std::filesystem::path& path) {
    try {
        (void)read(path);
    } catch (const IoError& e) {
        return e.what();
    }
    return "accepted";
}

TEST(ReadFile, ReadsEveryByteOfARegularFile) {
    const test::TemporaryDirectory directory;
    const std::string bytes("a\0b\r\n\xff", 6);
    test::write_bytes(directory / "f.bin", bytes);
    EXPECT_EQ(read_file(directory / "f.bin"), bytes);
}

// A named pipe would block the reader until something writes into it: it is refused at once,
// by every reader, with the path named.
TEST(ReadFile, RefusesANamedPipeWithoutWaitingForIt) {
    const test::TemporaryDirectory directory;
    const auto pipe = directory / "f.ply";
    ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
    const std::string says = pipe.string() + ": not a regular file";
    EXPECT_EQ(refusal([](const auto& p) { return read_file(p); }, pipe).rfind(says, 0), 0U);
    EXPECT_EQ(refusal([](const auto& p) { return read_mesh(p); }, pipe).rfind(says, 0), 0U);
    const auto xyz = directory / "f.xyz";
    ASSERT_EQ(::mkfifo(xyz.c_str(), 0600), 0);
    EXPECT_EQ(refusal([](const auto& p) { return read_points(p); }, xyz).rfind(xyz.string(), 0),
              0U);
}

TEST(ReadFile, NamesAMissingFileAndADirectory) {
    const test::TemporaryDirectory directory;
    EXPECT_EQ(refusal([](const auto& p) { return read_file(p); }, directory / "none"),
              (directory / "none").string() + ": cannot open for reading (no such file)");
    EXPECT_EQ(refusal([](const auto& p) { return read_file(p); }, directory.path()),
              directory.path().string() + ": is a directory, not a file");
}

}  // namespace
}  // namespace genflow
