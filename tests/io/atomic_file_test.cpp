// SPDX-License-Identifier: MIT
#include "genflow/io/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include "genflow/exceptions.h"
#include "genflow/io/read_file.h"
#include "support/test_meshes.h"

namespace genflow {
namespace {

// The names in a directory.
std::vector<std::string> names_in(const std::filesystem::path& directory) {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(directory)) {
        names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
}

TEST(AtomicFile, ReplacesContentsWhole) {
    const test::TemporaryDirectory directory;
    write_file_atomically(directory / "a.txt", "first");
    write_file_atomically(directory / "a.txt", "second");
    EXPECT_EQ(read_file(directory / "a.txt"), "second");
    EXPECT_EQ(names_in(directory.path()), std::vector<std::string>{"a.txt"});
}

// An existing output keeps its permissions; a symbolic link stays and its file is replaced.
TEST(AtomicFile, KeepsPermissionsAndWritesThroughALink) {
    const test::TemporaryDirectory directory;
    write_file_atomically(directory / "private.txt", "old");
    std::filesystem::permissions(
        directory / "private.txt",
        std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
    std::filesystem::create_symlink("private.txt", directory / "link.txt");
    write_file_atomically(directory / "link.txt", "new");
    EXPECT_TRUE(std::filesystem::is_symlink(directory / "link.txt"));
    EXPECT_EQ(read_file(directory / "private.txt"), "new");
    EXPECT_EQ(std::filesystem::status(directory / "private.txt").permissions(),
              std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
}

// A chain of links is followed to its end, also when that file is yet to be written; a loop of
// links is refused.
TEST(AtomicFile, FollowsAChainOfLinksAndRefusesALoop) {
    const test::TemporaryDirectory directory;
    std::filesystem::create_directory(directory / "sub");
    std::filesystem::create_symlink("sub/middle.txt", directory / "first.txt");
    std::filesystem::create_symlink("last.txt", directory / "sub" / "middle.txt");
    write_file_atomically(directory / "first.txt", "through");
    EXPECT_TRUE(std::filesystem::is_symlink(directory / "first.txt"));
    EXPECT_TRUE(std::filesystem::is_symlink(directory / "sub" / "middle.txt"));
    EXPECT_EQ(read_file(directory / "sub" / "last.txt"), "through");
    std::filesystem::create_symlink("loop.txt", directory / "loop.txt");
    EXPECT_THROW(check_output_path(directory / "loop.txt"), OutputError);
    EXPECT_THROW(write_file_atomically(directory / "loop.txt", "x"), OutputError);
}

// The outputs of a transaction appear together at commit(); without it, none changes and no
// temporary is left.
TEST(AtomicFile, ATransactionWritesAllOrNone) {
    const test::TemporaryDirectory directory;
    write_file_atomically(directory / "a.txt", "old a");
    {
        OutputTransaction outputs;
        write_file_atomically(directory / "a.txt", "new a");
        write_file_atomically(directory / "b.txt", "new b");
        EXPECT_EQ(read_file(directory / "a.txt"), "old a");
        EXPECT_FALSE(std::filesystem::exists(directory / "b.txt"));
    }
    EXPECT_EQ(names_in(directory.path()), std::vector<std::string>{"a.txt"});
    EXPECT_EQ(read_file(directory / "a.txt"), "old a");
    {
        OutputTransaction outputs;
        write_file_atomically(directory / "a.txt", "new a");
        {
            OutputTransaction step;  // joins the outer one
            write_file_atomically(directory / "b.txt", "new b");
            step.commit();
        }
        EXPECT_FALSE(std::filesystem::exists(directory / "b.txt"));
        outputs.commit();
    }
    EXPECT_EQ(read_file(directory / "a.txt"), "new a");
    EXPECT_EQ(read_file(directory / "b.txt"), "new b");
    EXPECT_EQ(names_in(directory.path()), (std::vector<std::string>{"a.txt", "b.txt"}));
}

TEST(AtomicFile, OutputPathsAreCheckedBeforeAnyWork) {
    const test::TemporaryDirectory directory;
    EXPECT_NO_THROW(check_output_path(directory / "new.ply"));
    for (const auto& [path, says] :
         {std::pair{directory / "none" / "x.ply",
                    "the directory " + (directory / "none").string() + " does not exist"},
          {directory.path(), "is a directory"}}) {
        try {
            check_output_path(path);
            ADD_FAILURE() << path;
        } catch (const OutputError& e) {
            EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
        }
    }
}

// Interrupted with outputs pending, the process removes their temporaries before it ends.
TEST(AtomicFile, ASignalRemovesThePendingTemporaries) {
    const test::TemporaryDirectory directory;
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        remove_temporaries_on_signals();
        OutputTransaction outputs;
        write_file_atomically(directory / "a.txt", "pending");
        std::raise(SIGTERM);
        ::_exit(0);  // not reached
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM);
    EXPECT_TRUE(names_in(directory.path()).empty());
}

}  // namespace
}  // namespace genflow
