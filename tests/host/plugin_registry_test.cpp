// Plugin host: loading, ABI version and symbol checks, duplicate names, discovery paths.
#include "host/host.h"
#include "host/plugin_registry.h"

#include "host/elf_symbol.h"

#include <gtest/gtest.h>

#include "test_util.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <fstream>

namespace fs = std::filesystem;
using patina::PluginError;
using patina::PluginRegistry;

namespace {

fs::path fixture(const char* which)
{
    return fs::path(PATINA_FIXTURE_PLUGIN_DIR) / which / (std::string("patina_fixture_") + which + ".so");
}

// Runs `f` and returns the message of the PluginError it throws.
template <class F>
std::string error_of(F&& f)
{
    return patina::test::message_of<PluginError>(f);
}

}  // namespace

TEST(PluginRegistry, LoadsAPlainCPlugin)
{
    PluginRegistry reg(patina::default_host().c_host());
    reg.load_file(fixture("good"));
    const patina::LoadedShader* s = reg.find("fixture_diffuse");
    ASSERT_NE(s, nullptr);
    EXPECT_EQ(s->desc->kind, PATINA_SHADER_BSDF);
    EXPECT_EQ(s->plugin_name, "fixture");
    EXPECT_EQ(s->desc->param_count, 8);
    EXPECT_EQ(reg.find("no_such_shader"), nullptr);
}

TEST(PluginRegistry, LoadingTheSameFileTwiceIsNotADuplicate)
{
    PluginRegistry reg(patina::default_host().c_host());
    reg.load_file(fixture("good"));
    reg.load_directory(fixture("good").parent_path());
    EXPECT_EQ(reg.plugin_files().size(), 1u);
}

TEST(PluginRegistry, WrongMajorVersionNamesFileAndVersions)
{
    PluginRegistry reg(patina::default_host().c_host());
    const std::string msg = error_of([&] { reg.load_file(fixture("wrong_version")); });
    EXPECT_NE(msg.find("patina_fixture_wrong_version.so"), std::string::npos) << msg;
    EXPECT_NE(msg.find("ABI 2.0"), std::string::npos) << msg;
    EXPECT_NE(msg.find("ABI 1.1"), std::string::npos) << msg;
    EXPECT_NE(msg.find("rebuild"), std::string::npos) << msg;
    EXPECT_EQ(reg.find("fixture_diffuse"), nullptr);  // nothing of it was registered
}

TEST(PluginRegistry, AWrongVersionIsRefusedWithoutRunningItsCode)
{
    // The wrong-version fixture has a constructor that writes this file when the library is
    // loaded: the version must be read from the ELF file, before dlopen.
    const fs::path witness = fs::path(PATINA_TEST_BUILD_DIR) /
                             ("constructor_ran_" + std::to_string(::getpid()));
    fs::remove(witness);
    ::setenv("PATINA_FIXTURE_CONSTRUCTOR_FILE", witness.c_str(), 1);
    PluginRegistry reg(patina::default_host().c_host());
    const std::string msg = error_of([&] { reg.load_file(fixture("wrong_version")); });
    ::unsetenv("PATINA_FIXTURE_CONSTRUCTOR_FILE");
    EXPECT_NE(msg.find("ABI 2.0"), std::string::npos) << msg;
    EXPECT_FALSE(fs::exists(witness)) << "the refused plugin's constructor ran";
    fs::remove(witness);
}

TEST(PluginRegistry, TheAbiVersionIsReadFromTheElfFile)
{
    EXPECT_EQ(patina::read_elf_int_symbol(fixture("good"), PATINA_PLUGIN_VERSION_SYMBOL),
              std::optional<int32_t>(PATINA_ABI_VERSION));
    EXPECT_EQ(patina::read_elf_int_symbol(fixture("wrong_version"), PATINA_PLUGIN_VERSION_SYMBOL),
              std::optional<int32_t>(200));
    EXPECT_EQ(patina::read_elf_int_symbol(fixture("good"), "no_such_symbol"), std::nullopt);
}

TEST(PluginRegistry, InvalidTablesAreRefusedBeforeUse)
{
    PluginRegistry reg(patina::default_host().c_host());
    const std::string nan = error_of([&] { reg.load_file(fixture("nan_default")); });
    EXPECT_NE(nan.find("parameter 'weight' has default nan outside its range [0, 1]"),
              std::string::npos) << nan;
    const std::string kind = error_of([&] { reg.load_file(fixture("bad_kind")); });
    EXPECT_NE(kind.find("unknown kind 77"), std::string::npos) << kind;
    EXPECT_EQ(reg.find("fixture_diffuse"), nullptr);
}

TEST(PluginRegistry, MissingEntrySymbolNamesFileAndSymbol)
{
    PluginRegistry reg(patina::default_host().c_host());
    const std::string msg = error_of([&] { reg.load_file(fixture("no_entry")); });
    EXPECT_NE(msg.find("patina_fixture_no_entry.so"), std::string::npos) << msg;
    EXPECT_NE(msg.find("patina_plugin_entry"), std::string::npos) << msg;
}

TEST(PluginRegistry, DuplicateShaderNameNamesBothFiles)
{
    PluginRegistry reg(patina::default_host().c_host());
    reg.load_file(fixture("good"));
    const std::string msg = error_of([&] { reg.load_file(fixture("duplicate")); });
    EXPECT_NE(msg.find("fixture_diffuse"), std::string::npos) << msg;
    EXPECT_NE(msg.find("patina_fixture_duplicate.so"), std::string::npos) << msg;
    EXPECT_NE(msg.find("patina_fixture_good.so"), std::string::npos) << msg;
    EXPECT_EQ(reg.plugin_files().size(), 1u);
}

TEST(PluginRegistry, MissingDirectoryIsAnError)
{
    PluginRegistry reg(patina::default_host().c_host());
    const std::string msg = error_of([&] { reg.load_directory("/nonexistent/patina/plugins"); });
    EXPECT_NE(msg.find("/nonexistent/patina/plugins"), std::string::npos) << msg;
    EXPECT_NE(msg.find("does not exist"), std::string::npos) << msg;
}

TEST(PluginRegistry, NotASharedLibraryIsAnError)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "bogus_plugin_dir";
    fs::create_directories(dir);
    const fs::path bogus = dir / "patina_bogus.so";
    std::ofstream(bogus) << "this is not an ELF file\n";
    PluginRegistry reg(patina::default_host().c_host());
    const std::string msg = error_of([&] { reg.load_directory(dir); });
    EXPECT_NE(msg.find("patina_bogus.so"), std::string::npos) << msg;
    EXPECT_NE(msg.find("cannot be loaded as a shared library"), std::string::npos) << msg;
}

TEST(PluginRegistry, PathListRequiresAbsoluteDirectories)
{
    PluginRegistry reg(patina::default_host().c_host());
    const std::string msg = error_of([&] { reg.load_path_list("relative/dir", "PATINA_PLUGIN_PATH"); });
    EXPECT_NE(msg.find("PATINA_PLUGIN_PATH"), std::string::npos) << msg;
    EXPECT_NE(msg.find("not an absolute path"), std::string::npos) << msg;
}

TEST(PluginRegistry, PathListLoadsEveryDirectoryAndSkipsEmptyEntries)
{
    PluginRegistry reg(patina::default_host().c_host());
    const std::string list = "::" + fixture("good").parent_path().string() + ":" + PATINA_TEST_PLUGIN_DIR;
    reg.load_path_list(list, "test");
    EXPECT_NE(reg.find("fixture_diffuse"), nullptr);
    EXPECT_NE(reg.find("lambert"), nullptr);
    EXPECT_GE(reg.plugin_files().size(), 2u);
}

TEST(PluginRegistry, UnknownShaderListsWhatIsLoaded)
{
    PluginRegistry reg(patina::default_host().c_host());
    reg.load_file(fixture("good"));
    const std::string msg = error_of([&] { reg.get("velvet"); });
    EXPECT_NE(msg.find("'velvet'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("fixture_diffuse"), std::string::npos) << msg;
}
