// Ctrl-C or a farm's kill while a bake runs: patina-texgen stops, exits with 130 and leaves
// no map, no manifest and no temporary file behind (issue 4, "Progress and cancellation").
#include "core/mesh_export.h"
#include "texgen/meshes/statue_mesh.h"

#include <gtest/gtest.h>

#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <vector>

extern char** environ;

namespace patina {
namespace {

namespace fs = std::filesystem;

// Start patina-texgen with `args`, send `signal_number` once its progress line has had time to
// appear, and return the exit status (128 + signal if it died of the signal).
int interrupt_bake(const std::vector<std::string>& args, int signal_number, const fs::path& log)
{
    std::vector<std::string> argv_storage = {std::string(PATINA_TEST_BIN_DIR) + "/patina-texgen"};
    argv_storage.insert(argv_storage.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : argv_storage)
        argv.push_back(a.data());
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 2, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0)
        return -1;
    // The bake below takes minutes; loading and rasterising take well under 2 s.
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    kill(pid, signal_number);
    int status = 0;
    waitpid(pid, &status, 0);
    if (WIFEXITED(status))
        return WEXITSTATUS(status);
    return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
}

TEST(Cancel, InterruptOrTerminateLeavesNoFile)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "cancel_test";
    fs::remove_all(dir);
    fs::create_directories(dir);
    texgen::StatueOptions o;
    o.rings = 60;
    o.segments = 48;
    save_mesh(dir / "statue.obj", texgen::make_statue(Imath::V3f(0.0f), o));

    for (const int sig : {SIGINT, SIGTERM}) {
        const fs::path out = dir / ("maps_" + std::to_string(sig));
        const fs::path log = dir / ("log_" + std::to_string(sig) + ".txt");
        const int status = interrupt_bake({"ao", "--mesh", (dir / "statue.obj").string(), "-o",
                                           out.string(), "--resolution", "1024", "--rays",
                                           "100000"},
                                          sig, log);
        EXPECT_EQ(status, 130) << "signal " << sig;
        // Nothing written: no map, no stack.toml, no temporary file.
        std::vector<std::string> left;
        if (fs::exists(out))
            for (const auto& e : fs::directory_iterator(out))
                left.push_back(e.path().filename().string());
        EXPECT_TRUE(left.empty()) << "signal " << sig << " left " << left.size() << " files, e.g. "
                                  << (left.empty() ? "" : left.front());
    }
}

}  // namespace
}  // namespace patina
