// `patina-texgen restore`: the colours before the fade. A faded texture or photograph, the
// fading material and the light it has had (a dose, a dose map, or a lighting policy and
// years) -> the estimated unfaded colours, and a confidence map flagging the texels where
// the answer is not unique (docs/forecast.md "Restoring").
#include "texgen/cli/commands.h"
#include "texgen/cli/fade_options.h"

#include "core/cancel.h"
#include "core/color_management.h"
#include "core/image_io.h"
#include "core/output_transaction.h"
#include "core/progress.h"
#include "texgen/fade/fade_map.h"
#include "texgen/fade/fade_material.h"
#include "texgen/forecast/fade_forecast.h"
#include "texgen/forecast/policy_file.h"
#include "texgen/restore/fade_inversion.h"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

struct RestoreOptions {
    fs::path image;
    std::string colorspace;
    FadeMaterialChoice material;
    std::optional<double> dose;
    fs::path dose_map;
    std::string channel;
    double scale = 1.0;
    std::string illuminant;
    // or a policy and years
    fs::path policies;
    std::string policy;
    LampPolicyChoice one;
    std::optional<double> years;
    double max_amount = 2.0;
    std::vector<std::string> colorants;
    int levels = 0;
    int sublayers = 50;
    double max_amplification = 1.5;
    std::string wavelengths = "360:830:5";
    fs::path out_dir;
    int threads = 0;
    bool quiet = false;
};

// The light and per-texel doses: (spectrum, doses per texel or one dose)
struct History {
    fade::Illuminant light;
    std::vector<float> doses;  // empty: `uniform` everywhere
    double uniform = 0.0;
    std::string description;
};

History gather_history(const RestoreOptions& o, int width, int height)
{
    const int given = (o.dose ? 1 : 0) + (o.dose_map.empty() ? 0 : 1) + (o.years ? 1 : 0);
    if (given != 1)
        throw std::runtime_error("give the light the image has had: --dose J/m^2, --dose-map MAP, "
                                 "or a policy (--lamp and --lux, or --policies and --policy) with "
                                 "--years");
    History h;
    if (o.years) {
        if (!(*o.years >= 0.0))
            throw std::runtime_error(fmt::format("--years {}: must be >= 0", *o.years));
        forecast::LightingPolicy p;
        if (!o.policies.empty()) {
            for (const forecast::LightingPolicy& q : forecast::read_policy_file(o.policies))
                if (q.name == o.policy)
                    p = q;
            if (p.name.empty())
                throw std::runtime_error("--policy '" + o.policy + "': no such policy in " +
                                         o.policies.string());
        } else {
            if (!o.one.lux || o.one.lamp.empty())
                throw std::runtime_error("--years needs a policy: --lamp and --lux, or --policies "
                                         "FILE --policy NAME");
            p = lamp_policy(o.one);
        }
        const forecast::PolicyExposure e = forecast::policy_exposure(p);
        h.light = e.spectrum;
        h.uniform = e.dose_per_year_j_m2 * *o.years;
        h.description = fmt::format("{} for {:g} years ({:.4g} J/m^2)", p.name, *o.years, h.uniform);
        return h;
    }
    h.light = fade::illuminant_from_text(o.illuminant.empty() ? "D65" : o.illuminant);
    if (o.dose) {
        if (!(*o.dose >= 0.0) || !std::isfinite(*o.dose))
            throw std::runtime_error(fmt::format("--dose {}: must be a finite number of J/m^2 >= 0", *o.dose));
        h.uniform = *o.dose;
        h.description = fmt::format("{:.4g} J/m^2 of {}", h.uniform, h.light.name);
        return h;
    }
    // A fade stack's dose.exr (channel `dose`, J/m^2) or an exposure map (`exposure`)
    const ImageData map = read_image(o.dose_map);
    int channel = map.channel(o.channel.empty() ? "dose" : o.channel);
    if (channel < 0 && o.channel.empty())
        channel = map.channel("exposure");
    if (channel < 0)
        throw std::runtime_error(fmt::format("--dose-map '{}': no channel '{}' (a fade stack's "
                                             "dose.exr has 'dose', an exposure map 'exposure')",
                                             o.dose_map.string(), o.channel.empty() ? "dose" : o.channel));
    if (map.width != width || map.height != height)
        throw std::runtime_error(fmt::format("--dose-map '{}' is {}x{}, the image {}x{}: they must "
                                             "match texel for texel",
                                             o.dose_map.string(), map.width, map.height, width, height));
    h.doses.resize(static_cast<size_t>(width) * height);
    for (size_t i = 0; i < h.doses.size(); ++i) {
        const double d = map.pixels[i * map.channels + channel] * o.scale;
        if (!(d >= 0.0) || !std::isfinite(d))
            throw std::runtime_error(fmt::format("--dose-map '{}': texel ({}, {}) has dose {}",
                                                 o.dose_map.string(), i % width, i / width, d));
        h.doses[i] = static_cast<float>(d);
    }
    h.description = fmt::format("the doses of {} ({})", o.dose_map.string(), h.light.name);
    return h;
}

void run_restore(const RestoreOptions& o)
{
    std::optional<tbb::global_control> threads;
    if (o.threads > 0)
        threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
    install_cancel_handler();
    const auto start = std::chrono::steady_clock::now();

    const fade::FadeMaterial material = load_material(o.material);

    const ImageData image = read_image(o.image);
    if (image.channels < 3)
        throw std::runtime_error(fmt::format("--image '{}': {} channel(s); a colour image has 3 "
                                             "(R, G, B)", o.image.string(), image.channels));
    const History history = gather_history(o, image.width, image.height);
    const ColorManager colors(ColorManager::default_config_path());
    const std::string ext = o.image.extension().string();
    const std::string space = !o.colorspace.empty()           ? o.colorspace
                              : (ext == ".exr" || ext == ".hdr") ? "lin_rec709"
                                                                 : "srgb_texture";
    reserve_output(o.out_dir / "restored.png");

    // The observed colours as CIE XYZ (D65 white at Y = 1), through OCIO
    const size_t n = static_cast<size_t>(image.width) * image.height;
    std::vector<float> xyz(3 * n);
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
            xyz[3 * i + c] = image.pixels[i * image.channels + c];
    colors.convert(space, "CIE-XYZ-D65", xyz.data(), n);

    const fade::WavelengthGrid grid = parse_grid(o.wavelengths);
    const forecast::ColourMeter meter(grid, fade::illuminant_by_name("D65"));
    restore::InversionOptions io;
    io.max_amount = o.max_amount;
    io.levels = o.levels;
    io.colorants = o.colorants;
    io.sublayers = o.sublayers;
    io.max_amplification = o.max_amplification;
    double max_dose = history.uniform;
    for (float d : history.doses)
        max_dose = std::max(max_dose, static_cast<double>(d));
    io.max_dose_j_m2 = std::max(max_dose, 1e-3);
    if (!o.quiet)
        std::fprintf(stderr, "restore: %s after %s; building the model...\n", material.name.c_str(),
                     history.description.c_str());
    const restore::FadeInversion inversion(material, history.light, grid, meter, io);
    throw_if_cancelled();

    std::vector<float> restored(3 * n), confidence(3 * n), amounts(3 * n, 0.0f);
    std::atomic<size_t> unique{0};
    Progress progress(static_cast<size_t>(image.height), o.quiet, "restore");
    tbb::parallel_for(0, image.height, [&](int y) {
        for (int x = 0; x < image.width; ++x) {
            const size_t i = static_cast<size_t>(y) * image.width + x;
            const double dose = history.doses.empty() ? history.uniform : history.doses[i];
            const restore::Inversion r =
                inversion.invert(Imath::V3d(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]), dose);
            restored[3 * i] = static_cast<float>(r.unfaded_xyz.x);
            restored[3 * i + 1] = static_cast<float>(r.unfaded_xyz.y);
            restored[3 * i + 2] = static_cast<float>(r.unfaded_xyz.z);
            confidence[3 * i] = static_cast<float>(std::min(r.amplification, 1e6));
            confidence[3 * i + 1] = static_cast<float>(r.residual);
            confidence[3 * i + 2] = r.unique ? 1.0f : 0.0f;
            for (size_t d = 0; d < inversion.dimensions(); ++d)
                amounts[3 * i + d] = static_cast<float>(r.amounts[d]);
            unique += r.unique ? 1 : 0;
        }
        progress.step(1);
    });
    progress.finish();
    throw_if_cancelled();

    // Restored colours: scene-linear EXR and the input's encoding as PNG
    std::vector<float> linear = restored;
    colors.convert("CIE-XYZ-D65", "lin_rec709", linear.data(), n);
    write_image_atomic(o.out_dir / "restored.exr", linear.data(), image.width, image.height, 3,
                       {}, OIIO::TypeDesc::HALF);
    std::vector<float> display = restored;
    colors.convert("CIE-XYZ-D65", "srgb_texture", display.data(), n);
    write_image_atomic(o.out_dir / "restored.png", display.data(), image.width, image.height, 3,
                       {}, OIIO::TypeDesc::UINT8);
    write_image_atomic(o.out_dir / "confidence.exr", confidence.data(), image.width, image.height,
                       3, {"amplification", "residual", "unique"}, OIIO::TypeDesc::FLOAT);
    std::vector<std::string> amount_names;
    for (const std::string& c : inversion.free_colorants())
        amount_names.push_back(c);
    while (amount_names.size() < 3)
        amount_names.push_back("unused" + std::to_string(amount_names.size()));
    write_image_atomic(o.out_dir / "amounts.exr", amounts.data(), image.width, image.height, 3,
                       amount_names, OIIO::TypeDesc::FLOAT);
    // The confidence as a picture: the restored colour where unique, red-grey where flagged
    std::vector<float> picture(3 * n);
    for (size_t i = 0; i < n; ++i) {
        const bool ok = confidence[3 * i + 2] > 0.5f;
        const float grey = 0.3f * display[3 * i] + 0.5f * display[3 * i + 1] + 0.2f * display[3 * i + 2];
        picture[3 * i] = ok ? display[3 * i] : 0.6f + 0.4f * grey;
        picture[3 * i + 1] = ok ? display[3 * i + 1] : 0.15f * grey;
        picture[3 * i + 2] = ok ? display[3 * i + 2] : 0.15f * grey;
    }
    write_image_atomic(o.out_dir / "confidence.png", picture.data(), image.width, image.height, 3,
                       {}, OIIO::TypeDesc::UINT8);
    if (!o.quiet)
        std::fprintf(stderr,
                     "restore: %dx%d, %.1f%% of the texels unique (amplification <= %g); solved for "
                     "%zu colorant amounts; wrote %s in %.2f s\n",
                     image.width, image.height, 100.0 * unique.load() / static_cast<double>(n),
                     o.max_amplification, inversion.dimensions(), o.out_dir.string().c_str(),
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace

void register_restore_command(CLI::App& app)
{
    auto o = std::make_shared<RestoreOptions>();
    CLI::App* cmd = app.add_subcommand(
        "restore",
        "the colours before the fade: invert the fading model per texel, given the faded image, "
        "the material and the light it has had; flag the texels where the answer is not unique");
    cmd->add_option("--image", o->image, "the faded texture or photograph")->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--colorspace", o->colorspace,
                    "its OCIO colour space (default: srgb_texture, lin_rec709 for .exr)");
    add_material_options(cmd, o->material);
    cmd->add_option("--dose", o->dose, "one dose for every texel, J/m^2 in the illuminant's band");
    cmd->add_option("--dose-map", o->dose_map,
                    "doses per texel: a fade stack's dose.exr or an exposure map in J/m^2");
    cmd->add_option("--channel", o->channel, "channel of the dose map (default: dose)");
    cmd->add_option("--scale", o->scale, "dose per unit of the map")->capture_default_str();
    cmd->add_option("--illuminant", o->illuminant, "the light of --dose or --dose-map (default D65)");
    cmd->add_option("--policies", o->policies, "lighting-policy file (with --policy and --years)");
    cmd->add_option("--policy", o->policy, "the policy's name in --policies");
    add_lamp_policy_options(cmd, o->one, " (with --lux and --years)");
    cmd->add_option("--years", o->years, "years shown under the policy");
    cmd->add_option("--max-amount", o->max_amount,
                    "largest original amount searched, times the material's")->capture_default_str();
    cmd->add_option("--colorants", o->colorants,
                    "the colorants whose original amounts to solve for (default: every fading "
                    "one, at most three); the others keep the material's")
        ->delimiter(',');
    cmd->add_option("--levels", o->levels, "model grid levels per colorant (0: by dimension)")
        ->capture_default_str();
    cmd->add_option("--sublayers", o->sublayers, "sublayers of the model's solver")->capture_default_str();
    cmd->add_option("--max-amplification", o->max_amplification,
                    "a texel is unique when the restored colour moves at most this much per unit "
                    "the observed colour moves")
        ->capture_default_str();
    cmd->add_option("--wavelengths", o->wavelengths, "solver wavelengths FIRST:LAST:STEP, nm")
        ->capture_default_str();
    cmd->add_option("-o,--out", o->out_dir,
                    "folder for restored.png/exr, confidence.png/exr, amounts.exr")->required();
    cmd->add_option("--threads", o->threads, "worker threads (0 = all cores)")->capture_default_str();
    cmd->add_flag("--quiet", o->quiet, "no progress");
    cmd->callback([o] { run_restore(*o); });
}

}  // namespace patina::texgen
