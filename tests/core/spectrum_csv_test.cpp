#include "core/spectrum_csv.h"

#include <gtest/gtest.h>

#include "test_util.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace patina {
namespace {

    namespace fs = std::filesystem;
    using patina::test::message_of;

    fs::path write_csv(const std::string& name, const std::string& text)
    {
        const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "spectrum_csv_test";
        fs::create_directories(dir);
        const fs::path p = dir / (name + "_" + std::to_string(::getpid()) + ".csv");
        std::ofstream(p) << text;
        return p;
    }

}  // namespace

TEST(SpectrumCsv, ReadsNamedColumnsSkippingCommentsAndBlankLines)
{
    const fs::path p = write_csv("good", "# a source line\n\nwavelength_nm, \"dark skin\",white\n"
                                         "400,0.05,0.9\n# mid-table note\n450,0.06,0.91\r\n");
    const SpectrumCsv csv = read_spectrum_csv(p);
    ASSERT_EQ(csv.columns.size(), 2u);
    EXPECT_EQ(csv.columns[0], "dark skin");
    EXPECT_EQ(csv.lambda_nm, (std::vector<double>{400, 450}));
    EXPECT_EQ(csv.values[csv.column("white")], (std::vector<double>{0.9, 0.91}));
}

TEST(SpectrumCsv, BadFilesAreRefusedNamingTheLine)
{
    EXPECT_NE(message_of([&] { read_spectrum_csv(write_csv("fields", "nm,a\n400,1\n450,1,2\n")); })
                  .find("fields_"), std::string::npos);  // the file named
    EXPECT_NE(message_of([&] { read_spectrum_csv(write_csv("fields", "nm,a\n400,1\n450,1,2\n")); })
                  .find(":3: 3 fields, the header has 2"), std::string::npos);
    EXPECT_NE(message_of([&] { read_spectrum_csv(write_csv("nan", "nm,a\n400,x1\n")); })
                  .find(":2: 'x1' in column 'a' is not a number"), std::string::npos);
    EXPECT_NE(message_of([&] { read_spectrum_csv(write_csv("order", "nm,a\n450,1\n400,1\n")); })
                  .find(":3: wavelength 400 nm after 450 nm"), std::string::npos);
    EXPECT_NE(message_of([&] { read_spectrum_csv(write_csv("empty", "# nothing\n")); })
                  .find("has no header"), std::string::npos);
    const SpectrumCsv csv = read_spectrum_csv(write_csv("cols", "nm,a,b\n400,1,2\n"));
    EXPECT_NE(message_of([&] { csv.column("c"); }).find("no column 'c' (it has: a, b)"),
              std::string::npos);
}

}  // namespace patina
