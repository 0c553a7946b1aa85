// The plan of a texgen series (formats/texgen_plan/texgen_plan.h): what `patina-texgen ... --plan`
// prints and patina-farm reads, round-tripped, and its refusals.
#include "formats/texgen_plan/texgen_plan.h"

#include "test_util.h"

#include <gtest/gtest.h>

namespace patina::formats {
namespace {

using patina::test::message_of;

TexgenPlan example()
{
    TexgenPlan plan;
    plan.command = "patina";
    plan.output = "/shots/urban";
    plan.tasks.push_back({"t = 0 y", {"patina", "urban.patina", "--times", "0", "-o", "/shots/urban/t00"},
                          {"/shots/urban/t00"}, 0.0, "t00"});
    plan.tasks.push_back({"t = 30 y", {"patina", "urban.patina", "--times=30", "-o", "/shots/urban/t30"},
                          {"/shots/urban/t30", "/shots/urban/extra"}, 30.0, "t30"});
    return plan;
}

TEST(TexgenPlan, RoundTripsEveryKey)
{
    const TexgenPlan plan = example();
    const TexgenPlan back = parse_texgen_plan(texgen_plan_text(plan), "plan");
    EXPECT_EQ(back.command, "patina");
    EXPECT_EQ(back.output, plan.output);
    EXPECT_FALSE(back.chained);
    ASSERT_EQ(back.tasks.size(), 2u);
    for (size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(back.tasks[i].label, plan.tasks[i].label);
        EXPECT_EQ(back.tasks[i].args, plan.tasks[i].args);
        EXPECT_EQ(back.tasks[i].outputs, plan.tasks[i].outputs);
        EXPECT_EQ(back.tasks[i].time_years, plan.tasks[i].time_years);
        EXPECT_EQ(back.tasks[i].folder, plan.tasks[i].folder);
    }
    // A stone chain: no times, no folders.
    TexgenPlan chain;
    chain.command = "stone";
    chain.output = "/s";
    chain.chained = true;
    chain.tasks.push_back({"cycles 0-5", {"stone", "--until", "5"}, {"/s/cycle_0005"}, std::nullopt, ""});
    const TexgenPlan chain_back = parse_texgen_plan(texgen_plan_text(chain), "plan");
    EXPECT_TRUE(chain_back.chained);
    EXPECT_FALSE(chain_back.tasks[0].time_years.has_value());
    EXPECT_TRUE(chain_back.tasks[0].folder.empty());
}

TEST(TexgenPlan, RefusesUnknownKeysMissingValuesAndNoTasks)
{
    const std::string typo = message_of([] {
        (void)parse_texgen_plan("[plan]\ncommand = \"patina\"\noutput = \"/o\"\nchaned = true\n"
                                "[[task]]\nlabel = \"a\"\nargs = [\"patina\"]\noutputs = [\"/o\"]\n",
                                "p.toml");
    });
    EXPECT_NE(typo.find("p.toml:4:"), std::string::npos) << typo;
    EXPECT_NE(typo.find("chaned: unknown key"), std::string::npos) << typo;
    const std::string task_typo = message_of([] {
        (void)parse_texgen_plan("[plan]\ncommand = \"patina\"\noutput = \"/o\"\n[[task]]\n"
                                "label = \"a\"\nargs = [\"patina\"]\noutputs = [\"/o\"]\n"
                                "time_year = 3\n",
                                "p.toml");
    });
    EXPECT_NE(task_typo.find("task 0: time_year: unknown key"), std::string::npos) << task_typo;
    const std::string no_args = message_of([] {
        (void)parse_texgen_plan("[plan]\ncommand = \"patina\"\noutput = \"/o\"\n[[task]]\n"
                                "label = \"a\"\noutputs = [\"/o\"]\n",
                                "p.toml");
    });
    EXPECT_NE(no_args.find("task 0: args:"), std::string::npos) << no_args;
    const std::string none = message_of([] {
        (void)parse_texgen_plan("[plan]\ncommand = \"patina\"\noutput = \"/o\"\n", "p.toml");
    });
    EXPECT_NE(none.find("no [[task]]"), std::string::npos) << none;
    const std::string syntax = message_of([] { (void)parse_texgen_plan("[plan\n", "p.toml"); });
    EXPECT_NE(syntax.find("p.toml:1:"), std::string::npos) << syntax;
}

}  // namespace
}  // namespace patina::formats
