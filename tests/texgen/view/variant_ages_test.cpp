// The ages of an exported series' variants come from what export recorded in the materials'
// extras (texgen/view/variant_ages.h), whatever the variants are called.
#include "texgen/view/variant_ages.h"

#include <gtest/gtest.h>

namespace patina::texgen {
namespace {

    using nlohmann::json;

    /// A series of `names.size()` variants on one primitive, material i showing variant i
    /// with `extras` i (null: none), plus a kept-off material without extras on a second
    /// primitive showing every variant.
    json series(const std::vector<std::string>& names, const std::vector<json>& extras)
    {
        json gltf;
        json variants = json::array(), materials = json::array(), mappings = json::array();
        for (size_t i = 0; i < names.size(); ++i) {
            variants.push_back({{"name", names[i]}});
            json m = {{"name", "step " + std::to_string(i)}};
            if (!extras[i].is_null())
                m["extras"] = {{"patina", extras[i]}};
            materials.push_back(m);
            mappings.push_back({{"material", i}, {"variants", {i}}});
        }
        materials.push_back({{"name", "glass"}});
        json all = json::array();
        for (size_t i = 0; i < names.size(); ++i)
            all.push_back(i);
        gltf["extensions"]["KHR_materials_variants"]["variants"] = variants;
        gltf["materials"] = materials;
        gltf["meshes"] = json::array(
            {{{"primitives",
               {{{"material", 0}, {"extensions", {{"KHR_materials_variants", {{"mappings", mappings}}}}}},
                {{"material", names.size()},
                 {"extensions",
                  {{"KHR_materials_variants",
                    {{"mappings", {{{"material", names.size()}, {"variants", all}}}}}}}}}}}}});
        return gltf;
    }

}  // namespace

TEST(VariantAges, YearsComeFromTheExtrasNotTheNames)
{
    const VariantAges ages = variant_ages(
        series({"new", "weathered", "old"},
               {{{"time_years", 0.0}}, {{"time_years", 12.5}}, {{"time_years", 30.0}}}));
    EXPECT_EQ(ages.values, (std::vector<double>{0.0, 12.5, 30.0}));
    EXPECT_EQ(ages.unit, "y");
    EXPECT_EQ(ages.labels, (std::vector<std::string>{"0 y", "12.5 y", "30 y"}));
}

TEST(VariantAges, SecondsAreShownInTheLargestUnitTheLastAgeReaches)
{
    // A fading series: 0, 1 and 2 days (86400 s a day).
    const VariantAges days = variant_ages(
        series({"a", "b", "c"}, {{{"time_s", 0.0}}, {{"time_s", 86400.0}}, {{"time_s", 172800.0}}}));
    EXPECT_EQ(days.unit, "d");
    EXPECT_EQ(days.values, (std::vector<double>{0.0, 1.0, 2.0}));
    const VariantAges hours =
        variant_ages(series({"a", "b"}, {{{"time_s", 0.0}}, {{"time_s", 43200.0}}}));
    EXPECT_EQ(hours.unit, "h");
    EXPECT_EQ(hours.labels.back(), "12 h");
}

TEST(VariantAges, WithoutRecordedTimesTheNamesAreAllThereIs)
{
    // A series by dose records no time; one variant without extras leaves them all unknown.
    const VariantAges none = variant_ages(series({"1e6 J/m2", "2e6 J/m2"}, {json(), json()}));
    EXPECT_TRUE(none.values.empty());
    EXPECT_EQ(none.labels, (std::vector<std::string>{"1e6 J/m2", "2e6 J/m2"}));
    const VariantAges partial =
        variant_ages(series({"0 y", "x"}, {{{"time_years", 0.0}}, json()}));
    EXPECT_TRUE(partial.values.empty());
    EXPECT_EQ(partial.labels[1], "x");
}

}  // namespace patina::texgen
