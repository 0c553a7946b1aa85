#include "texgen/view/viewer_folder.h"

#include "core/color_management.h"
#include "core/image_io.h"
#include "texgen/sun/sky_map.h"

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
    for (const json& v : *variants)
        summary.ages.push_back(v.value("name", std::string()));

    // The display's views as OCIO's own GLSL (ES 3.0), from the page's working space.
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
        config->getProcessor(t)->getDefaultGPUProcessor()->extractGpuShaderInfo(desc);
        if (desc->getNumTextures() > 0 || desc->getNum3DTextures() > 0 || desc->getNumUniforms() > 0)
            throw std::runtime_error(fmt::format(
                "view: OCIO's shader of the view '{}' needs lookup textures or uniforms, which "
                "the page does not load", view));
        views.push_back({{"name", view}, {"glsl", desc->getShaderText()}});
        summary.views.push_back(view);
    }

    SkyMapOptions clear;  // the lookdev sky: CIE clear, the sun 35 degrees up in the SSE
    SkyMapOptions overcast;
    overcast.sky = cie_traditional_overcast();
    const json data = {
        {"title", o.title.empty() ? o.model.stem().string() : o.title},
        {"model", OIIO::Strutil::base64_encode(glb)},
        {"ages", summary.ages},
        {"display", display},
        {"source", source},
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
