// One texel three ways: the layered_km shader (what patina-render shows), flatten (what
// export writes) and the stack's preview compute one stack model
// (patina/shading/layer_stack.h) on the optics the stack records.
#include "layered_fixture.h"

#include "core/spectrum.h"
#include "texgen/flatten/flat_texel.h"
#include "texgen/patina/stack_preview.h"

namespace patina::test {
namespace {

    // Index-matched interfaces (specular 0): the shader is its Kubelka-Munk diffuse term
    // alone, f(wo, wi) = R_d / π at every pair of directions, with no glossy lobe and no
    // coupling. K varies with wavelength, so every wavelength sees another stack.
    const TestMaterial kStone{"stone", false, 0.40f, 0.08f, 1.0f, 0.0f, 0.6f};
    const TestMaterial kGreen{"green", false, 1.2f, 0.05f, 0.35f, 0.0f, 0.5f};
    const TestMaterial kBrown{"brown", false, 0.1f, 2.0f, 1.2f, 0.0f, 0.25f};

    /// A test material as a stack.toml records it (the floats the shader reads).
    formats::MaterialOptics optics_of(const TestMaterial& m)
    {
        formats::MaterialOptics o;
        o.name = m.name;
        o.roughness = m.roughness;
        o.lambda_nm = {360.0, 830.0};
        o.absorption_per_um = {m.K, m.K_830};
        o.scattering_per_um = {m.S, m.S};
        o.specular = {m.specular, m.specular};
        return o;
    }

    texgen::BandStack band_stack_of(const TestStack& stack)
    {
        formats::PatinaTable t;
        t.base = stack.base;
        for (const TestMaterial& m : stack.materials)
            t.materials.emplace(m.name, optics_of(m));
        for (const TestLayer& l : stack.layers) {
            formats::PatinaLayer entry;
            entry.material = l.material;
            t.layers.push_back(entry);
        }
        return texgen::band_stack(t, "test/stack.toml");
    }

    /// The shader's R_d = π f at `lambda` (up to PATINA_MAX_WAVELENGTHS of them).
    std::vector<float> shader_reflectance(Layered& shader, const std::vector<float>& lambda)
    {
        std::vector<float> out;
        for (size_t first = 0; first < lambda.size(); first += PATINA_MAX_WAVELENGTHS) {
            PatinaWavelengths wl{};
            wl.count = static_cast<int>(
                std::min<size_t>(PATINA_MAX_WAVELENGTHS, lambda.size() - first));
            for (int i = 0; i < wl.count; ++i)
                wl.lambda_nm[i] = lambda[first + i];
            shader.set_wavelengths(wl);
            const Spectrum f = shader.f(direction_deg(20.0f, 0.0f), direction_deg(55.0f, 150.0f));
            for (int i = 0; i < wl.count; ++i)
                out.push_back(f[i] * shading::kPi);
        }
        return out;
    }

    /// The wavelengths of layered_km's grid, 360-830 nm every 5 nm.
    std::vector<float> grid_wavelengths()
    {
        std::vector<float> grid;
        for (int i = 0; i < 95; ++i)
            grid.push_back(360.0f + 5.0f * i);
        return grid;
    }

    /// A reflectance on that grid (linear between its values) as linear Rec.709 under D65:
    /// CIE 15's 1 nm integration, then OCIO.
    Imath::V3f grid_colour(const std::vector<float>& spectrum, const ColorManager& colors)
    {
        const Xyz xyz = spectrum_to_xyz([&](double lambda) {
            const double x = std::clamp((lambda - 360.0) / 5.0, 0.0, 94.0);
            const int i = std::min(static_cast<int>(x), 93);
            return spectrum[i] + (x - i) * (spectrum[i + 1] - spectrum[i]);
        });
        float rgb[3] = {static_cast<float>(xyz[0]), static_cast<float>(xyz[1]),
                        static_cast<float>(xyz[2])};
        colors.convert("CIE-XYZ-D65", "lin_rec709", rgb, 1);
        return {rgb[0], rgb[1], rgb[2]};
    }

}  // namespace

TEST(OneStackModel, LayeredKmFlattenAndThePreviewGiveOneAnswer)
{
    const TestStack stack{"stone", {{"brown", 0.4f}, {"green", 1.2f}}, {kStone, kGreen, kBrown}};
    Layered shader(write_stack("one_stack_model", stack));
    ASSERT_TRUE(shader) << shader.errors();
    const texgen::BandStack bands = band_stack_of(stack);
    const std::vector<float> d{0.4f, 1.2f};

    // 1. The shader and flatten at flatten's wavelengths: the same number.
    std::vector<float> band_lambda;
    for (int i = 0; i < texgen::kBandCount; ++i)
        band_lambda.push_back(texgen::band_wavelength(i));
    const std::vector<float> rendered = shader_reflectance(shader, band_lambda);
    const texgen::Bands flat = texgen::stack_diffuse(bands, d, false);
    for (int i = 0; i < texgen::kBandCount; ++i)
        EXPECT_NEAR(rendered[i], flat[i / 4][i % 4], 2e-6f * flat[i / 4][i % 4])
            << band_lambda[i] << " nm";
    // The bands see K vary (not a vacuous test).
    EXPECT_GT(*std::max_element(rendered.begin(), rendered.end()) -
                  *std::min_element(rendered.begin(), rendered.end()),
              0.05f);

    // 2. The shader's colour over the whole spectrum (5 nm, layered_km's grid, integrated
    //    on CIE 15's 1 nm grid under D65) and flatten's colour from its 16 bands agree to
    //    the quadrature (docs/flatten.md).
    const ColorManager colors(fs::path(PATINA_SOURCE_DIR) / "ocio" / "config.ocio");
    const Imath::V3f rgb = grid_colour(shader_reflectance(shader, grid_wavelengths()), colors);
    const texgen::BandsToRgb to_rgb(colors);
    const texgen::FlatTexel texel = texgen::flatten_texel(bands, d, to_rgb);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(texel.diffuse[c], rgb[c], 3e-4f) << "channel " << c;  // 1e-4 measured

    // 3. The preview is flatten's diffuse albedo, bit for bit.
    const std::vector<std::vector<float>> per_layer{{d[0]}, {d[1]}};
    const Imath::V3f preview = texgen::stack_diffuse_color(bands, per_layer, 1, to_rgb).front();
    for (int c = 0; c < 3; ++c)
        EXPECT_EQ(preview[c], texel.diffuse[c]) << "channel " << c;
}

TEST(OneStackModel, FlattenComputesTheShadersAlbedo)
{
    // Interfaces that reflect (a copper base, layers of specular 0.08 and 0.04): the texel's
    // directional albedo as flatten computes it for the glTF fit (texel_albedo, per colour
    // channel) against the shader's own albedo at every wavelength of its 5 nm grid,
    // integrated to a colour, at the 8 cosines the fit uses.
    const TestMaterial copper{"copper", true, 0, -1, 0, 0.9f, 0.2f, 0.27f, 3.4f};
    const TestMaterial brown{"brown", false, 0.1f, 2.0f, 1.2f, 0.08f, 0.25f};
    const TestMaterial green{"green", false, 1.2f, 0.05f, 0.35f, 0.04f, 0.5f};
    const TestStack stack{"copper", {{"brown", 0.3f}, {"green", 0.6f}}, {copper, brown, green}};
    Layered shader(write_stack("one_stack_albedo", stack));
    ASSERT_TRUE(shader) << shader.errors();

    formats::PatinaTable t;
    t.base = "copper";
    formats::MaterialOptics c;
    c.name = "copper";
    c.metal = true;
    c.roughness = copper.roughness;
    c.lambda_nm = {360.0, 830.0};
    c.n = {copper.n, copper.n};
    c.k = {copper.k, copper.k};
    c.specular = {copper.specular, copper.specular};
    t.materials.emplace("copper", c);
    for (const TestMaterial& m : {brown, green}) {
        t.materials.emplace(m.name, optics_of(m));
        formats::PatinaLayer l;
        l.material = m.name;
        t.layers.push_back(l);
    }
    texgen::BandStack bands = texgen::band_stack(t, "test/stack.toml");
    const ColorManager colors(fs::path(PATINA_SOURCE_DIR) / "ocio" / "config.ocio");
    const texgen::BandsToRgb to_rgb(colors);
    texgen::tabulate_lobe_albedos(bands, to_rgb);
    const std::vector<float> d{0.3f, 0.6f};
    const texgen::FlatTexel texel = texgen::flatten_texel(
        bands, d, to_rgb, {&texgen::gltf_albedo_model(), texgen::GltfTarget::khronos});
    const texgen::AlbedoParts parts = texgen::texel_albedo(texel);

    double worst = 0.0;
    for (int g = 0; g < shading::kGaussNodes; ++g) {
        const float mu = shading::kGaussMu[g];
        const Vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
        const std::vector<float> grid = grid_wavelengths();
        std::vector<float> spectrum;
        for (size_t first = 0; first < grid.size(); first += PATINA_MAX_WAVELENGTHS) {
            PatinaWavelengths wl{};
            wl.count = static_cast<int>(std::min<size_t>(PATINA_MAX_WAVELENGTHS, grid.size() - first));
            for (int i = 0; i < wl.count; ++i)
                wl.lambda_nm[i] = grid[first + i];
            shader.set_wavelengths(wl);
            const Spectrum a = shader.albedo(wo);
            spectrum.insert(spectrum.end(), a.begin(), a.begin() + wl.count);
        }
        const Imath::V3f rgb = grid_colour(spectrum, colors);
        for (int k = 0; k < 3; ++k) {
            const double flat = parts.diffuse[g][k] + parts.glossy[g][k];
            worst = std::max(worst, std::abs(flat - rgb[k]));
            EXPECT_NEAR(flat, rgb[k], 0.002) << "cosine " << mu << " channel " << k;  // 0.0004 measured
        }
    }
    std::printf("[ albedo ] flatten's texel albedo against layered_km's: worst %.4f\n", worst);
}

}  // namespace patina::test
