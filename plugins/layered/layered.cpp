/*
 * layered_km — A patina stack: Kubelka-Munk layers over a base, one glossy lobe per
 * interface (bsdf)
 * =====================================================================================
 *
 *  Parameter        Type    Default  Description
 *  ---------------  ------  -------  -----------------------------------------------------
 *  stack            file    (none)   The stack.toml `patina-texgen patina` wrote.
 *  thickness_scale  float   1        Multiplies every layer thickness (µm) read from the maps.
 *  model            string  "km"     "km": the fast model of Dorsey & Hanrahan 1996 §4;
 *                                    "random_walk": the stochastic reference.
 *  walk_samples     int     64       Random walks per evaluation in "random_walk" mode.
 *
 * At create the shader reads stack.toml (the base, the layers bottom to top with their
 * thickness maps, and [patina.materials."<name>"]: K, S and specular per wavelength,
 * roughness, and n, k for a metal base), opens each layer's thickness map through
 * host->open_texture (colour space "raw", paths relative to stack.toml) and resamples every
 * material onto a 5 nm grid.
 *
 * Per shading point and wavelength (D&H 1996 §4):
 *   - each layer's KM reflectance R and transmittance T from K, S and its thickness d (§4.1,
 *     the hyperbolic closed form written without overflow; exact at d = 0 and K = 0);
 *   - the layers composited from the top down and over the base (§4.2:
 *     R = R1 + T1² R2 / (1 - R1 R2), T = T1 T2 / (1 - R1 R2)): the diffuse lobe R / π;
 *   - one GGX lobe per interface, with the roughness and specular colour of the material below
 *     it (each layer's own top surface, then the base's), times T_above², the KM
 *     transmittance of the layers above, squared (§4.3). A dielectric interface reflects
 *     with the exact Fresnel of the index η = (1 + √F0) / (1 - √F0) whose normal reflectance
 *     is the specular colour F0 (so specular 0 reflects nothing at any angle); a metal base
 *     uses the exact conductor Fresnel of its n + ik. Two adjacent layers of one material are
 *     one layer (no interface between them).
 *
 * Choices the paper leaves open (plugins/layered/README.md explains them):
 *   - A metal base under layers: the diffuse compositing sees its hemispherical reflectance
 *     2 ∫ F(μ) μ dμ; the light it reflects directly (T_above² R_base) is its glossy lobe and
 *     is taken out of the diffuse part, so a bare or zero-thickness stack is the conductor.
 *   - Energy: what a surface reflects does not reach below it. With g_j(μ) = fade_j T_above_j²
 *     E_j(μ) (E_j the directional albedo of surface j's lobe, tabulated at create), each lobe
 *     and the diffuse part are multiplied by (1 - g_j(μo)) (1 - g_j(μi)) for every dielectric
 *     surface j above them, and the diffuse light the surfaces send back down is returned by
 *     the stack: the diffuse lobe is R_d / (π (1 - R_d ḡ)), ḡ the hemispherical mean of the
 *     surfaces' combined g. Reciprocal; the directional albedo stays <= 1 (and is 1 - g(μo)
 *     + g(μo) for a white stack without absorption, when T_above = 1).
 *   - A layer thinner than 0.05 µm fades its interface in linearly (no gloss from a film
 *     far thinner than a wavelength, no sudden gloss at a filtered coverage edge).
 *   - Roughness below 0.03 is treated as 0.03 (no delta lobes).
 *
 * Sampling picks a lobe in proportion to its estimated albedo at wo, then samples GGX visible
 * normals or the cosine; pdf is the same mixture, and sample returns exactly eval and pdf.
 * Both sides reflect alike; nothing is transmitted. "random_walk" samples as "km" does but
 * returns the random-walk estimate of f (random_walk.cpp).
 */
#include "layered_model.h"

#include <patina/plugin_support.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <new>
#include <string>

namespace patina::layered {
namespace {

    constexpr const char* kName = "layered_km";

    // clang-format off
    const PatinaParamDecl kParams[] = {
        {"stack", PATINA_PARAM_FILE, {0.0f, 0.0f, 0.0f}, "", nullptr, 0.0f, 0.0f, "",
         "The stack.toml written by patina-texgen patina: layers, thickness maps and the "
         "optical description of their materials."},
        {"thickness_scale", PATINA_PARAM_FLOAT, {1.0f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 1000.0f,
         "", "Multiplies every layer thickness (micrometres) read from the maps."},
        {"model", PATINA_PARAM_STRING, {0.0f, 0.0f, 0.0f}, "km", nullptr, 0.0f, 0.0f, "",
         "\"km\": Kubelka-Munk layers with one glossy lobe per interface (D&H 1996 section 4); "
         "\"random_walk\": the stochastic reference of the same stack."},
        {"walk_samples", PATINA_PARAM_INT, {64.0f, 0.0f, 0.0f}, nullptr, nullptr, 1.0f, 65536.0f, "",
         "Random walks per evaluation when model = \"random_walk\"."},
    };
    // clang-format on

    struct Instance {
        LayeredModel model;
        uint64_t id;  ///< unique for the process's lifetime (keys the per-thread cache)
    };

    std::atomic<uint64_t> g_next_id{1};

    /// The set-up of the last shading point of this thread, and the terms of its last wo. A
    /// renderer calls sample, eval and pdf at one point with one set of wavelengths and one
    /// wo: the thickness lookups and the KM compositing run once for all three, and the
    /// wo terms (E(μo), Λ(wo), the lobe probabilities) once per wo. Keys compare bits, so a
    /// hit returns exactly what a fresh set-up would.
    struct CachedPoint {
        uint64_t owner = 0;
        float key[6] = {};
        PatinaWavelengths wl{};
        PointState state;
        bool has_outgoing = false;
        float wo_key[3] = {};
        Outgoing outgoing;
    };

    struct Shading {
        const PointState& state;
        const Outgoing& outgoing;
    };

    CachedPoint& point(const Instance& inst, const PatinaShadingContext* ctx,
                       const PatinaWavelengths& wl)
    {
        thread_local CachedPoint cache;
        if (!ctx) {
            thread_local CachedPoint uncached;
            inst.model.setup(ctx, wl, &uncached.state);
            uncached.has_outgoing = false;
            return uncached;
        }
        const float key[6] = {ctx->uv.x,     ctx->uv.y,     ctx->duvdx[0],
                              ctx->duvdx[1], ctx->duvdy[0], ctx->duvdy[1]};
        const int n = std::clamp(wl.count, 0, PATINA_MAX_WAVELENGTHS);
        if (cache.owner == inst.id && std::memcmp(cache.key, key, sizeof key) == 0 &&
            cache.wl.count == wl.count &&
            std::memcmp(cache.wl.lambda_nm, wl.lambda_nm, sizeof(float) * n) == 0)
            return cache;
        inst.model.setup(ctx, wl, &cache.state);
        cache.owner = inst.id;
        std::memcpy(cache.key, key, sizeof key);
        cache.wl = wl;
        cache.has_outgoing = false;
        return cache;
    }

    Shading shading(const void* instance, const PatinaShadingContext* ctx,
                    const PatinaWavelengths& wl, PatinaVec3 wo)
    {
        CachedPoint& p = point(*static_cast<const Instance*>(instance), ctx, wl);
        const float wo_key[3] = {wo.x, wo.y, std::abs(wo.z)};  // outgoing() folds wo.z
        if (!p.has_outgoing || std::memcmp(p.wo_key, wo_key, sizeof wo_key) != 0) {
            LayeredModel::outgoing(p.state, wo, &p.outgoing);
            std::memcpy(p.wo_key, wo_key, sizeof wo_key);
            p.has_outgoing = true;
        }
        return {p.state, p.outgoing};
    }

    void report(const PatinaHost* host, const std::string& message)
    {
        if (host && host->error)
            host->error(host, kName, message.c_str());
    }

    void* create(const PatinaHost* host, const PatinaParamValue* values)
    {
        const plugin::Parameters p(host, kName, kParams, values);
        const char* path = p.text("stack");
        ModelOptions options;
        options.thickness_scale = p.number("thickness_scale");
        const std::string model = p.text("model");
        options.walk_samples = p.integer("walk_samples");
        if (!p.ok())
            return nullptr;
        if (!*path) {
            report(host, "stack: no stack.toml given");
            return nullptr;
        }
        if (model == "km" || model.empty())
            options.model = Model::kubelka_munk;
        else if (model == "random_walk")
            options.model = Model::random_walk;
        else {
            report(host, "model: '" + model + "' is not \"km\" or \"random_walk\"");
            return nullptr;
        }
        if (!(options.thickness_scale >= 0.0f) || options.walk_samples < 1) {
            report(host, "thickness_scale must be >= 0 and walk_samples >= 1");
            return nullptr;
        }
        if (!PATINA_HOST_HAS_READ_IMAGE(host) || !host->open_texture || !host->texture_lookup) {
            report(host, "the host does not offer open_texture (ABI 1.1); it cannot load a stack");
            return nullptr;
        }
        try {
            const StackFile stack = read_stack_file(path);
            // Each map file opened once: layers reading channels of one file share a handle
            // (and the model one lookup).
            std::map<std::string, const PatinaTexture*> opened;
            std::vector<ThicknessSource> sources;
            for (size_t l = 0; l < stack.layers.size(); ++l) {
                const std::string file = stack.layers[l].map_file.string();
                const PatinaTexture*& t = opened[file];
                if (!t)
                    t = host->open_texture(host, file.c_str(), "raw");
                if (!t) {
                    report(host, std::string(path) + ": layer " + std::to_string(l + 1) + " (" +
                                     stack.layers[l].material + "): cannot open thickness map '" +
                                     file + "'");
                    return nullptr;
                }
                sources.push_back({t, stack.layers[l].channel});
            }
            return new Instance{LayeredModel(stack, sources, host, options),
                                g_next_id.fetch_add(1)};
        } catch (const std::exception& e) {
            report(host, e.what());
            return nullptr;
        }
    }

    void destroy(void* instance)
    {
        delete static_cast<Instance*>(instance);
    }

    const LayeredModel& model_of(const void* instance)
    {
        return static_cast<const Instance*>(instance)->model;
    }

    // Each entry point: the (cached) set-up of the point, then the model.

    void eval(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo, PatinaVec3 wi,
              const PatinaWavelengths* wl, float* f)
    {
        const Shading s = shading(instance, ctx, *wl, wo);
        model_of(instance).eval(s.state, s.outgoing, wo, wi, f);
    }

    float pdf(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo, PatinaVec3 wi,
              const PatinaWavelengths* wl)
    {
        const Shading s = shading(instance, ctx, *wl, wo);
        return model_of(instance).pdf(s.state, s.outgoing, wo, wi);
    }

    int sample(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo, float u_lobe,
               PatinaVec2 u, const PatinaWavelengths* wl, PatinaBsdfSample* out)
    {
        const Shading s = shading(instance, ctx, *wl, wo);
        return model_of(instance).sample(s.state, s.outgoing, wo, u_lobe, u, out);
    }

    void albedo(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo,
                const PatinaWavelengths* wl, float* a)
    {
        model_of(instance).albedo(point(*static_cast<const Instance*>(instance), ctx, *wl).state,
                                  wo, a);
    }

    const PatinaBsdfFuncs kFuncs = {eval, pdf, sample, albedo};

}  // namespace
}  // namespace patina::layered

PATINA_PLUGIN("layered", "0.1.0",
              patina::plugin::describe(
                  patina::layered::kName,
                  "A patina stack (stack.toml): Kubelka-Munk layers composited over a metal or "
                  "dielectric base, one GGX lobe per interface attenuated by the layers above "
                  "(Dorsey & Hanrahan 1996, section 4).",
                  patina::layered::kParams, patina::layered::create, patina::layered::destroy,
                  patina::layered::kFuncs))
