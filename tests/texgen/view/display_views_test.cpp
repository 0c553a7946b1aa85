// The viewer's display transforms (texgen/view, docs/viewer.md "Colour"): the views of
// Patina's OCIO config, OCIO's GLSL for the short ones, and for the ACES output transform a
// 65^3 table baked by OCIO, whose lookup (the page's GLSL: the log2 shaper, trilinear
// interpolation of half floats) is checked here against OCIO's CPU processor.
#include "texgen/view/viewer_folder.h"

#include "core/color_management.h"

#include <OpenColorIO/OpenColorIO.h>
#include <Imath/half.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace patina::texgen {
namespace {

    namespace OCIO = OCIO_NAMESPACE;

    std::vector<unsigned char> base64_decode(const std::string& text)
    {
        auto value = [](char c) -> int {
            if (c >= 'A' && c <= 'Z') return c - 'A';
            if (c >= 'a' && c <= 'z') return c - 'a' + 26;
            if (c >= '0' && c <= '9') return c - '0' + 52;
            return c == '+' ? 62 : c == '/' ? 63 : -1;
        };
        std::vector<unsigned char> out;
        int bits = 0, buffer = 0;
        for (char c : text) {
            const int v = value(c);
            if (v < 0)
                continue;  // '=' padding
            buffer = (buffer << 6) | v;
            bits += 6;
            if (bits >= 8) {
                bits -= 8;
                out.push_back(static_cast<unsigned char>((buffer >> bits) & 0xff));
            }
        }
        return out;
    }

}  // namespace

TEST(DisplayViews, ShortViewsAreOciosGlslAndAcesIsABakedTableThatMatchesOcio)
{
    const ColorManager colors(std::filesystem::path(PATINA_SOURCE_DIR) / "ocio" / "config.ocio");
    const nlohmann::json views = nlohmann::json::parse(display_views_json(colors));
    ASSERT_EQ(views.size(), 3u);
    EXPECT_EQ(views[0]["name"], "ACES 1.0 - SDR Video");
    EXPECT_EQ(views[1]["name"], "Un-tone-mapped");
    EXPECT_EQ(views[2]["name"], "Raw");
    EXPECT_FALSE(views[1].contains("lut"));
    EXPECT_NE(views[1]["glsl"].get<std::string>().find("vec4 patina_display(vec4 inPixel)"),
              std::string::npos);
    ASSERT_TRUE(views[0].contains("lut"));
    const int n = views[0]["lut"]["size"];
    ASSERT_EQ(n, 65);
    const std::vector<unsigned char> bytes = base64_decode(views[0]["lut"]["rgba_f16"]);
    ASSERT_EQ(bytes.size(), size_t(n) * n * n * 4 * 2);
    auto texel = [&](int r, int g, int b, int c) {
        Imath::half h;
        h.setBits(static_cast<unsigned short>(bytes[((size_t(b) * n + g) * n + r) * 8 + c * 2] |
                                              bytes[((size_t(b) * n + g) * n + r) * 8 + c * 2 + 1] << 8));
        return float(h);
    };
    // The page's lookup (display_pass.js, viewer_folder.cpp baked_view): eps 2^-10, max 64.
    const double range = std::log2(1.0 + 64.0 * 1024.0);
    auto lookup = [&](const float rgb[3], float out[3]) {
        double x[3];
        int i0[3];
        double f[3];
        for (int c = 0; c < 3; ++c) {
            x[c] = std::clamp(std::log2(1.0 + std::max(rgb[c], 0.0f) * 1024.0) / range, 0.0, 1.0) * (n - 1);
            i0[c] = std::min(static_cast<int>(x[c]), n - 2);
            f[c] = x[c] - i0[c];
        }
        for (int c = 0; c < 3; ++c) {
            double v = 0;
            for (int k = 0; k < 8; ++k) {
                const int dr = k & 1, dg = (k >> 1) & 1, db = (k >> 2) & 1;
                const double w = (dr ? f[0] : 1 - f[0]) * (dg ? f[1] : 1 - f[1]) * (db ? f[2] : 1 - f[2]);
                v += w * texel(i0[0] + dr, i0[1] + dg, i0[2] + db, c);
            }
            out[c] = static_cast<float>(v);
        }
    };
    const OCIO::ConstConfigRcPtr config = OCIO::Config::CreateFromFile(colors.config_path().c_str());
    OCIO::DisplayViewTransformRcPtr t = OCIO::DisplayViewTransform::Create();
    t->setSrc("lin_rec709");
    t->setDisplay("sRGB");
    t->setView("ACES 1.0 - SDR Video");
    const OCIO::ConstCPUProcessorRcPtr cpu = config->getProcessor(t)->getDefaultCPUProcessor();
    // Scene-linear colours from 1/256 to 16 (a grey card to a highlight), log-uniform.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> stops(-8.0, 4.0);
    double worst = 0.0, sum = 0.0;
    const int count = 4000;
    for (int i = 0; i < count; ++i) {
        float rgb[3], want[3], got[3];
        for (float& c : rgb)
            c = static_cast<float>(std::exp2(stops(rng)));
        std::copy(rgb, rgb + 3, want);
        cpu->applyRGB(want);
        lookup(rgb, got);
        for (int c = 0; c < 3; ++c) {
            worst = std::max(worst, double(std::abs(got[c] - want[c])));
            sum += std::abs(got[c] - want[c]);
        }
    }
    std::printf("baked ACES view against OCIO: mean |error| %.5f, max %.5f (display-referred)\n",
                sum / (3.0 * count), worst);
    // Measured: mean 0.00031 (0.08 of an 8-bit code value), max 0.0178 (4.5 codes). The worst
    // are colours of extreme chroma (one channel thousands of times another), where the ACES
    // output transform bends hardest between two grid points; textures stay far from them.
    EXPECT_LE(sum / (3.0 * count), 0.25 / 255.0);
    EXPECT_LE(worst, 6.0 / 255.0);
}

}  // namespace patina::texgen
