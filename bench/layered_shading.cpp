// Shading cost of the layered_km shader (plugins/layered) per sample — eval + sample + pdf at
// a random uv and random directions, 4 hero wavelengths — for a 5-layer patina stack over
// copper (256² mip-mapped thickness maps, in one 5-channel thickness.exr as
// `patina-texgen patina` writes it; one map per layer printed for reference), against:
//   1. the basic plugin's lambert with a reflectance_scale_map (one texture lookup per call)
//      and without one (no lookup): target layered <= 3x lambert;
//   2. the same layered code compiled into this program and called directly (no dlopen, no
//      function pointers, inlining allowed): target ABI overhead <= 5%.
// A plain main: prints ns per sample and both ratios (bench/README.md).
#include "host/host.h"
#include "core/image_io.h"
#include "host/plugin_registry.h"
#include "host/shader_instance.h"
#include "core/spectrum.h"

// The plugin's sources, compiled in for the direct path: the very functions the plugin's
// table points to (layered.cpp's eval, sample, pdf), called directly.
#include "../plugins/layered/layered.cpp"
#include "../plugins/layered/layered_model.cpp"
#include "../plugins/layered/random_walk.cpp"
#include "../plugins/layered/stack_file.cpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

int g_samples = 400000;  // argv[1] overrides (e.g. a short run under callgrind)
bool g_reference = true; // argv[2] = "noref" skips the slow random-walk reference
constexpr int kSize = 256;

/// A 5-layer stack like the urban §5.1 strip: tarnish, cuprite, two patina stages, dirt.
/// `one_map`: the thicknesses in one 5-channel thickness.exr, channels named and read as
/// texgen/patina/stack_writer.cpp writes them (one texture lookup per point); else one map
/// per layer (what patina-texgen patina wrote before, and still writes for other tools).
fs::path write_bench_stack(const fs::path& dir, bool one_map)
{
    fs::create_directories(dir);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    const char* names[5] = {"tarnish", "cuprite", "patina3", "patina4", "dirt"};
    const float max_um[5] = {0.4f, 0.8f, 4.0f, 3.0f, 1.4f};
    const float K[5] = {1.2f, 1.6f, 0.25f, 0.3f, 0.3f}, S[5] = {1.5f, 1.2f, 0.35f, 0.35f, 0.35f};
    std::ostringstream t;
    std::vector<float> all(kSize * kSize * 5);
    // Float texels, as stack_writer writes them unless asked for --half (environment variable
    // BENCH_HALF=1: half floats, as this bench used before).
    patina::TextureOptions options;
    options.format = std::getenv("BENCH_HALF") ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT;
    for (int l = 0; l < 5; ++l) {
        std::vector<float> texels(kSize * kSize);
        for (float& x : texels)
            x = uniform(rng) < 0.2f ? 0.0f : max_um[l] * uniform(rng);
        for (size_t p = 0; p < texels.size(); ++p)
            all[p * 5 + l] = texels[p];
        if (!one_map) {
            patina::make_texture_atomic(dir / (std::string(names[l]) + ".exr"), texels.data(),
                                        kSize, kSize, 1, {"thickness"}, options);
            t << "[maps." << names[l] << "]\nfile = '" << names[l] << ".exr'\n";
        }
    }
    if (one_map) {
        // stack_writer's channel names (layer_channel_name): they sort in layer order, as
        // OpenEXR keeps channels.
        const std::vector<std::string> channels = {"layer01_tarnish", "layer02_cuprite",
                                                   "layer03_patina3", "layer04_patina4",
                                                   "layer05_dirt"};
        patina::make_texture_atomic(dir / "thickness.exr", all.data(), kSize, kSize, 5, channels,
                                    options);
        t << "[maps.thickness]\nfile = 'thickness.exr'\nchannels = [";
        for (int l = 0; l < 5; ++l)
            t << (l ? ", '" : "'") << channels[l] << "'";
        t << "]\n";
    }
    t << "[patina]\nbase = 'copper'\n";
    for (int l = 0; l < 5; ++l) {
        t << "[[patina.layers]]\nmaterial = '" << names[l] << "'\n";
        if (one_map)
            t << "map = 'thickness'\nchannel = 'layer0" << l + 1 << "_" << names[l] << "'\n";
        else
            t << "map = '" << names[l] << "'\n";
    }
    t << "[patina.materials.copper]\nmetal = true\nroughness = 0.15\n"
         "wavelengths_nm = [360, 550, 600, 830]\nn = [1.36, 1.02, 0.3, 0.26]\n"
         "k = [1.97, 2.58, 3.2, 5.2]\n";
    for (int l = 0; l < 5; ++l)
        t << "[patina.materials." << names[l] << "]\nroughness = 0.4\n"
          << "wavelengths_nm = [360, 500, 830]\nspecular = [0.04, 0.04, 0.05]\n"
          << "absorption_per_um = [" << K[l] << ", " << 0.5f * K[l] << ", " << K[l] << "]\n"
          << "scattering_per_um = [" << S[l] << ", " << S[l] << ", " << S[l] << "]\n";
    std::ofstream(dir / "stack.toml") << t.str();
    return dir / "stack.toml";
}

struct Input {
    PatinaShadingContext ctx{};
    PatinaVec3 wo, wi;
    float u_lobe;
    PatinaVec2 u;
};

std::vector<Input> make_inputs()
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    std::vector<Input> in(4096);
    for (Input& x : in) {
        x.ctx.N = {0, 0, 1};
        x.ctx.uv = {uniform(rng), uniform(rng)};
        auto dir = [&] {
            const patina::shading::Vec3 d = patina::shading::sample_cosine_hemisphere(
                {uniform(rng), uniform(rng)});
            return PatinaVec3{d.x, d.y, d.z};
        };
        x.wo = dir();
        x.wi = dir();
        x.u_lobe = uniform(rng);
        x.u = {uniform(rng), uniform(rng)};
    }
    return in;
}

volatile int g_config = 0;

/// Best of 3 runs, ns per sample. `Config` only gives each configuration its own symbol (the
/// store keeps the compiler from folding them into one), so callgrind's inclusive cost of
/// time_per_sample<N, ...> / (3 x samples) is its instructions per sample (0: layered with
/// one 5-channel map through the ABI, 1: the same linked in, 2: lambert + map, 3: lambert,
/// 4: layered with one map per layer, through the ABI).
template <int Config, typename F> [[gnu::noinline]] double time_per_sample(F&& shade)
{
    g_config = Config;
    double best = 1e30;
    for (int run = 0; run < 3; ++run) {
        const auto t0 = Clock::now();
        for (int i = 0; i < g_samples; ++i)
            shade(i);
        const double ns = std::chrono::duration<double, std::nano>(Clock::now() - t0).count();
        best = std::min(best, ns / g_samples);
    }
    return best;
}

volatile float g_sink = 0.0f;

}  // namespace

int main(int argc, char** argv)
{
    if (argc > 1)
        g_samples = std::max(1, std::atoi(argv[1]));
    if (argc > 2 && std::string(argv[2]) == "noref")
        g_reference = false;
    const fs::path dir = fs::temp_directory_path() / "patina_bench_layered";
    const fs::path stack = write_bench_stack(dir / "maps", false);
    const fs::path stack_one_map = write_bench_stack(dir / "one_map", true);
    std::vector<float> scale(kSize * kSize, 0.8f);
    patina::make_texture_atomic(dir / "scale.exr", scale.data(), kSize, kSize, 1, {"Y"});

    patina::Host& host = patina::default_host();
    patina::PluginRegistry registry(host.c_host());
    registry.load_directory(PATINA_TEST_PLUGIN_DIR);
    const auto layered = patina::create_shader_instance(
        registry, "layered_km", toml::table{{"stack", stack_one_map.string()}}, "bench");
    const auto layered_five_maps = patina::create_shader_instance(
        registry, "layered_km", toml::table{{"stack", stack.string()}}, "bench");
    const auto lambert_map = patina::create_shader_instance(
        registry, "lambert",
        toml::table{{"reflectance", toml::array{0.5, 0.4, 0.3}},
                    {"reflectance_scale_map", (dir / "scale.exr").string()}},
        "bench");
    const auto lambert = patina::create_shader_instance(
        registry, "lambert", toml::table{{"reflectance", toml::array{0.5, 0.4, 0.3}}}, "bench");

    // The same shader compiled in, created with the same parameters.
    const std::string stack_path = stack_one_map.string();
    PatinaParamValue values[4] = {};
    values[0].type = PATINA_PARAM_FILE;
    values[0].s = stack_path.c_str();
    values[1].type = PATINA_PARAM_FLOAT;
    values[1].f = 1.0f;
    values[2].type = PATINA_PARAM_STRING;
    values[2].s = "km";
    values[3].type = PATINA_PARAM_INT;
    values[3].i = 64;
    void* direct = patina::layered::create(host.c_host(), values);
    if (!direct) {
        std::fprintf(stderr, "layered_km create failed\n");
        return 1;
    }

    const std::vector<Input> inputs = make_inputs();
    const PatinaWavelengths wl = patina::sample_wavelengths_visible(0.37f, 4);

    auto through_abi = [&](const patina::ShaderInstance& s) {
        const PatinaBsdfFuncs* bsdf = s.bsdf();
        const void* inst = s.get();
        return [&, bsdf, inst](int i) {
            const Input& x = inputs[i & 4095];
            float f[PATINA_MAX_WAVELENGTHS];
            PatinaBsdfSample smp;
            bsdf->eval(inst, &x.ctx, x.wo, x.wi, &wl, f);
            bsdf->sample(inst, &x.ctx, x.wo, x.u_lobe, x.u, &wl, &smp);
            g_sink = g_sink + f[0] + smp.pdf + bsdf->pdf(inst, &x.ctx, x.wo, x.wi, &wl);
        };
    };
    auto linked_in = [&](int i) {
        const Input& x = inputs[i & 4095];
        float f[PATINA_MAX_WAVELENGTHS];
        PatinaBsdfSample smp;
        patina::layered::eval(direct, &x.ctx, x.wo, x.wi, &wl, f);
        patina::layered::sample(direct, &x.ctx, x.wo, x.u_lobe, x.u, &wl, &smp);
        g_sink = g_sink + f[0] + smp.pdf + patina::layered::pdf(direct, &x.ctx, x.wo, x.wi, &wl);
    };

    // The reference mode, for scale: eval only, 64 walks per wavelength.
    values[2].s = "random_walk";
    void* reference = g_reference ? patina::layered::create(host.c_host(), values) : nullptr;
    double t_reference = 0.0;
    if (reference) {
        const auto t0 = Clock::now();
        constexpr int kReferenceSamples = 2000;
        for (int i = 0; i < kReferenceSamples; ++i) {
            const Input& x = inputs[i & 4095];
            float f[PATINA_MAX_WAVELENGTHS] = {};
            patina::layered::eval(reference, &x.ctx, x.wo, x.wi, &wl, f);
            g_sink = g_sink + f[0];
        }
        t_reference =
            std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / kReferenceSamples;
        patina::layered::destroy(reference);
    }

    const double t_layered = time_per_sample<0>(through_abi(*layered));
    const double t_direct = time_per_sample<1>(linked_in);
    const double t_lambert_map = time_per_sample<2>(through_abi(*lambert_map));
    const double t_lambert = time_per_sample<3>(through_abi(*lambert));
    const double t_five_maps = time_per_sample<4>(through_abi(*layered_five_maps));

    std::printf("layered_km, 5 layers over copper, eval + sample + pdf, 4 wavelengths, "
                "%d samples, best of 3:\n", g_samples);
    std::printf("  layered_km through the ABI      %8.1f ns/sample (one 5-channel map)\n",
                t_layered);
    std::printf("  layered model linked in         %8.1f ns/sample\n", t_direct);
    std::printf("  layered_km, one map per layer   %8.1f ns/sample\n", t_five_maps);
    std::printf("  lambert + scale map (ABI)       %8.1f ns/sample\n", t_lambert_map);
    std::printf("  lambert (ABI)                   %8.1f ns/sample\n", t_lambert);
    std::printf("  random_walk reference, eval only %8.0f ns/sample (64 walks per wavelength)\n",
                t_reference);
    std::printf("ratio layered / lambert with map  %6.2f  (target <= 3)\n",
                t_layered / t_lambert_map);
    std::printf("ratio layered / lambert with map  %6.2f  with one map per layer (reference)\n",
                t_five_maps / t_lambert_map);
    std::printf("ratio layered / lambert plain     %6.2f\n", t_layered / t_lambert);
    std::printf("ratio ABI / linked in             %6.3f  (target <= 1.05)\n",
                t_layered / t_direct);
    patina::layered::destroy(direct);
    return 0;
}
