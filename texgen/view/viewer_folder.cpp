#include "texgen/view/viewer_folder.h"

#include "texgen/view/variant_ages.h"

#include "core/color_management.h"
#include "core/image_io.h"
#include "texgen/sun/sky_map.h"

#include <Imath/half.h>
#include <OpenColorIO/OpenColorIO.h>
#include <OpenImageIO/strutil.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace patina::texgen {

namespace fs = std::filesystem;
namespace OCIO = OCIO_NAMESPACE;
using nlohmann::json;

namespace {

    std::string read_bytes(const fs::path& file)
    {
        std::ifstream in(file, std::ios::binary);
        if (!in)
            throw std::runtime_error(fmt::format("view: cannot read '{}'", file.string()));
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }

    /// The JSON chunk of a binary glTF (glTF 2.0 §4.4: a 12-byte header, then chunks of
    /// length, type and data; the first is JSON).
    json glb_json(const std::string& glb, const fs::path& file)
    {
        auto u32 = [&](size_t at) {
            uint32_t v = 0;
            std::memcpy(&v, glb.data() + at, 4);
            return v;
        };
        if (glb.size() < 20 || u32(0) != 0x46546C67u /* "glTF" */ || u32(16) != 0x4E4F534Au)
            throw std::runtime_error(fmt::format(
                "view: '{}' is not a binary glTF (.glb) written by `patina-texgen export`",
                file.string()));
        const uint32_t length = u32(12);
        if (20 + size_t(length) > glb.size())
            throw std::runtime_error(fmt::format("view: '{}' is cut short", file.string()));
        return json::parse(glb.substr(20, length));
    }

    /// The OCIO colour space of three.js's working space (linear Rec.709 primaries, D65).
    std::string linear_rec709(const OCIO::ConstConfigRcPtr& config, const fs::path& path)
    {
        for (const char* name : {"lin_rec709", "Linear Rec.709 (sRGB)", "lin_srgb"})
            if (config->getColorSpace(name))
                return name;
        throw std::runtime_error(fmt::format(
            "view: the OCIO config '{}' has no linear Rec.709 colour space (lin_rec709), the "
            "space the page renders in", path.string()));
    }

    /// Views whose OCIO shader is longer than this (the ACES output transform: thousands of
    /// operations a pixel, a quarter of a frame in a software WebGL) are baked instead.
    constexpr size_t kLongShader = 4096;
    /// The baked views: a lut_size^3 table over a log2 shaper from 0 to kLutMax (OCIO's CPU
    /// processor at every grid point), looked up trilinearly in the page.
    constexpr int kLutSize = 65;
    constexpr double kLutEpsilon = 1.0 / 1024.0, kLutMax = 64.0;

    /// The view baked by OCIO into a 3D LUT: the table (RGBA half floats, base64) and the
    /// GLSL that looks it up, with the shaper x = log2(1 + c / eps) / log2(1 + max / eps).
    json baked_view(const OCIO::ConstProcessorRcPtr& processor)
    {
        const OCIO::ConstCPUProcessorRcPtr cpu = processor->getDefaultCPUProcessor();
        const double range = std::log2(1.0 + kLutMax / kLutEpsilon);
        std::vector<Imath::half> table(static_cast<size_t>(kLutSize) * kLutSize * kLutSize * 4);
        auto scene_value = [&](int i) {
            return static_cast<float>(kLutEpsilon * (std::exp2(range * i / (kLutSize - 1)) - 1.0));
        };
        size_t at = 0;
        for (int b = 0; b < kLutSize; ++b)  // WebGL's 3D texture: x (red) fastest
            for (int g = 0; g < kLutSize; ++g)
                for (int r = 0; r < kLutSize; ++r) {
                    float rgb[3] = {scene_value(r), scene_value(g), scene_value(b)};
                    cpu->applyRGB(rgb);
                    table[at++] = rgb[0];
                    table[at++] = rgb[1];
                    table[at++] = rgb[2];
                    table[at++] = 1.0f;
                }
        const std::string bytes(reinterpret_cast<const char*>(table.data()), table.size() * 2);
        const std::string glsl = fmt::format(
            "uniform highp sampler3D patina_lut;\n"
            "vec4 patina_display(vec4 c)\n{{\n"
            "  vec3 x = log2(1.0 + max(c.rgb, vec3(0.0)) / {0:.9g}) / {1:.9g};\n"
            "  x = clamp(x, 0.0, 1.0) * {2:.9g} + {3:.9g};\n"
            "  return vec4(texture(patina_lut, x).rgb, c.a);\n}}\n",
            kLutEpsilon, range, (kLutSize - 1.0) / kLutSize, 0.5 / kLutSize);
        return {{"glsl", glsl}, {"lut", {{"size", kLutSize}, {"rgba_f16", OIIO::Strutil::base64_encode(bytes)}}}};
    }

    /// The sky of `options` in three.js's equirectangular layout (its equirectUv: u from
    /// atan2(z, x), v from asin(y), the first row the nadir), RGB floats, base64.
    json environment(const std::string& name, const SkyMapOptions& options, int width)
    {
        const SkyModel sky(options);
        const int height = width / 2;
        std::vector<float> rgba(static_cast<size_t>(width) * height * 4);
        for (int j = 0; j < height; ++j)
            for (int i = 0; i < width; ++i) {
                const double phi = ((i + 0.5) / width - 0.5) * 2.0 * M_PI;
                const double lat = ((j + 0.5) / height - 0.5) * M_PI;
                const Imath::V3d d(std::cos(lat) * std::cos(phi), std::sin(lat),
                                   std::cos(lat) * std::sin(phi));
                const float v = static_cast<float>(sky.radiance(d));
                float* p = &rgba[(static_cast<size_t>(j) * width + i) * 4];
                p[0] = p[1] = p[2] = v;
                p[3] = 1.0f;
            }
        const std::string bytes(reinterpret_cast<const char*>(rgba.data()), rgba.size() * 4);
        json sun = nullptr;
        if (sky.sun_irradiance() > 0.0)
            sun = {{"direction", {sky.sun_direction().x, sky.sun_direction().y, sky.sun_direction().z}},
                   {"irradiance", sky.sun_irradiance()}};
        return {{"name", name}, {"width", width}, {"height", height},
                {"rgba_f32", OIIO::Strutil::base64_encode(bytes)}, {"sun", sun}};
    }

}  // namespace

fs::path viewer_bundle_dir()
{
    std::vector<fs::path> tried;
    if (const char* env = std::getenv("PATINA_VIEWER_DIR"); env && *env)
        tried.emplace_back(env);
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec)
        tried.push_back((exe.parent_path() / ".." / "share" / "patina" / "viewer").lexically_normal());
    for (const fs::path& dir : tried)
        if (fs::is_regular_file(dir / "viewer.js", ec) && fs::is_regular_file(dir / "index.html", ec))
            return dir;
    std::string where;
    for (const fs::path& dir : tried)
        where += (where.empty() ? "" : ", ") + dir.string();
    throw std::runtime_error(fmt::format(
        "view: the built viewer (viewer.js, index.html) is in none of: {}; build the project "
        "(the viewer is built from viewer/ with npm's esbuild) or set PATINA_VIEWER_DIR",
        where));
}

std::string display_views_json(const ColorManager& colors)
{
    // The display's views from the page's working space: OCIO's own GLSL (ES 3.0), or baked.
    const OCIO::ConstConfigRcPtr config = OCIO::Config::CreateFromFile(colors.config_path().c_str());
    const std::string source = linear_rec709(config, colors.config_path());
    const std::string display = config->getDefaultDisplay();
    json views = json::array();
    for (int i = 0; i < config->getNumViews(display.c_str()); ++i) {
        const std::string view = config->getView(display.c_str(), i);
        OCIO::DisplayViewTransformRcPtr t = OCIO::DisplayViewTransform::Create();
        t->setSrc(source.c_str());
        t->setDisplay(display.c_str());
        t->setView(view.c_str());
        OCIO::GpuShaderDescRcPtr desc = OCIO::GpuShaderDesc::CreateShaderDesc();
        desc->setLanguage(OCIO::GPU_LANGUAGE_GLSL_ES_3_0);
        desc->setFunctionName("patina_display");
        const OCIO::ConstProcessorRcPtr processor = config->getProcessor(t);
        processor->getDefaultGPUProcessor()->extractGpuShaderInfo(desc);
        const bool analytic = desc->getNumTextures() == 0 && desc->getNum3DTextures() == 0 &&
                              desc->getNumUniforms() == 0;
        json entry = analytic && std::strlen(desc->getShaderText()) <= kLongShader
                         ? json{{"glsl", desc->getShaderText()}}
                         : baked_view(processor);
        entry["name"] = view;
        views.push_back(entry);
    }
    return views.dump();
}

ViewerSummary write_viewer(const ViewerOptions& o, const ColorManager& colors)
{
    const fs::path bundle = viewer_bundle_dir();
    const std::string glb = read_bytes(o.model);
    const json gltf = glb_json(glb, o.model);
    ViewerSummary summary;
    const json* variants = nullptr;
    if (gltf.contains("extensions") && gltf["extensions"].contains("KHR_materials_variants"))
        variants = &gltf["extensions"]["KHR_materials_variants"]["variants"];
    if (!variants || variants->empty())
        throw std::runtime_error(fmt::format(
            "view: '{}' has no material variants (KHR_materials_variants): export a time "
            "series with `patina-texgen export`", o.model.string()));
    const VariantAges ages = variant_ages(gltf);
    summary.ages = ages.labels;

    const OCIO::ConstConfigRcPtr config = OCIO::Config::CreateFromFile(colors.config_path().c_str());
    const std::string display = config->getDefaultDisplay();
    const json views = json::parse(display_views_json(colors));
    for (const json& v : views)
        summary.views.push_back(v["name"]);
    SkyMapOptions clear;  // the lookdev sky: CIE clear, the sun 35 degrees up in the SSE
    SkyMapOptions overcast;
    overcast.sky = cie_traditional_overcast();
    const json data = {
        {"title", o.title.empty() ? o.model.stem().string() : o.title},
        {"model", OIIO::Strutil::base64_encode(glb)},
        {"ages", ages.labels},
        {"age_values", ages.values},
        {"age_unit", ages.unit},
        {"display", display},
        {"default_view", config->getDefaultView(display.c_str())},
        {"views", views},
        {"environments", {environment("lookdev sky (clear)", clear, o.environment_width),
                          environment("overcast sky", overcast, o.environment_width)}}};
    const std::string script = "// Written by patina-texgen view: the asset and the display "
                               "transforms the page shows.\nwindow.PATINA_VIEWER = " +
                               data.dump() + ";\n";
    write_file_atomic(o.out / "data.js", {script}, "viewer data");
    write_file_atomic(o.out / "viewer.js", {read_bytes(bundle / "viewer.js")}, "viewer bundle");
    write_file_atomic(o.out / "index.html", {read_bytes(bundle / "index.html")}, "viewer page");
    return summary;
}

}  // namespace patina::texgen
