// The band quadrature of flatten (band_optics.h) on the optics of a real stack: the urban
// copper sample's materials as `patina-texgen patina` records them (copper's measured n and
// k, the layers' uplifted spectra), against the same stack evaluated in double at every
// nanometre from the paper's closed forms (D&H 1996 §4.1-4.2) and integrated on CIE 15's
// 1 nm grid.
#include "core/color_difference.h"
#include "core/color_management.h"
#include "core/image_io.h"
#include "core/spectrum.h"
#include "texgen/flatten/flat_texel.h"
#include "texgen/flatten/patina_stack_files.h"

#include <patina/shading/fresnel.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace patina::texgen {
namespace {

namespace fs = std::filesystem;

/// A recorded table at `lambda` (linear, constant beyond its ends), in double.
double table_at(const formats::MaterialOptics& m, const std::vector<double>& v, double lambda)
{
    const std::vector<double>& l = m.lambda_nm;
    if (lambda <= l.front())
        return v.front();
    if (lambda >= l.back())
        return v.back();
    const size_t i = static_cast<size_t>(std::upper_bound(l.begin(), l.end(), lambda) - l.begin());
    const double t = (lambda - l[i - 1]) / (l[i] - l[i - 1]);
    return v[i - 1] + t * (v[i] - v[i - 1]);
}

struct Layer {
    double r_top, r_bottom, t;
};

/// §4.1 in double: R = S g / ((S + K) g + 1 + e^−2x), T = 2 e^−x / (...), x = βd.
Layer km(double K, double S, double d)
{
    const double beta = std::sqrt(K * (K + 2.0 * S)), x = beta * d;
    const double g = beta > 0.0 ? (1.0 - std::exp(-2.0 * x)) / beta : 2.0 * d;
    const double den = (S + K) * g + 1.0 + std::exp(-2.0 * x);
    return {S * g / den, S * g / den, 2.0 * std::exp(-x) / den};
}

/// The stack's diffuse reflectance at `lambda` over its base, a metal's once-through
/// reflection left out (flat_texel.h), layers bottom to top with thickness `d`.
double reference_diffuse(const PatinaStackFiles& stack, const std::vector<float>& d, double lambda)
{
    Layer above{0.0, 0.0, 1.0};
    for (size_t l = stack.layers.size(); l-- > 0;) {
        if (!(d[l] > 0.0f))
            continue;
        const formats::MaterialOptics& m = stack.materials.at(stack.layers[l].material);
        const Layer b = km(table_at(m, m.absorption_per_um, lambda),
                           table_at(m, m.scattering_per_um, lambda), d[l]);
        const double den = 1.0 - above.r_bottom * b.r_top;  // §4.2
        above = {above.r_top + above.t * above.t * b.r_top / den,
                 b.r_bottom + b.t * b.t * above.r_bottom / den, above.t * b.t / den};
    }
    const formats::MaterialOptics& base = stack.materials.at(stack.base);
    double rb;
    if (base.metal) {
        // Hemispherical reflectance 2 ∫ F μ dμ, 2000 midpoints, real-arithmetic Fresnel.
        const float n = static_cast<float>(table_at(base, base.n, lambda));
        const float k = static_cast<float>(table_at(base, base.k, lambda));
        double sum = 0.0;
        for (int q = 0; q < 2000; ++q) {
            const double mu = (q + 0.5) / 2000.0;
            sum += shading::fresnel_conductor_real(static_cast<float>(mu), n, k) * mu;
        }
        rb = 2.0 * sum / 2000.0;
    } else {
        const double q = table_at(base, base.absorption_per_um, lambda) /
                         table_at(base, base.scattering_per_um, lambda);
        rb = 1.0 + q - std::sqrt(q * q + 2.0 * q);
    }
    const double r = above.r_top + above.t * above.t * rb / (1.0 - above.r_bottom * rb);
    return base.metal ? r - above.t * above.t * rb : r;
}

TEST(BandOptics, TwentyNanometreBandsAgreeWithANanometreIntegrationOnRealOptics)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "band_optics_test";
    fs::remove_all(dir);
    const std::string command = std::string(PATINA_TEST_BIN_DIR) + "/patina-texgen patina '" +
                                PATINA_SOURCE_DIR + "/samples/copper_strips/urban.patina' -o '" +
                                (dir / "urban").string() +
                                "' --resolution 16 --times 1,6,30 --quiet --no-preview";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;

    const ColorManager colors(fs::path(PATINA_SOURCE_DIR) / "ocio/config.ocio");
    const BandsToRgb to_rgb(colors);
    const Imath::V3d white(0.95047, 1.0, 1.08883);  // D65, CIE 15:2004 Table T.3
    double worst = 0.0;
    int texels = 0;
    for (const char* step : {"t01", "t06", "t30"}) {
        const PatinaStackFiles stack = read_patina_stack(dir / "urban" / step);
        const BandStack bands = band_stack(stack);
        std::vector<ImageData> maps;
        for (const StackLayerFiles& l : stack.layers)
            maps.push_back(read_image(l.files.front()));
        for (int y = 0; y < 16; y += 5)
            for (int x = 0; x < 16; x += 5) {
                std::vector<float> d;
                for (size_t l = 0; l < maps.size(); ++l)
                    d.push_back(maps[l].at(x, y, maps[l].channel(stack.layers[l].channel)));
                const Imath::V3f flat = flatten_texel(bands, d, to_rgb).diffuse;
                const Xyz xyz = spectrum_to_xyz(
                    [&](double lambda) { return reference_diffuse(stack, d, lambda); });
                float ref[3] = {static_cast<float>(xyz[0]), static_cast<float>(xyz[1]),
                                static_cast<float>(xyz[2])};
                float got[3] = {flat.x, flat.y, flat.z};
                colors.convert("lin_rec709", "CIE-XYZ-D65", got, 1);
                const double de =
                    delta_e2000(xyz_to_lab(Imath::V3d(ref[0], ref[1], ref[2]), white),
                                xyz_to_lab(Imath::V3d(got[0], got[1], got[2]), white));
                worst = std::max(worst, de);
                ++texels;
                EXPECT_LT(de, 0.1) << step << " texel (" << x << ", " << y << ")";
            }
    }
    EXPECT_EQ(texels, 48);  // worst measured: 0.04
    std::printf("band quadrature on the urban stacks: worst ΔE00 %.3f over %d texels\n", worst,
                texels);
}

}  // namespace
}  // namespace patina::texgen
