// The spectral optics of the patina materials (texgen/patina/stack_materials.h) and the
// [patina.materials] section stack_writer writes into stack.toml for the layered shader.
#include "texgen/patina/material_library.h"
#include "texgen/patina/patina_domain.h"
#include "texgen/patina/stack_materials.h"
#include "texgen/patina/stack_writer.h"
#include "shipped_materials.h"

#include <patina/shading/kubelka_munk.h>
#include "core/rgb_spectrum.h"
#include "test_util.h"

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using patina::ColorManager;
using namespace patina::texgen;

namespace {

const ColorManager& colors() { return test::repository_colors(); }
const MaterialLibrary& shipped() { return test::shipped_copper_library(); }

fs::path write_library(const std::string& name, const std::string& text)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "stack_materials";
    fs::create_directories(dir);
    std::ofstream(dir / name) << text;
    return dir / name;
}

int grid_index(float lambda_nm)
{
    return static_cast<int>((lambda_nm - kSpectralStartNm) / kSpectralStepNm + 0.5f);
}

}  // namespace

TEST(StackMaterials, CopperIsJohnsonAndChristy)
{
    const PatinaMaterial& cu = shipped().at("copper");
    ASSERT_EQ(cu.spectral.n.size(), static_cast<size_t>(kSpectralSamples));
    // Johnson & Christy 1972 (refractiveindex.info): 548.6 nm n = 1.02, k = 2.577;
    // 582.1 nm n = 0.70, k = 2.704: linear interpolation at 560 nm.
    const float t = (560.0f - 548.6f) / (582.1f - 548.6f);
    EXPECT_NEAR(cu.spectral.n[grid_index(560)], 1.02f + t * (0.70f - 1.02f), 1e-5f);
    EXPECT_NEAR(cu.spectral.k[grid_index(560)], 2.577f + t * (2.704f - 2.577f), 1e-5f);
    // 659.5 nm: n = 0.22, k = 3.747 (interpolated at 660).
    EXPECT_NEAR(cu.spectral.n[grid_index(660)], 0.22f, 0.002f);
    EXPECT_NEAR(cu.spectral.k[grid_index(660)], 3.747f + 0.5f / 45.0f * (4.205f - 3.747f), 1e-4f);
}

TEST(StackMaterials, LayerSpectraFollowKubelkaMunk)
{
    for (const PatinaMaterial& m : shipped().materials()) {
        if (m.is_metal)
            continue;
        ASSERT_EQ(m.spectral.absorption.size(), static_cast<size_t>(kSpectralSamples)) << m.name;
        for (int i = 0; i < kSpectralSamples; ++i) {
            const float K = m.spectral.absorption[i], S = m.spectral.scattering[i];
            ASSERT_GT(S, 0.0f) << m.name;
            // R_inf = 1 + K/S - sqrt((K/S)^2 + 2 K/S) (D&H 1996 §4.1) is the stored R_inf.
            EXPECT_NEAR(patina::shading::km_r_infinity(K / S), m.spectral.r_infinity[i], 1e-4f) << m.name;
        }
    }
    // The uplifted R_inf of a plain layer has its colour: RGB of the spectrum under D65
    // (core/rgb_spectrum.h's inverse) in linear Rec.709 equals the material's colour.
    const PatinaMaterial& brochantite = shipped().at("brochantite");
    const patina::RgbToSpectrum uplift(colors().working_rgb_to_xyz());
    float rgb[3] = {brochantite.color.x, brochantite.color.y, brochantite.color.z};
    colors().convert("lin_rec709", colors().working_space(), rgb, 1);
    const PatinaRgbSpectrum s = uplift.uplift({rgb[0], rgb[1], rgb[2]}, false);
    for (int i = 0; i < kSpectralSamples; ++i)
        EXPECT_NEAR(brochantite.spectral.r_infinity[i],
                    patina::RgbToSpectrum::eval(s, kSpectralStartNm + kSpectralStepNm * i), 1e-4f);
}

TEST(StackMaterials, MixturesMixSpectralKAndSByVolume)
{
    // Duncan's rule per wavelength: "marine patina 3" = 0.7 atacamite + 0.2 cuprite + 0.1 dirt.
    const PatinaMaterial& mix = shipped().at("marine patina 3");
    const PatinaMaterial& a = shipped().at("atacamite");
    const PatinaMaterial& c = shipped().at("cuprite");
    const PatinaMaterial& d = shipped().at("dirt");
    for (int i = 0; i < kSpectralSamples; ++i) {
        EXPECT_NEAR(mix.spectral.absorption[i],
                    0.7f * a.spectral.absorption[i] + 0.2f * c.spectral.absorption[i] +
                        0.1f * d.spectral.absorption[i],
                    1e-5f);
        EXPECT_NEAR(mix.spectral.scattering[i],
                    0.7f * a.spectral.scattering[i] + 0.2f * c.spectral.scattering[i] +
                        0.1f * d.spectral.scattering[i],
                    1e-5f);
    }
}

TEST(StackMaterials, MetalWithoutTablesGetsTheIndexOfItsColour)
{
    // Gulbrandsen 2014: n, k from the reflectance r with edge tint r; the normal-incidence
    // Fresnel reflectance ((n-1)^2 + k^2) / ((n+1)^2 + k^2) (Born & Wolf §14.2) gives r back.
    const fs::path file = write_library("gold.toml", R"(
[materials.gold]
kind = "metal"
color = [1.0, 0.78, 0.34]
color_space = "lin_rec709"
)");
    MaterialLibrary lib;
    lib.load(file, colors());
    const PatinaMaterial& gold = lib.at("gold");
    const std::vector<float> r = uplift_reflectance(gold.color, colors());
    for (int i = 0; i < kSpectralSamples; ++i) {
        const float n = gold.spectral.n[i], k = gold.spectral.k[i];
        const float r0 = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
        EXPECT_NEAR(r0, std::clamp(r[i], 1e-4f, 0.9999f), 2e-3f) << i;
    }
}

TEST(StackMaterials, SpectralTablesAndTheirErrors)
{
    const fs::path good = write_library("table.toml", R"(
[materials.ink]
color = [0.2, 0.2, 0.6]
scattering = 2.0
wavelengths_nm = [400, 600, 800]
r_inf = [0.5, 0.25, 0.1]
)");
    MaterialLibrary lib;
    lib.load(good, colors());
    const PatinaMaterial& ink = lib.at("ink");
    EXPECT_NEAR(ink.spectral.r_infinity[grid_index(500)], 0.375f, 1e-6f);
    EXPECT_NEAR(ink.spectral.r_infinity[grid_index(360)], 0.5f, 1e-6f);  // clamped end
    // K = S (1 - R)^2 / (2 R) (D&H 1996 §4.1 inverted) at 600 nm: 2 * 0.5625 / 0.5.
    EXPECT_NEAR(ink.spectral.absorption[grid_index(600)], 2.25f, 1e-5f);

    auto error_of = [](const std::string& text) {
        const fs::path f = write_library("bad.toml", text);
        return patina::test::message_of([&] {
            MaterialLibrary l;
            l.load(f, colors());
        });
    };
    EXPECT_NE(error_of("[materials.a]\ncolor = [0.5, 0.5, 0.5]\nscattering = 1\n"
                       "wavelengths_nm = [400, 500]\nr_inf = [0.5]\n")
                  .find("bad.toml:5:9: 'r_inf' has 1 values for 2 wavelengths"),
              std::string::npos);
    EXPECT_NE(error_of("[materials.a]\nkind = \"metal\"\ncolor = [0.5, 0.5, 0.5]\n"
                       "wavelengths_nm = [400, 500]\nn = [1, 1]\n")
                  .find("give both 'n' and 'k'"),
              std::string::npos);
    EXPECT_NE(error_of("[materials.a]\ncolor = [0.5, 0.5, 0.5]\nscattering = 1\n"
                       "wavelengths_nm = [500, 400]\nr_inf = [0.5, 0.5]\n")
                  .find("'wavelengths_nm' must increase"),
              std::string::npos);
    EXPECT_NE(error_of("[materials.a]\nkind = \"metal\"\ncolor = [0.5, 0.5, 0.5]\n"
                       "wavelengths_nm = [400, 500]\nr_inf = [0.5, 0.5]\n")
                  .find("'r_inf' is for a layer"),
              std::string::npos);
}

TEST(StackMaterials, StackWriterWritesTheMaterialsSection)
{
    const PatinaDomain domain = make_strip_domain(8, 8, 0.1);
    PatinaStep step;
    step.time_years = 6;
    step.base = &shipped().at("copper");
    step.layers.push_back({&shipped().at("tarnish"), "coat", std::vector<float>(64, 0.5f)});
    step.layers.push_back({&shipped().at("marine patina 3"), "coat", std::vector<float>(64, 2.0f)});
    step.layers.push_back({&shipped().at("tarnish"), "coat", std::vector<float>(64, 0.1f)});
    step.total_um.assign(64, 2.6f);
    PatinaOutputOptions options;
    options.preview = false;
    options.script = "test.patina";
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "stack_materials" / "stack";
    fs::remove_all(dir);
    write_patina_step(dir, step, domain, options, colors());

    const toml::table root = toml::parse_file((dir / "stack.toml").string());
    // The existing [patina] keys stay as they were.
    EXPECT_EQ(root["patina"]["base"].value<std::string>(), "copper");
    EXPECT_EQ(root["patina"]["layers"].as_array()->size(), 3u);
    const toml::table* materials = root["patina"]["materials"].as_table();
    ASSERT_NE(materials, nullptr);
    EXPECT_EQ(materials->size(), 3u);  // copper, tarnish (once), marine patina 3
    const toml::table& cu = *(*materials)["copper"].as_table();
    EXPECT_EQ(cu["metal"].value<bool>(), true);
    EXPECT_EQ(cu["wavelengths_nm"].as_array()->size(), static_cast<size_t>(kSpectralSamples));
    EXPECT_NEAR(*cu["n"][grid_index(560)].value<double>(), shipped().at("copper").spectral.n[grid_index(560)], 1e-6);
    const toml::table& marine = *(*materials)["marine patina 3"].as_table();
    EXPECT_EQ(marine["metal"].value<bool>(), false);
    for (const char* key : {"absorption_per_um", "scattering_per_um", "specular"}) {
        ASSERT_NE(marine[key].as_array(), nullptr) << key;
        EXPECT_EQ(marine[key].as_array()->size(), static_cast<size_t>(kSpectralSamples)) << key;
    }
    EXPECT_NEAR(*marine["absorption_per_um"][10].value<double>(),
                shipped().at("marine patina 3").spectral.absorption[10], 1e-6);
    EXPECT_NEAR(*marine["roughness"].value<double>(), 0.5, 1e-6);
}
