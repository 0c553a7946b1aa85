// The colour pipeline end to end against a measured chart (docs/lookdev.md): the
// ColorChecker of samples/lookdev/colorchecker.toml (Ohta 1997's measured spectra under a
// uniform D65 sky) rendered by patina-render, each patch measured in the EXR and the PNG,
// against CIELAB computed directly from the same spectra under the same illuminant and
// observer (CIE 1931 2°, D65; CIE 15:2004).
#include "render_fixture.h"

#include "core/color_difference.h"
#include "core/spectrum.h"
#include "core/spectrum_csv.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <map>
#include <cstdio>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

const fs::path kChart = fs::path(PATINA_SOURCE_DIR) / "samples" / "lookdev" / "colorchecker.toml";
const fs::path kSpectra = fs::path(PATINA_SOURCE_DIR) / "data" / "colorchecker_ohta1997.csv";

/// The CIELAB of every patch from its spectrum (spectrum_to_xyz: 1 nm, white Y = 1), and
/// the names.
struct Reference {
    std::vector<std::string> names;
    std::vector<patina::Xyz> xyz;
    patina::Xyz white{};
};

Reference reference()
{
    const patina::SpectrumCsv csv = patina::read_spectrum_csv(kSpectra);
    Reference r;
    r.names = csv.columns;
    for (const std::vector<double>& v : csv.values) {
        // Linear between the 5 nm samples, held at the end values (as the renderer's
        // tabulated spectra are).
        const patina::SpectrumFn reflectance = [&](double lambda) {
            if (lambda <= csv.lambda_nm.front())
                return v.front();
            if (lambda >= csv.lambda_nm.back())
                return v.back();
            const size_t i = static_cast<size_t>(std::upper_bound(csv.lambda_nm.begin(),
                                                                  csv.lambda_nm.end(), lambda) -
                                                 csv.lambda_nm.begin());
            const double t = (lambda - csv.lambda_nm[i - 1]) / (csv.lambda_nm[i] - csv.lambda_nm[i - 1]);
            return v[i - 1] + t * (v[i] - v[i - 1]);
        };
        r.xyz.push_back(patina::spectrum_to_xyz(reflectance));
    }
    r.white = patina::spectrum_to_xyz([](double) { return 1.0; });
    return r;
}

Imath::V3d v3(const patina::Xyz& x)
{
    return {x[0], x[1], x[2]};
}

/// The mean of each patch's central 40 x 40 pixels (the chart's layout: 0.9 squares 1 apart,
/// centred, one unit 400 / 2 / (20 tan 6°) pixels at 600 x 400).
std::vector<std::array<double, 3>> patch_means(const fs::path& image)
{
    OIIO::ImageBuf buf(image.string());
    EXPECT_TRUE(buf.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << buf.geterror();
    const int w = buf.spec().width, h = buf.spec().height;
    const double unit = 0.5 * h / (20.0 * std::tan(6.0 * M_PI / 180.0));
    std::vector<std::array<double, 3>> means;
    for (int i = 0; i < 24; ++i) {
        const double x = -2.5 + i % 6, y = 1.5 - i / 6;
        const int cx = static_cast<int>(std::lround(0.5 * w + x * unit));
        const int cy = static_cast<int>(std::lround(0.5 * h - y * unit));
        const OIIO::ROI box(cx - 20, cx + 20, cy - 20, cy + 20, 0, 1, 0, 3);
        std::vector<float> px(40 * 40 * 3);
        buf.get_pixels(box, OIIO::TypeDesc::FLOAT, px.data());
        std::array<double, 3> m{0, 0, 0};
        for (size_t p = 0; p < px.size(); p += 3)
            for (int c = 0; c < 3; ++c)
                m[c] += px[p + c];
        for (double& c : m)
            c /= 40.0 * 40.0;
        means.push_back(m);
    }
    return means;
}

fs::path render(const fs::path& scene, const std::string& name)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "colorchecker" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    pr::PluginSearch search;
    search.bundled = false;
    search.environment = false;
    search.command_line = {PATINA_TEST_PLUGIN_DIR};
    pr::RenderOptions opt;
    opt.output = dir / "chart.exr";
    opt.quiet = true;
    pr::render_scene_file(scene, search, opt);
    return opt.output;
}

struct Errors {
    std::vector<double> de;
    double mean() const
    {
        double s = 0;
        for (double d : de)
            s += d;
        return s / static_cast<double>(de.size());
    }
    double max() const { return *std::max_element(de.begin(), de.end()); }
};

/// ΔE2000 of each patch of the working-space EXR against the reference, printed as a table.
Errors measure_exr(const fs::path& exr, const Reference& ref, const std::string& title)
{
    const patina::ColorManager& colors = patina::default_host().colors();
    const std::vector<std::array<double, 3>> rgb = patch_means(exr);
    // The pipeline's white: the working space's (1, 1, 1) in XYZ (D65 at Y = 1).
    float white[3] = {1, 1, 1};
    colors.convert(colors.working_space(), "CIE-XYZ-D65", white, 1);
    Errors e;
    std::printf("%s\n%-22s %22s %22s %7s\n", title.c_str(), "patch", "rendered L* a* b*",
                "reference L* a* b*", "dE2000");
    for (size_t i = 0; i < rgb.size(); ++i) {
        float xyz[3] = {float(rgb[i][0]), float(rgb[i][1]), float(rgb[i][2])};
        colors.convert(colors.working_space(), "CIE-XYZ-D65", xyz, 1);
        const patina::Lab got =
            patina::xyz_to_lab({xyz[0], xyz[1], xyz[2]}, {white[0], white[1], white[2]});
        const patina::Lab want = patina::xyz_to_lab(v3(ref.xyz[i]), v3(ref.white));
        e.de.push_back(patina::delta_e2000(got, want));
        std::printf("%-22s %6.2f %6.2f %6.2f   %6.2f %6.2f %6.2f   %6.3f\n", ref.names[i].c_str(),
                    got.L, got.a, got.b, want.L, want.a, want.b, e.de.back());
    }
    std::printf("mean %.3f, max %.3f\n", e.mean(), e.max());
    return e;
}

}  // namespace

// The measured spectra, rendered: the error of the whole spectral pipeline (wavelength
// sampling, the CIE tables, XYZ to ACEScg and back through OCIO).
TEST(ColorChecker, MeasuredSpectraRenderWithinHalfADeltaE2000)
{
    const Reference ref = reference();
    ASSERT_EQ(ref.names.size(), 24u);
    const Errors e = measure_exr(render(kChart, "spectral"), ref, "measured spectra, rendered");
    // The bounds: mean ΔE2000 <= 0.5, max <= 1.0.
    EXPECT_LE(e.mean(), 0.5);
    EXPECT_LE(e.max(), 1.0);
}

namespace {

/// The chart with every patch given as a colour in `space` (the reference's XYZ converted
/// by OCIO, clipped to [0, 1]), uplifted by the renderer: the path a scene takes when it
/// knows only RGB. Returns the scene and which patches were clipped.
fs::path uplift_chart(const Reference& ref, const std::string& space, std::vector<bool>& clipped)
{
    const patina::ColorManager& colors = patina::default_host().colors();
    std::ifstream in(kChart);
    std::stringstream text;
    text << in.rdbuf();
    std::string scene = text.str();
    clipped.assign(ref.xyz.size(), false);
    for (size_t i = 0; i < ref.xyz.size(); ++i) {
        float rgb[3] = {float(ref.xyz[i][0]), float(ref.xyz[i][1]), float(ref.xyz[i][2])};
        colors.convert("CIE-XYZ-D65", space, rgb, 1);
        for (float& c : rgb)
            if (c < 0.0f || c > 1.0f) {
                clipped[i] = true;
                c = std::clamp(c, 0.0f, 1.0f);
            }
        const std::string from = fmt::format(
            "reflectance_spectrum = {{ file = \"../../data/colorchecker_ohta1997.csv\", column = "
            "\"{}\" }}",
            ref.names[i]);
        const size_t at = scene.find(from);
        EXPECT_NE(at, std::string::npos) << ref.names[i];
        scene.replace(at, from.size(),
                      fmt::format("reflectance = {{ rgb = [{:.9g}, {:.9g}, {:.9g}], colorspace = "
                                  "\"{}\" }}",
                                  rgb[0], rgb[1], rgb[2], space));
    }
    return render_test::write_scene("colorchecker_" + space, scene);
}

/// IEC 61966-2-1 (sRGB): the encoding of a linear value in [0, 1].
double srgb_encode(double v)
{
    v = std::clamp(v, 0.0, 1.0);
    return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

double srgb_decode(double e)
{
    return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
}

}  // namespace

// The same chart given as RGB colours (the uplift path, Jakob & Hanika 2019): reported, and
// bounded by what it measures. A colour inside the space's gamut comes back as a smooth
// spectrum of the same XYZ under D65 (a metamer of the measured one), so in-gamut patches
// land close; a patch outside [0, 1] in the space is clipped first and lands further.
TEST(ColorChecker, RgbPatchesThroughTheUpliftAreReported)
{
    const Reference ref = reference();
    for (const std::string space : {"lin_rec709", "ACEScg"}) {
        std::vector<bool> clipped;
        const Errors e = measure_exr(render(uplift_chart(ref, space, clipped), "uplift_" + space),
                                     ref, "the chart as " + space + " colours, uplifted");
        Errors inside;
        for (size_t i = 0; i < e.de.size(); ++i) {
            if (clipped[i])
                std::printf("  clipped to [0, 1] in %s: %s (dE2000 %.3f)\n", space.c_str(),
                            ref.names[i].c_str(), e.de[i]);
            else
                inside.de.push_back(e.de[i]);
        }
        ASSERT_FALSE(inside.de.empty());
        // An in-gamut colour is reproduced up to the uplift's fit and the sampling noise.
        EXPECT_LE(inside.mean(), 0.5) << space;
        EXPECT_LE(inside.max(), 1.0) << space;
    }
}

// The display PNG (the chart's view, Un-tone-mapped: scene-linear through the sRGB curve)
// against the sRGB encoding of the reference values (IEC 61966-2-1, computed here), patch
// by patch: within one code value on average, and in ΔE2000.
TEST(ColorChecker, DisplayPngIsTheSrgbEncodingOfTheReference)
{
    const Reference ref = reference();
    const patina::ColorManager& colors = patina::default_host().colors();
    const fs::path exr = render(kChart, "display");
    const std::vector<std::array<double, 3>> png = patch_means(fs::path(exr).replace_extension(".png"));
    float white[3] = {1, 1, 1};
    colors.convert("lin_rec709", "CIE-XYZ-D65", white, 1);
    Errors e;
    double code_sum = 0, code_max = 0;
    std::printf("%-22s %20s %20s %7s\n", "patch", "PNG sRGB (0-255)", "reference sRGB", "dE2000");
    for (size_t i = 0; i < ref.xyz.size(); ++i) {
        float lin[3] = {float(ref.xyz[i][0]), float(ref.xyz[i][1]), float(ref.xyz[i][2])};
        colors.convert("CIE-XYZ-D65", "lin_rec709", lin, 1);
        std::array<double, 3> want{};
        float got_lin[3], want_lin[3];
        for (int c = 0; c < 3; ++c) {
            want[c] = 255.0 * srgb_encode(lin[c]);
            // patch_means read the 8-bit PNG as floats in [0, 1].
            const double got = 255.0 * png[i][c];
            code_sum += std::abs(got - want[c]);
            code_max = std::max(code_max, std::abs(got - want[c]));
            got_lin[c] = float(srgb_decode(png[i][c]));
            want_lin[c] = float(srgb_decode(want[c] / 255.0));
        }
        colors.convert("lin_rec709", "CIE-XYZ-D65", got_lin, 1);
        colors.convert("lin_rec709", "CIE-XYZ-D65", want_lin, 1);
        const Imath::V3d w(white[0], white[1], white[2]);
        e.de.push_back(patina::delta_e2000(
            patina::xyz_to_lab({got_lin[0], got_lin[1], got_lin[2]}, w),
            patina::xyz_to_lab({want_lin[0], want_lin[1], want_lin[2]}, w)));
        std::printf("%-22s %6.1f %6.1f %6.1f   %6.1f %6.1f %6.1f   %6.3f\n", ref.names[i].c_str(),
                    255.0 * png[i][0], 255.0 * png[i][1], 255.0 * png[i][2], want[0], want[1],
                    want[2], e.de.back());
    }
    const double code_mean = code_sum / (3.0 * double(ref.xyz.size()));
    std::printf("code values: mean |difference| %.3f, max %.3f; dE2000 mean %.3f, max %.3f\n",
                code_mean, code_max, e.mean(), e.max());
    EXPECT_LE(code_mean, 1.0);
    EXPECT_LE(e.mean(), 0.5);
    EXPECT_LE(e.max(), 1.0);
}

namespace {

const fs::path kArgyllRef = "/usr/share/color/argyll/ref";

/// The numbers between BEGIN_DATA and END_DATA of an ArgyllCMS CGATS file (.sp, .cie), and
/// the value of `keyword` in its header ("" when absent).
struct Cgats {
    std::vector<std::vector<std::string>> rows;
    std::map<std::string, std::string> keywords;
};

Cgats read_cgats(const fs::path& file)
{
    std::ifstream in(file);
    EXPECT_TRUE(in) << "cannot read " << file << ": install Debian's argyll-ref (scripts/bootstrap.sh)";
    Cgats c;
    std::string line;
    bool data = false;
    while (std::getline(in, line)) {
        std::istringstream words(line);
        std::vector<std::string> w;
        for (std::string s; words >> s;)
            w.push_back(s);
        if (w.empty())
            continue;
        if (w[0] == "BEGIN_DATA")
            data = true;
        else if (w[0] == "END_DATA")
            data = false;
        else if (data)
            c.rows.push_back(w);
        else if (w.size() == 2)
            c.keywords[w[0]] = w[1].size() > 1 && w[1].front() == '"' ? w[1].substr(1, w[1].size() - 2) : w[1];
    }
    return c;
}

}  // namespace

// The chart's published reference: ArgyllCMS's X-Rite/GretagMacbeth ColorChecker CIELAB
// under D50 (Debian argyll-ref, ref/ColorChecker.cie), against Ohta's spectra under Argyll's
// CIE D50 (ref/D50_1.0.sp) with the same observer. A different chart and measurement, so it
// is reported (the table in docs/lookdev.md), not held to a bound of the pipeline; what is
// asserted is that this comparison reproduces the figures the reference data's own notes
// give for it (CIEDE2000 mean 0.97, max 1.68 at orange), so the table is computed right.
TEST(ColorChecker, PublishedReferenceIsReported)
{
    const Cgats d50 = read_cgats(kArgyllRef / "D50_1.0.sp");
    const Cgats chart = read_cgats(kArgyllRef / "ColorChecker.cie");
    ASSERT_EQ(d50.rows.size(), 1u);
    ASSERT_EQ(chart.rows.size(), 24u);
    const double start = std::stod(d50.keywords.at("SPECTRAL_START_NM"));
    const double end = std::stod(d50.keywords.at("SPECTRAL_END_NM"));
    const size_t bands = d50.rows[0].size();
    ASSERT_EQ(bands, std::stoul(d50.keywords.at("SPECTRAL_BANDS")));
    const double step = (end - start) / double(bands - 1);
    const patina::SpectrumFn illuminant = [&](double lambda) {
        const double x = std::clamp((lambda - start) / step, 0.0, double(bands - 1));
        const size_t i = std::min(static_cast<size_t>(x), bands - 2);
        const double t = x - double(i);
        return (1 - t) * std::stod(d50.rows[0][i]) + t * std::stod(d50.rows[0][i + 1]);
    };
    const patina::SpectrumCsv csv = patina::read_spectrum_csv(kSpectra);
    const patina::Xyz white = patina::spectrum_to_xyz([](double) { return 1.0; }, illuminant);
    Errors e;
    size_t worst = 0;
    std::printf("%-22s %22s %22s %7s\n", "patch", "Ohta 1997 under D50", "argyll-ref (D50)", "dE2000");
    for (size_t p = 0; p < 24; ++p) {
        const std::vector<double>& v = csv.values[p];
        const patina::Xyz xyz = patina::spectrum_to_xyz(
            [&](double lambda) {
                const double x = std::clamp((lambda - 380.0) / 5.0, 0.0, 80.0);
                const size_t i = std::min(static_cast<size_t>(x), size_t(79));
                return v[i] + (x - double(i)) * (v[i + 1] - v[i]);
            },
            illuminant);
        const patina::Lab ours = patina::xyz_to_lab(v3(xyz), v3(white));
        const patina::Lab theirs{std::stod(chart.rows[p][1]), std::stod(chart.rows[p][2]),
                                 std::stod(chart.rows[p][3])};
        e.de.push_back(patina::delta_e2000(ours, theirs));
        if (e.de.back() > e.de[worst])
            worst = p;
        std::printf("%-22s %6.2f %6.2f %6.2f   %6.2f %6.2f %6.2f   %6.3f\n", csv.columns[p].c_str(),
                    ours.L, ours.a, ours.b, theirs.L, theirs.a, theirs.b, e.de.back());
    }
    std::printf("mean %.3f, max %.3f (%s)\n", e.mean(), e.max(), csv.columns[worst].c_str());
    EXPECT_NEAR(e.mean(), 0.97, 0.1);
    EXPECT_NEAR(e.max(), 1.68, 0.1);
    EXPECT_EQ(csv.columns[worst], "orange");
}
