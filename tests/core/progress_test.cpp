#include "core/progress.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <fcntl.h>
#include <unistd.h>

namespace patina {
namespace {

    /// What `f` writes to stderr (file descriptor 2, where Progress writes).
    template <typename F>
    std::string stderr_of(F&& f)
    {
        // A file per test: CTest runs the tests of this file in parallel processes.
        const auto file = std::filesystem::path(PATINA_TEST_BUILD_DIR) /
                          (std::string("progress_test.") +
                           ::testing::UnitTest::GetInstance()->current_test_info()->name() +
                           ".err");
        std::fflush(stderr);
        const int saved = ::dup(2);
        const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        ::dup2(fd, 2);
        ::close(fd);
        f();
        std::fflush(stderr);
        ::dup2(saved, 2);
        ::close(saved);
        std::ifstream in(file);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }

}  // namespace

TEST(Progress, AWarningOrErrorAfterAProgressLineStartsALineOfItsOwn)
{
    const std::string text = stderr_of([] {
        Progress progress(10, false, "bake");
        progress.step(1);  // the first step prints: "\rbake:  10.0% ..."
        print_warning("patina-texgen", "something to know");
        progress.step(1);  // throttled: nothing more printed within half a second
        end_progress_line();
    });
    const size_t bar = text.find("\rbake:");
    const size_t warning = text.find("patina-texgen: warning: something to know\n");
    ASSERT_NE(bar, std::string::npos) << text;
    ASSERT_NE(warning, std::string::npos) << text;
    EXPECT_EQ(text[warning - 1], '\n') << text;
    // Nothing is open any more: a second call prints nothing.
    EXPECT_EQ(stderr_of([] { end_progress_line(); }), "");
}

TEST(Progress, AProgressLineLeftOpenByAnExceptionIsEndedOnce)
{
    const std::string text = stderr_of([] {
        try {
            Progress progress(4, false, "patina");
            progress.step(1);
            throw std::runtime_error("map not found");
        } catch (const std::exception&) {
            end_progress_line();  // what every tool's error edge does
            std::fprintf(stderr, "patina-texgen: error: map not found\n");
        }
    });
    EXPECT_NE(text.find("\npatina-texgen: error: map not found\n"), std::string::npos) << text;
    EXPECT_EQ(text.find("\n\n"), std::string::npos) << text;
}

}  // namespace patina
