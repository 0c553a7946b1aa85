#include "core/output_transaction.h"

#include "core/cancel.h"
#include "core/image_io.h"

#include <gtest/gtest.h>

#include "test_util.h"

#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace patina {
namespace {

    namespace fs = std::filesystem;
    using patina::test::message_of;

    /// A fresh folder of this test's own.
    fs::path fresh_dir(const std::string& name)
    {
        const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "output_transaction_test" /
                             (name + "_" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
        return dir;
    }

    void write_text(const fs::path& path, const std::string& text)
    {
        std::ofstream(path, std::ios::binary) << text;
    }

    std::string read_text(const fs::path& path)
    {
        std::ifstream in(path, std::ios::binary);
        std::ostringstream s;
        s << in.rdbuf();
        return s.str();
    }

    /// Names in `dir` (not recursive), sorted.
    std::set<std::string> names_in(const fs::path& dir)
    {
        std::set<std::string> names;
        for (const auto& e : fs::directory_iterator(dir))
            names.insert(e.path().filename().string());
        return names;
    }

}  // namespace

TEST(OutputTransaction, FilesMoveInOnlyAtCommit)
{
    const fs::path dir = fresh_dir("commit");
    write_text(dir / "a.txt", "old a");
    {
        OutputTransaction outputs;
        const CurrentOutputs current(outputs);
        write_file_atomic(dir / "a.txt", {"new a"}, "test file");
        write_file_atomic(dir / "sub" / "b.txt", {"new b"}, "test file");
        // Nothing has moved yet; the run reads its own version through output_to_read.
        EXPECT_EQ(read_text(dir / "a.txt"), "old a");
        EXPECT_FALSE(fs::exists(dir / "sub"));
        EXPECT_EQ(read_text(output_to_read(dir / "a.txt")), "new a");
        EXPECT_EQ(outputs.staged_count(), 2u);
        outputs.commit();
    }
    EXPECT_EQ(read_text(dir / "a.txt"), "new a");
    EXPECT_EQ(read_text(dir / "sub" / "b.txt"), "new b");
    EXPECT_EQ(names_in(dir), (std::set<std::string>{"a.txt", "sub"}));
}

TEST(OutputTransaction, ARunThatEndsWithoutCommitLeavesEverythingAsItWas)
{
    const fs::path dir = fresh_dir("rollback");
    write_text(dir / "a.txt", "old a");
    write_text(dir / "stale.txt", "stale");
    try {
        OutputTransaction outputs;
        const CurrentOutputs current(outputs);
        write_file_atomic(dir / "a.txt", {"new a"}, "test file");
        write_file_atomic(dir / "new" / "c.txt", {"new c"}, "test file");
        remove_output(dir / "stale.txt");
        throw std::runtime_error("the run fails after writing");
    } catch (const std::runtime_error&) {
    }
    EXPECT_EQ(read_text(dir / "a.txt"), "old a");
    EXPECT_EQ(read_text(dir / "stale.txt"), "stale");
    // No new folder, no staging folder.
    EXPECT_EQ(names_in(dir), (std::set<std::string>{"a.txt", "stale.txt"}));
}

TEST(OutputTransaction, CommitSoFarKeepsWhatIsStagedAndStaysOpen)
{
    // A long run's checkpoint: what it staged so far goes into place even after a signal;
    // what it stages later needs the final commit, and is dropped without it.
    const fs::path dir = fresh_dir("commit_so_far");
    try {
        OutputTransaction outputs;
        const CurrentOutputs current(outputs);
        write_file_atomic(dir / "step1" / "a.txt", {"a"}, "test file");
        request_cancel();
        outputs.commit_so_far();
        reset_cancel();
        EXPECT_EQ(read_text(dir / "step1" / "a.txt"), "a");
        EXPECT_EQ(outputs.staged_count(), 0u);
        write_file_atomic(dir / "step2" / "b.txt", {"b"}, "test file");
        write_file_atomic(dir / "step1" / "a.txt", {"a again"}, "test file");
        EXPECT_EQ(read_text(output_to_read(dir / "step1" / "a.txt")), "a again");
        throw std::runtime_error("the run fails after its checkpoint");
    } catch (const std::runtime_error&) {
    }
    EXPECT_EQ(read_text(dir / "step1" / "a.txt"), "a");
    EXPECT_EQ(names_in(dir), (std::set<std::string>{"step1"}));
    EXPECT_EQ(names_in(dir / "step1"), (std::set<std::string>{"a.txt"}));
}

TEST(OutputTransaction, DeletionsWaitForTheCommit)
{
    const fs::path dir = fresh_dir("delete");
    write_text(dir / "layer03.exr", "old layer");
    OutputTransaction outputs;
    const CurrentOutputs current(outputs);
    remove_output(dir / "layer03.exr");
    EXPECT_TRUE(fs::exists(dir / "layer03.exr"));
    EXPECT_FALSE(fs::exists(output_to_read(dir / "layer03.exr")));
    outputs.commit();
    EXPECT_FALSE(fs::exists(dir / "layer03.exr"));
}

TEST(OutputTransaction, ATargetThatIsAFolderFailsAtReserveBeforeAnyWork)
{
    const fs::path dir = fresh_dir("folder_target");
    fs::create_directories(dir / "out.png");
    OutputTransaction outputs;
    const std::string msg = message_of([&] { outputs.reserve(dir / "out.png"); });
    EXPECT_NE(msg.find("out.png"), std::string::npos) << msg;
    EXPECT_NE(msg.find("is a folder"), std::string::npos) << msg;

    write_text(dir / "x", "a file");
    const std::string parent = message_of([&] { outputs.reserve(dir / "x" / "y.exr"); });
    EXPECT_NE(parent.find("is not a folder"), std::string::npos) << parent;
}

TEST(OutputTransaction, CommitChecksEveryTargetBeforeMovingAny)
{
    const fs::path dir = fresh_dir("precheck");
    write_text(dir / "out.exr", "old exr");
    OutputTransaction outputs;
    const CurrentOutputs current(outputs);
    write_file_atomic(dir / "out.exr", {"new exr"}, "test file");
    write_file_atomic(dir / "out.png", {"new png"}, "test file");
    // A folder appears at the second name after it was staged (the render's case).
    fs::create_directories(dir / "out.png");
    const std::string msg = message_of([&] { outputs.commit(); });
    EXPECT_NE(msg.find("out.png"), std::string::npos) << msg;
    EXPECT_NE(msg.find("no output was written"), std::string::npos) << msg;
    EXPECT_EQ(read_text(dir / "out.exr"), "old exr");
}

TEST(OutputTransaction, AMoveThatFailsUndoesTheMovesBeforeIt)
{
    const fs::path dir = fresh_dir("undo");
    write_text(dir / "a.txt", "old a");
    write_text(dir / "gone.txt", "to be deleted");
    OutputTransaction outputs;
    const CurrentOutputs current(outputs);
    write_file_atomic(dir / "a.txt", {"new a"}, "test file");
    remove_output(dir / "gone.txt");
    write_file_atomic(dir / "new" / "b.txt", {"new b"}, "test file");
    write_file_atomic(dir / "blocked" / "c.txt", {"new c"}, "test file");
    // 'blocked' becomes a file after staging: the last move fails (not a folder).
    write_text(dir / "blocked", "in the way");
    const std::string msg = message_of([&] { outputs.commit(); });
    EXPECT_NE(msg.find("c.txt"), std::string::npos) << msg;
    EXPECT_NE(msg.find("restored"), std::string::npos) << msg;
    EXPECT_EQ(read_text(dir / "a.txt"), "old a");
    EXPECT_EQ(read_text(dir / "gone.txt"), "to be deleted");
    EXPECT_FALSE(fs::exists(dir / "new"));
}

TEST(OutputTransaction, ACancelledRunCommitsNothing)
{
    const fs::path dir = fresh_dir("cancel");
    write_text(dir / "a.txt", "old a");
    OutputTransaction outputs;
    const CurrentOutputs current(outputs);
    write_file_atomic(dir / "a.txt", {"new a"}, "test file");
    request_cancel();
    EXPECT_THROW(outputs.commit(), Cancelled);
    reset_cancel();
    EXPECT_EQ(read_text(dir / "a.txt"), "old a");
}

TEST(OutputTransaction, AWriterThatFailedHalfWayBlocksTheCommit)
{
    const fs::path dir = fresh_dir("failed_writer");
    OutputTransaction outputs;
    const CurrentOutputs current(outputs);
    write_file_atomic(dir / "manifest.toml", {"first version"}, "test file");
    {
        // A second version of the same file, abandoned half-written (its writer threw and
        // a caller caught the exception).
        StagedOutput staged(dir / "manifest.toml");
        write_text(staged.path(), "half");
    }
    const std::string msg = message_of([&] { outputs.commit(); });
    EXPECT_NE(msg.find("manifest.toml"), std::string::npos) << msg;
    EXPECT_FALSE(fs::exists(dir / "manifest.toml"));
}

TEST(OutputTransaction, StagingFoldersArePrivateAndUnpredictable)
{
    const fs::path dir = fresh_dir("private");
    std::set<std::string> folders;
    for (int run = 0; run < 2; ++run) {
        OutputTransaction outputs;
        const fs::path staged = outputs.stage(dir / "out.exr");
        const fs::path folder = staged.parent_path();
        EXPECT_EQ(folder.parent_path(), dir);
        EXPECT_TRUE(folder.filename().string().starts_with(".patina-staging-"));
        struct stat st {};
        ASSERT_EQ(::lstat(folder.c_str(), &st), 0);
        EXPECT_TRUE(S_ISDIR(st.st_mode));
        EXPECT_EQ(st.st_mode & 0777, 0700u) << "the staging folder must be private";
        folders.insert(folder.filename().string());
    }
    EXPECT_EQ(folders.size(), 2u) << "two runs must not stage under the same name";
}

TEST(OutputTransaction, SymlinksPlantedAtTheOldTemporaryNamesAreNotFollowed)
{
    // Before the staging folders, a write went to `<out>.tmp-<pid>-<n>`, opened without
    // O_EXCL or O_NOFOLLOW: another user's symlink at that name made the write land in the
    // symlink's target, and the final output became the symlink.
    const fs::path dir = fresh_dir("symlinks");
    const fs::path victim = dir / "victim.txt";
    write_text(victim, "precious");
    const fs::path out = dir / "out.exr";
    for (int n = 0; n < 64; ++n)
        fs::create_symlink(victim, fs::path(out.string() + ".tmp-" + std::to_string(::getpid()) +
                                            "-" + std::to_string(n)));
    const std::vector<float> pixels(4 * 4 * 3, 0.5f);
    write_image_atomic(out, pixels.data(), 4, 4, 3, {}, OIIO::TypeDesc::HALF);
    write_file_atomic(dir / "out.exr.txt", {"text"}, "test file");

    EXPECT_EQ(read_text(victim), "precious");
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(out)));
    EXPECT_EQ(read_image(out).width, 4);
}

TEST(OutputTransaction, ASymlinkAtTheTargetIsReplacedNotWrittenThrough)
{
    const fs::path dir = fresh_dir("target_symlink");
    const fs::path victim = dir / "victim.txt";
    write_text(victim, "precious");
    fs::create_symlink(victim, dir / "out.txt");
    write_file_atomic(dir / "out.txt", {"new"}, "test file");
    EXPECT_EQ(read_text(victim), "precious");
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir / "out.txt")));
    EXPECT_EQ(read_text(dir / "out.txt"), "new");
}

TEST(OutputTransaction, ASecondSignalWaitsForTheCommitToFinish)
{
    EXPECT_EXIT(
        {
            install_cancel_handler();
            {
                const HoldTermination hold;
                std::raise(SIGTERM);  // the first signal sets the flag
                ::usleep(300'000);    // (sooner, it would count as the same one twice)
                std::raise(SIGTERM);  // the second would terminate: held
                std::fputs("still running", stderr);
            }
            std::_Exit(0);  // not reached: the held signal is carried out above
        },
        testing::KilledBySignal(SIGTERM), "still running");
}

TEST(OutputTransaction, TheSameSignalDeliveredTwiceIsOneRequest)
{
    // timeout(1) sends SIGTERM to the process and then to its process group: the two arrive
    // microseconds apart and must not count as a user insisting.
    EXPECT_EXIT(
        {
            install_cancel_handler();
            std::raise(SIGTERM);
            std::raise(SIGTERM);
            std::_Exit(cancel_requested() ? 7 : 8);
        },
        testing::ExitedWithCode(7), "");
}

}  // namespace patina
