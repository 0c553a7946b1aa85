// `patina-texgen sky`: a lat-long sky EXR for a scene's [environment] (a CIE sky scaled by
// the clear-sky irradiances, texgen/sun/sky_map.h), and the [sun] that goes with it, printed
// as the scene's TOML.
#include "texgen/cli/commands.h"

#include "core/cli_errors.h"
#include "core/image_io.h"
#include "texgen/sun/sky_map.h"

#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <string>

namespace patina::texgen {

namespace {

    struct SkyArguments {
        SkyMapOptions map;
        std::string sky = "clear";
        std::filesystem::path out = "sky.exr";
    };

    void run_sky(SkyArguments a)
    {
        if (a.out.extension() != ".exr")
            throw std::runtime_error(fmt::format("-o '{}' must be an .exr file", a.out.string()));
        a.map.sky = parse_cie_sky(a.sky, "--sky");
        const SkyMap m = make_sky_map(a.map);
        std::vector<float> rgb;
        rgb.reserve(m.radiance.size() * 3);
        for (float v : m.radiance)
            rgb.insert(rgb.end(), {v, v, v});
        const Metadata meta = {
            {"patina:baker", std::string("sky")},
            {"patina:sky", a.map.sky.name},
            {"patina:sun_elevation_deg", float(a.map.sun_elevation_deg)},
            {"patina:sun_azimuth_deg", float(a.map.sun_azimuth_deg)},
            {"patina:sun_irradiance", float(m.sun_irradiance)},
            {"patina:ghi_w_m2", float(m.physical.ghi)},
            {"patina:dni_w_m2", float(m.physical.dni)},
            {"patina:dhi_w_m2", float(m.physical.dhi)},
            {"patina:description",
             std::string("sky radiance, grey (D65 white in the renderer), scaled so that sky "
                         "and [sun] give a horizontal surface the irradiance pi")},
        };
        write_image_atomic(a.out, rgb.data(), m.width, m.height, 3, {"R", "G", "B"},
                           OIIO::TypeDesc::HALF, meta);
        // What a scene adds for this sky (the sun as a distant light: sharp shadows).
        std::printf("[environment]\nfile = \"%s\"\ncolorspace = \"raw\"\n", a.out.filename().string().c_str());
        if (m.sun_irradiance > 0.0)
            std::printf("\n[sun]\ndirection = [%.6f, %.6f, %.6f]\nirradiance = %.6f\n",
                        m.sun_direction.x, m.sun_direction.y, m.sun_direction.z,
                        m.sun_irradiance);
    }

}  // namespace

void register_sky_command(CLI::App& app)
{
    auto a = std::make_shared<SkyArguments>();
    CLI::App* cmd = app.add_subcommand(
        "sky", "write a lat-long sky (a CIE sky under the clear-sky irradiances) for a scene's "
               "[environment], and print the [sun] that goes with it");
    cmd->add_option("-o,--out", a->out, "the sky EXR")->capture_default_str();
    cmd->add_option("--sky", a->sky, "clear (CIE type 12), overcast (Moon-Spencer) or a CIE "
                                     "standard general sky 1..15")
        ->capture_default_str();
    cmd->add_option("--sun-elevation", a->map.sun_elevation_deg, "degrees above the horizon")
        ->capture_default_str()
        ->check(CLI::Range(-90.0, 90.0));
    cmd->add_option("--sun-azimuth", a->map.sun_azimuth_deg,
                    "degrees eastward from north (-z), as `patina-texgen sun` prints it")
        ->capture_default_str();
    cmd->add_option("--linke-turbidity", a->map.linke_turbidity,
                    "Linke turbidity (2 very clean, 3 typical, 5+ hazy)")
        ->capture_default_str()
        ->check(CLI::Range(1.0, 10.0));
    cmd->add_option("--ground-albedo", a->map.ground_albedo, "the ground below the horizon")
        ->capture_default_str();
    cmd->add_option("--resolution", a->map.width, "texels around (the height is half)")
        ->capture_default_str();
    cmd->callback([a] { run_sky(*a); });
}

}  // namespace patina::texgen
