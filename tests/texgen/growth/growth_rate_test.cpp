#include "texgen/growth/growth_model.h"

#include <gtest/gtest.h>

#include "test_util.h"

#include <cmath>

namespace patina::texgen {
namespace {

    using patina::test::message_of;

    constexpr GrowthRate kAllRates[] = {GrowthRate::Linear, GrowthRate::Parabolic,
                                        GrowthRate::Logarithmic, GrowthRate::Cubic};

    TEST(GrowthNames, ParseThePaperSpellingsOnly)
    {
        // D&H 1996 §3.3 and the §5.1 scripts: "BD linear 1 20", "ST cubic", "DPD", "RD".
        EXPECT_EQ(growth_model_from_name("ST"), GrowthModelKind::SteadyThickening);
        EXPECT_EQ(growth_model_from_name("RD"), GrowthModelKind::RandomDeposition);
        EXPECT_EQ(growth_model_from_name("RDR"), GrowthModelKind::RandomDepositionRelaxed);
        EXPECT_EQ(growth_model_from_name("BD"), GrowthModelKind::BallisticDeposition);
        EXPECT_EQ(growth_model_from_name("DPD"), GrowthModelKind::DirectedPercolationDepinning);
        EXPECT_EQ(growth_model_from_name("noise"), GrowthModelKind::Noise);
        EXPECT_EQ(growth_model_from_name("turbulence"), GrowthModelKind::Turbulence);
        EXPECT_FALSE(growth_model_from_name("bd"));
        EXPECT_FALSE(growth_model_from_name("DPDD"));
        EXPECT_FALSE(growth_model_from_name(""));
        EXPECT_EQ(growth_rate_from_name("linear"), GrowthRate::Linear);
        EXPECT_EQ(growth_rate_from_name("parabolic"), GrowthRate::Parabolic);
        EXPECT_EQ(growth_rate_from_name("logarithmic"), GrowthRate::Logarithmic);
        EXPECT_EQ(growth_rate_from_name("cubic"), GrowthRate::Cubic);
        EXPECT_FALSE(growth_rate_from_name("Linear"));
        EXPECT_FALSE(growth_rate_from_name("exponential"));
    }

    TEST(GrowthNames, ListsRoundTrip)
    {
        ASSERT_EQ(growth_model_names().size(), 7u);
        for (std::string_view name : growth_model_names()) {
            const auto model = growth_model_from_name(name);
            ASSERT_TRUE(model) << name;
            EXPECT_EQ(growth_model_name(*model), name);
        }
        ASSERT_EQ(growth_rate_names().size(), 4u);
        for (std::string_view name : growth_rate_names()) {
            const auto rate = growth_rate_from_name(name);
            ASSERT_TRUE(rate) << name;
            EXPECT_EQ(growth_rate_name(*rate), name);
        }
    }

    TEST(GrowthRate, NormalisedAndMonotone)
    {
        for (GrowthRate rate : kAllRates) {
            EXPECT_EQ(growth_rate(rate, 0.0), 0.0) << growth_rate_name(rate);
            EXPECT_DOUBLE_EQ(growth_rate(rate, 1.0), 1.0) << growth_rate_name(rate);
            double previous = 0.0;
            for (int k = 1; k <= 100; ++k) {
                const double g = growth_rate(rate, k / 100.0);
                EXPECT_GT(g, previous) << growth_rate_name(rate) << " at " << k;
                previous = g;
            }
        }
    }

    TEST(GrowthRate, ShapesOfTheRateLaws)
    {
        // Linear x = kt; parabolic x^2 = kt; cubic x^3 = kt (Evans 1960): at a quarter of the
        // run, 1/4, 1/2 and 4^(-1/3) of the final thickness.
        EXPECT_DOUBLE_EQ(growth_rate(GrowthRate::Linear, 0.25), 0.25);
        EXPECT_DOUBLE_EQ(growth_rate(GrowthRate::Parabolic, 0.25), 0.5);
        EXPECT_NEAR(growth_rate(GrowthRate::Cubic, 0.125), 0.5, 1e-15);
        // Logarithmic x = ln(1 + 20 t) / ln 21: ln 3 / ln 21 at t = 0.1.
        EXPECT_NEAR(growth_rate(GrowthRate::Logarithmic, 0.1), std::log(3.0) / std::log(21.0),
                    1e-15);
        // Decelerating laws lie above the linear one and in the order of their exponents
        // early on: cubic > parabolic > linear (x ~ t^(1/3), t^(1/2), t).
        for (double f : {0.01, 0.1, 0.5, 0.9}) {
            EXPECT_GT(growth_rate(GrowthRate::Cubic, f), growth_rate(GrowthRate::Parabolic, f));
            EXPECT_GT(growth_rate(GrowthRate::Parabolic, f), growth_rate(GrowthRate::Linear, f));
            EXPECT_GT(growth_rate(GrowthRate::Logarithmic, f), growth_rate(GrowthRate::Linear, f));
        }
        // The logarithmic law flattens: its second half adds less than a quarter.
        EXPECT_LT(1.0 - growth_rate(GrowthRate::Logarithmic, 0.5), 0.25);
    }

    TEST(GrowthRate, RejectsFractionsOutsideTheRun)
    {
        EXPECT_NE(message_of([] { growth_rate(GrowthRate::Linear, 1.5); }).find("1.5"),
                  std::string::npos);
        EXPECT_THROW(growth_rate(GrowthRate::Cubic, -0.1), std::invalid_argument);
        EXPECT_THROW(growth_rate(GrowthRate::Parabolic, std::nan("")), std::invalid_argument);
    }

    TEST(GrowthRate, FractionOfAScriptStep)
    {
        GrowthSpec spec;
        spec.step = 5;
        spec.total = 40;
        EXPECT_DOUBLE_EQ(growth_fraction(spec), 0.125);
        spec.step = 41;
        EXPECT_NE(message_of([&] { growth_fraction(spec); }).find("step"), std::string::npos);
        spec.step = 0;
        spec.total = 0;
        EXPECT_NE(message_of([&] { growth_fraction(spec); }).find("total"), std::string::npos);
    }

} // namespace
} // namespace patina::texgen
