#include "layered_model.h"

#include <patina/shading/kubelka_munk.h>
#include <patina/shading/lanes.h>

#include <patina/shading/fresnel.h>
#include <patina/shading/frame.h>
#include <patina/shading/sampling.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::layered {

using namespace patina::shading;
using namespace patina::shading::simd;

namespace {

    /// Roughness below which an interface is treated as this smooth (no delta lobes: the
    /// model sums rough lobes only).
    constexpr float kMinRoughness = 0.03f;

    /// Where μ falls in an albedo table row: node n and weight t.
    struct MuPos {
        int n;
        float t;
    };
    MuPos mu_pos(float mu)
    {
        const float x = std::clamp(mu, 0.0f, 1.0f) * (kAlbedoNodes - 1);
        const int n = std::min(static_cast<int>(x), kAlbedoNodes - 2);
        return {n, x - static_cast<float>(n)};
    }

    /// Row `row` of a kAlbedoNodes table at μ (the interpolation interface_albedo does).
    float row_at(const float* row, MuPos m)
    {
        return row[m.n] + m.t * (row[m.n + 1] - row[m.n]);
    }

    /// `values` over `lambda` (linear, clamped ends) resampled onto the common grid.
    Grid resample(const std::vector<float>& lambda, const std::vector<float>& values)
    {
        Grid g{};
        if (values.empty())
            return g;
        PatinaTabulatedSpectrum table{static_cast<int>(values.size()), lambda.data(),
                                      values.data()};
        for (int i = 0; i < kGridSize; ++i)
            g[i] = patina_tabulated_eval(&table, kGridStartNm + kGridStepNm * i);
        return g;
    }

    /// The directional albedo tables of a material's lobe (patina/shading/ggx_albedo.h) and
    /// their rows at the Gauss nodes.
    void tabulate_albedo(CompiledMaterial* m)
    {
        shading::tabulate_ggx_albedo(m->distribution, m->albedo, m->albedo_one);
        for (int q = 0; q < kF0Nodes; ++q)
            for (int g = 0; g < kGaussNodes; ++g)
                m->albedo_gauss[q * kGaussNodes + g] =
                    row_at(&m->albedo[q * kAlbedoNodes], mu_pos(kGaussMu[g]));
    }

    CompiledMaterial compile(const MaterialOptics& o)
    {
        CompiledMaterial m;
        m.metal = o.metal;
        m.roughness = std::max(o.roughness, kMinRoughness);
        const float alpha = TrowbridgeReitz::roughness_to_alpha(m.roughness);
        m.distribution = TrowbridgeReitz(alpha, alpha);
        m.specular = resample(o.lambda_nm, o.specular);
        if (o.metal) {
            m.eta = resample(o.lambda_nm, o.n);
            m.kappa = resample(o.lambda_nm, o.k);
            for (int i = 0; i < kGridSize; ++i)
                m.base_reflectance[i] = base_reflectance_metal(m.eta[i], m.kappa[i]);
        } else {
            m.absorption = resample(o.lambda_nm, o.absorption_per_um);
            m.scattering = resample(o.lambda_nm, o.scattering_per_um);
            for (int i = 0; i < kGridSize; ++i)
                m.base_reflectance[i] =
                    base_reflectance_dielectric(m.absorption[i], m.scattering[i]);
        }
        tabulate_albedo(&m);
        return m;
    }

    /// Both directions in the upper hemisphere (the stack reflects alike on both sides);
    /// false when they lie on different sides or in the tangent plane.
    bool to_upper(Vec3* wo, Vec3* wi)
    {
        if (!(wo->z * wi->z > 0.0f))
            return false;
        wo->z = std::abs(wo->z);
        wi->z = std::abs(wi->z);
        return true;
    }

    /// Two lobes with the same microfacet widths: D, G and the visible-normal density of one
    /// are those of the other.
    bool same_widths(const TrowbridgeReitz& a, const TrowbridgeReitz& b)
    {
        return a.alpha_x() == b.alpha_x() && a.alpha_y() == b.alpha_y();
    }

    /// grid_eval at the grid positions of four lanes: the table values gathered, the
    /// interpolation in one register.
    V4 grid_eval4(const Grid& g, const GridPos* p)
    {
        const V4 a{g[p[0].i], g[p[1].i], g[p[2].i], g[p[3].i]};
        const V4 b{g[p[0].i + 1], g[p[1].i + 1], g[p[2].i + 1], g[p[3].i + 1]};
        const V4 t{p[0].t, p[1].t, p[2].t, p[3].t};
        return a + t * (b - a);
    }

    /// Adds a layer of `m`, thickness d, under the composite of the layers above it (its
    /// reflectance from above and below and its transmittance), four lanes from `gp`: KM R,
    /// T (§4.1) and the composite (§4.2), both patina/shading/kubelka_munk.h.
    /// Material `m`, `d` µm thick, under the layers above, at four grid positions.
    void add_layer(const CompiledMaterial& m, float d, const GridPos* gp, LayersAbove<V4>* above)
    {
        above->add(grid_eval4(m.absorption, gp), grid_eval4(m.scattering, gp), d);
    }

    /// eta_of_f0 for four lanes.
    V4 eta_of_f0_4(V4 f0)
    {
        const V4 s = sqrt4(clamp4(f0, 0.0f, 0.99f));
        return (1.0f + s) / (1.0f - s);
    }

    /// fresnel_dielectric(c, eta) for four lanes, c in [0, 1] (light from above).
    V4 fresnel_dielectric4(float c, V4 eta)
    {
        const float sin2_theta_i = 1.0f - c * c;
        const V4 sin2_theta_t = sin2_theta_i / (eta * eta);
        const V4 x = 1.0f - sin2_theta_t;
        const V4 cos_theta_t = sqrt4(x < splat(0.0f) ? splat(0.0f) : x);
        const V4 r_parl = (eta * c - cos_theta_t) / (eta * c + cos_theta_t);
        const V4 r_perp = (c - eta * cos_theta_t) / (c + eta * cos_theta_t);
        const V4 f = 0.5f * (r_parl * r_parl + r_perp * r_perp);
        return sin2_theta_t >= splat(1.0f) ? splat(1.0f) : f;
    }

}  // namespace

GridPos grid_pos(float lambda_nm)
{
    const float x = std::clamp((lambda_nm - kGridStartNm) / kGridStepNm, 0.0f,
                               static_cast<float>(kGridSize - 1));
    GridPos p;
    p.i = std::min(static_cast<int>(x), kGridSize - 2);
    p.t = x - static_cast<float>(p.i);
    return p;
}

LayeredModel::LayeredModel(const StackFile& stack, const std::vector<ThicknessSource>& sources,
                           const PatinaHost* host, const ModelOptions& options)
    : host_(host), options_(options)
{
    if (stack.layers.size() > static_cast<size_t>(kMaxLayers))
        throw std::runtime_error(stack.path.string() + ": " +
                                 std::to_string(stack.layers.size()) +
                                 " layers; the layered shader takes at most " +
                                 std::to_string(kMaxLayers));
    // Compile each material once; pointers stay valid (reserve before taking them).
    materials_.reserve(stack.materials.size());
    std::map<std::string, const CompiledMaterial*> by_name;
    for (const auto& [name, optics] : stack.materials) {
        materials_.push_back(compile(optics));
        by_name[name] = &materials_.back();
    }
    base_ = by_name.at(stack.base);
    for (const StackLayer& l : stack.layers)
        layers_.push_back(by_name.at(l.material));

    // Group the layers by texture: one lookup per texture fetches the channels of all its
    // layers (a multi-channel thickness map costs one lookup for the whole stack).
    layer_fetch_.assign(layers_.size(), {-1, 0});
    for (size_t l = 0; l < layers_.size() && l < sources.size(); ++l) {
        const ThicknessSource& src = sources[l];
        if (!src.texture || src.channel < 0)
            continue;
        int lo = src.channel, hi = src.channel;
        for (size_t k = l + 1; k < sources.size(); ++k)
            if (sources[k].texture == src.texture && layer_fetch_[k][0] < 0 &&
                sources[k].channel >= 0) {
                lo = std::min(lo, sources[k].channel);
                hi = std::max(hi, sources[k].channel);
            }
        if (layer_fetch_[l][0] >= 0)
            continue;
        if (hi - lo + 1 > kMaxFetchChannels)
            lo = hi = src.channel;  // too wide a span: this layer alone
        const int f = static_cast<int>(fetches_.size());
        fetches_.push_back({src.texture, lo, hi - lo + 1});
        for (size_t k = l; k < sources.size(); ++k)
            if (sources[k].texture == src.texture && layer_fetch_[k][0] < 0 &&
                sources[k].channel >= lo && sources[k].channel <= hi)
                layer_fetch_[k] = {f, sources[k].channel - lo};
    }
}

SpectralArray LayeredModel::interface_albedo(const Interface& lobe, float mu, int count)
{
    // albedo_table(material, f0, mu) with the F0 row found in setup.
    const float x = std::clamp(mu, 0.0f, 1.0f) * (kAlbedoNodes - 1);
    const int n = std::min(static_cast<int>(x), kAlbedoNodes - 2);
    const float t = x - static_cast<float>(n);
    const float* table = lobe.material->albedo.data();
    SpectralArray e;
    for (int i = 0; i < count; ++i) {
        const float* row0 = table + lobe.albedo_row[i] * kAlbedoNodes + n;
        const float* row1 = row0 + kAlbedoNodes;
        const float e0 = row0[0] + t * (row0[1] - row0[0]);
        const float e1 = row1[0] + t * (row1[1] - row1[0]);
        e[i] = (e0 + lobe.albedo_row_t[i] * (e1 - e0)) * lobe.albedo_scale[i];
    }
    return e;
}

namespace {

    /// The row of the albedo table F0 falls in (see albedo_table), four lanes from `o`.
    void locate_albedo_row4(Interface* lobe, int o)
    {
        const V4 f0 = load4(lobe->f0, o);
        const V4 sqrt_f0 = f0 > splat(0.0f) ? sqrt4(splat(1.0f) < f0 ? splat(1.0f) : f0)
                                            : splat(0.0f);
        const V4 y =
            clamp4((sqrt_f0 - kF0MinSqrt) / (kF0MaxSqrt - kF0MinSqrt), 0.0f, 1.0f) *
            static_cast<float>(kF0Nodes - 1);
        I4 q = __builtin_convertvector(y, I4);
        const I4 last = I4{} + (kF0Nodes - 2);
        q = last < q ? last : q;
        store4(&lobe->albedo_row[o], q);
        store4(&lobe->albedo_row_t[o], y - __builtin_convertvector(q, V4));
        store4(&lobe->albedo_scale[o],
               sqrt_f0 < splat(kF0MinSqrt) ? sqrt_f0 / kF0MinSqrt : splat(1.0f));
    }

    void locate_albedo_row(Interface* lobe, int count)
    {
        for (int o = 0; o < count; o += kLanes)
            locate_albedo_row4(lobe, o);
    }

    /// interface_albedo at four lanes from `o`: each lane's two neighbouring nodes of its two
    /// F0 rows are read as pairs and sorted into registers by shuffles.
    [[gnu::always_inline]] inline V4 interface_albedo4(const Interface& lobe, MuPos m, int o)
    {
        const float* table = lobe.material->albedo.data() + m.n;
        const float* p[kLanes];
        for (int l = 0; l < kLanes; ++l)
            p[l] = table + lobe.albedo_row[o + l] * kAlbedoNodes;
        // {row0[n], row0[n + 1]} of lanes 0, 1 and 2, 3; the same of row1.
        const V4 a01 = load2x2(p[0], p[1]), a23 = load2x2(p[2], p[3]);
        const V4 b01 = load2x2(p[0] + kAlbedoNodes, p[1] + kAlbedoNodes);
        const V4 b23 = load2x2(p[2] + kAlbedoNodes, p[3] + kAlbedoNodes);
        const I4 even{0, 2, 4, 6}, odd{1, 3, 5, 7};
        const V4 r00 = __builtin_shuffle(a01, a23, even), r01 = __builtin_shuffle(a01, a23, odd);
        const V4 r10 = __builtin_shuffle(b01, b23, even), r11 = __builtin_shuffle(b01, b23, odd);
        const V4 e0 = r00 + m.t * (r01 - r00);
        const V4 e1 = r10 + m.t * (r11 - r10);
        return (e0 + load4(lobe.albedo_row_t, o) * (e1 - e0)) * load4(lobe.albedo_scale, o);
    }

    /// The conductor Fresnel of four lanes with the point's n and k: fresnel_conductor_real's
    /// double arithmetic, two lanes per register, the c-independent terms computed once.
    struct ConductorLanes {
        D2 nk[2];       ///< n² - k²
        D2 four_nk[2];  ///< 4 n² k²
        bool mirror[kLanes];  ///< n = k = 0: reflects everything
    };

    ConductorLanes conductor_lanes(const Interface& lobe, int o)
    {
        ConductorLanes cl;
        for (int l = 0; l < kLanes; ++l) {
            const double n = lobe.f0[o + l], kk = lobe.kappa[o + l];
            cl.nk[l / 2][l % 2] = n * n - kk * kk;
            cl.four_nk[l / 2][l % 2] = 4.0 * n * n * kk * kk;
            cl.mirror[l] = lobe.f0[o + l] == 0.0f && lobe.kappa[o + l] == 0.0f;
        }
        return cl;
    }

    V4 fresnel_conductor4(float cos_theta_i, const ConductorLanes& cl)
    {
        const double c = std::min(1.0, std::abs(static_cast<double>(cos_theta_i)));
        const double c2 = c * c, s2 = 1.0 - c2;
        V4 f;
        for (int half = 0; half < 2; ++half) {
            const D2 t0 = cl.nk[half] - s2;
            const D2 a2b2 = sqrt2(t0 * t0 + cl.four_nk[half]);
            const D2 h = 0.5 * (a2b2 + t0);
            const D2 zero{0.0, 0.0};
            const D2 a = sqrt2(zero < h ? h : zero);  // std::max(0.0, h)
            const D2 t1 = a2b2 + c2, t2 = 2.0 * a * c;
            const D2 rs = (t1 - t2) / (t1 + t2);
            const D2 t3 = c2 * a2b2 + s2 * s2, t4 = t2 * s2;
            const D2 r = 0.5 * (rs + rs * (t3 - t4) / (t3 + t4));
            for (int l = 0; l < 2; ++l)
                f[2 * half + l] = cl.mirror[2 * half + l] || !std::isfinite(r[l])
                                      ? 1.0f
                                      : static_cast<float>(std::clamp(r[l], 0.0, 1.0));
        }
        return f;
    }

}  // namespace

void LayeredModel::setup(const PatinaShadingContext* ctx, const PatinaWavelengths& wl,
                         PointState* state) const
{
    std::array<float, kMaxLayers> thickness{};
    const float u = ctx ? ctx->uv.x : 0.0f, v = ctx ? ctx->uv.y : 0.0f;
    // One lookup per texture; a failed lookup reads as thickness 0 for its layers.
    std::array<float, kMaxLayers * kMaxFetchChannels> fetched;
    std::array<bool, kMaxLayers> fetch_ok{};
    for (size_t f = 0; f < fetches_.size(); ++f) {
        const Fetch& x = fetches_[f];
        fetch_ok[f] = host_->texture_lookup(host_, x.texture, ctx, u, v, x.first, x.count,
                                            &fetched[f * kMaxFetchChannels]) != 0;
    }
    for (size_t l = 0; l < layers_.size(); ++l) {
        const auto [f, offset] = layer_fetch_[l];
        if (f >= 0 && fetch_ok[f])
            thickness[l] = fetched[f * kMaxFetchChannels + offset] * options_.thickness_scale;
    }
    setup_thickness(thickness.data(), wl, state);
    state->u = u;
    state->v = v;
}

void LayeredModel::setup_thickness(const float* thickness_um, const PatinaWavelengths& wl,
                                   PointState* s) const
{
    s->wl = wl;
    const int count = wavelength_count(wl);
    const int groups = lane_groups(count);
    // Lanes past `count` sit at grid position 0 (their values are never read).
    std::array<GridPos, PATINA_MAX_WAVELENGTHS> gp{};
    for (int i = 0; i < count; ++i)
        gp[i] = grid_pos(wl.lambda_nm[i]);

    // The layers above the current depth as one composite, per lane group, walked from the
    // top down (patina/shading/layer_stack.h, §4.2-4.3).
    constexpr int kGroups = PATINA_MAX_WAVELENGTHS / kLanes;
    LayersAbove<V4> above_layers[kGroups];
    s->interfaces = 0;
    s->layers = 0;
    const CompiledMaterial* above = nullptr;
    for (int l = static_cast<int>(layers_.size()) - 1; l >= 0; --l) {
        const float d = thickness_um[l];
        if (!(d > 0.0f) || !is_finite(d))
            continue;
        const CompiledMaterial& m = *layers_[l];
        // KM R, T of this layer (§4.1) composited under the layers above (§4.2), below.
        // A layer of the material above continues it: no interface between them.
        if (!has_interface(&m, above)) {
            s->thickness_um[s->layers - 1] += d;
            for (int g = 0; g < groups; ++g)
                add_layer(m, d, &gp[kLanes * g], &above_layers[g]);
            continue;
        }
        above = &m;
        // The glossy lobe of this layer's top surface, seen through the layers above: its
        // specular colour times T_above² (§4.3).
        Interface& lobe = s->lobe[s->interfaces++];
        lobe.material = &m;
        lobe.fade = interface_fade(d);
        lobe.coupled = true;
        for (int g = 0; g < groups; ++g) {
            const int o = kLanes * g;
            store4(&lobe.attenuation[o], above_layers[g].attenuation(lobe.fade));
            store4(&lobe.f0[o], grid_eval4(m.specular, &gp[o]));
        }
        const Interface* prev = s->interfaces > 1 ? &s->lobe[s->interfaces - 2] : nullptr;
        bool same_f0 = prev != nullptr;
        for (int i = 0; i < count && same_f0; ++i)
            same_f0 = lobe.f0[i] == prev->f0[i];
        // Layers of one specular colour: the index and albedo rows of the lobe above.
        if (same_f0) {
            lobe.eta = prev->eta;
            lobe.albedo_row = prev->albedo_row;
            lobe.albedo_row_t = prev->albedo_row_t;
            lobe.albedo_scale = prev->albedo_scale;
        } else {
            for (int o = 0; o < count; o += kLanes) {
                store4(&lobe.eta[o], eta_of_f0_4(load4(lobe.f0, o)));
                locate_albedo_row4(&lobe, o);
            }
        }
        s->thickness_um[s->layers] = d;
        s->layer_material[s->layers++] = &m;
        for (int g = 0; g < groups; ++g)
            add_layer(m, d, &gp[kLanes * g], &above_layers[g]);
    }
    // The base's own surface: a conductor (n, k) or a dielectric lobe (specular).
    const CompiledMaterial& b = *base_;
    Interface& lobe = s->lobe[s->interfaces++];
    lobe.material = &b;
    lobe.fade = 1.0f;
    lobe.coupled = !b.metal;
    s->base = &b;
    for (int g = 0; g < groups; ++g) {
        const int o = kLanes * g;
        store4(&lobe.attenuation[o], above_layers[g].attenuation());
        const V4 r_base = grid_eval4(b.base_reflectance, &gp[o]);
        if (b.metal) {
            store4(&lobe.f0[o], grid_eval4(b.eta, &gp[o]));
            store4(&lobe.kappa[o], grid_eval4(b.kappa, &gp[o]));
            store4(&lobe.hemispherical[o], r_base);
        } else {
            const V4 f0 = grid_eval4(b.specular, &gp[o]);
            store4(&lobe.f0[o], f0);
            store4(&lobe.eta[o], eta_of_f0_4(f0));
        }
        // The stack over the opaque base (§4.2); a metal's direct reflection is its glossy
        // lobe, so the diffuse part keeps only the light the layers scattered.
        store4(&s->diffuse[o], clamp4(above_layers[g].diffuse_over(r_base, b.metal), 0.0f, 1.0f));
    }
    for (int i = count; i < PATINA_MAX_WAVELENGTHS; ++i)
        s->diffuse[i] = 0.0f;
    if (!b.metal)
        locate_albedo_row(&lobe, count);

    // The diffuse light the surfaces reflect back down is not lost: the stack below sends
    // R_d of it up again. With g(μ) = 1 - Π_j (1 - g_j(μ)) the surfaces' combined effective
    // reflectance (g_j = fade T_above² E_j, see eval) and ḡ = 2 ∫ g(μ) μ dμ, the diffuse lobe
    // is (1 - g(μo)) (1 - g(μi)) R_d / (π (1 - R_d ḡ)): its albedo (1 - g(μo)) R_d (1 - ḡ) /
    // (1 - R_d ḡ) is 1 - g(μo) for a white stack (R_d = 1) and never more.
    // ḡ by 8-point Gauss-Legendre quadrature over μ in [0, 1]; E_j at the nodes comes from
    // the material's albedo_gauss rows (the values interface_albedo would interpolate), the
    // 8 nodes of one wavelength in two registers.
    static_assert(kGaussNodes == 2 * kLanes);
    SpectralArray pass_mean(0.0f);
    for (int i = 0; i < count; ++i) {
        V4 pass_lo = splat(1.0f), pass_hi = splat(1.0f);
        for (int j = 0; j < s->interfaces; ++j) {
            const Interface& l = s->lobe[j];
            if (!l.coupled)
                continue;
            const float* row0 = &l.material->albedo_gauss[l.albedo_row[i] * kGaussNodes];
            const float* row1 = row0 + kGaussNodes;
            const float t = l.albedo_row_t[i], scale = l.albedo_scale[i];
            const float a = l.attenuation[i];
            const V4 lo0 = load4(row0), lo1 = load4(row1);
            const V4 hi0 = load4(row0 + kLanes), hi1 = load4(row1 + kLanes);
            pass_lo *= 1.0f - a * ((lo0 + t * (lo1 - lo0)) * scale);
            pass_hi *= 1.0f - a * ((hi0 + t * (hi1 - hi0)) * scale);
        }
        const V4 lo = pass_lo * load4(kGaussMeanWeight);
        const V4 hi = pass_hi * load4(kGaussMeanWeight + kLanes);
        float sum = 0.0f;  // in node order, as a scalar loop adds them
        for (int q = 0; q < kLanes; ++q)
            sum += lo[q];
        for (int q = 0; q < kLanes; ++q)
            sum += hi[q];
        pass_mean[i] = sum;
    }
    for (int o = 0; o < PATINA_MAX_WAVELENGTHS; o += kLanes) {
        const V4 g_mean = clamp4(1.0f - load4(pass_mean, o), 0.0f, 1.0f);
        const V4 diffuse = load4(s->diffuse, o);
        const V4 denom = 1.0f - diffuse * g_mean;
        const V4 lobe_value = denom > splat(1e-6f) ? diffuse / denom : splat(0.0f);
        store4(&s->diffuse_lobe[o], lobe_value);
        store4(&s->diffuse_albedo[o], lobe_value * (1.0f - g_mean));
    }
}

void LayeredModel::outgoing(const PointState& s, Vec3 wo, Outgoing* o)
{
    o->wo = Vec3(wo.x, wo.y, std::abs(wo.z));
    const float mu_o = o->wo.z;
    const int count = wavelength_count(s.wl);
    const int groups = lane_groups(count);
    const MuPos at_mu = mu_pos(mu_o);
    // Lobe selection probabilities at wo (glossy lobes, then the diffuse one), in proportion
    // to an estimate of each lobe's albedo, with E(μo) and Λ(wo) kept for eval.
    constexpr int kGroups = PATINA_MAX_WAVELENGTHS / kLanes;
    V4 coupling[kGroups] = {splat(1.0f), splat(1.0f)};
    float total = 0.0f;
    for (int j = 0; j < s.interfaces; ++j) {
        const Interface& lobe = s.lobe[j];
        SpectralArray& e = o->e[j];
        const float one = lobe.material->metal ? albedo_table(lobe.material->albedo_one, mu_o)
                                               : 0.0f;
        float sum = 0.0f;  // mean over the wavelengths, added in order
        for (int g = 0; g < groups; ++g) {
            const int k = kLanes * g;
            const V4 eg = lobe.material->metal ? load4(lobe.hemispherical, k) * one
                                               : interface_albedo4(lobe, at_mu, k);
            store4(&e[k], eg);
            const V4 a = load4(lobe.attenuation, k);
            const V4 term = coupling[g] * a * eg;
            for (int l = 0; l < kLanes && k + l < count; ++l)
                sum += term[l];
            if (lobe.coupled)
                coupling[g] *= 1.0f - a * eg;
        }
        const TrowbridgeReitz& dist = lobe.material->distribution;
        o->lambda[j] = j > 0 && same_widths(dist, s.lobe[j - 1].material->distribution)
                           ? o->lambda[j - 1]
                           : dist.lambda(o->wo);
        o->p[j] = count > 0 ? sum / count : 0.0f;
        total += o->p[j];
    }
    float sum = 0.0f;
    for (int g = 0; g < groups; ++g) {
        const V4 term = coupling[g] * load4(s.diffuse_albedo, kLanes * g);
        for (int l = 0; l < kLanes && kLanes * g + l < count; ++l)
            sum += term[l];
    }
    o->p[s.interfaces] = count > 0 ? sum / count : 0.0f;
    total += o->p[s.interfaces];
    o->sampleable = mu_o > 0.0f && total > 0.0f && is_finite(total);
    if (o->sampleable)
        for (int j = 0; j <= s.interfaces; ++j)
            o->p[j] /= total;
}

void LayeredModel::eval_km(const PointState& s, const Outgoing& o, Vec3 wo, Vec3 wi,
                           SpectralArray* f) const
{
    *f = SpectralArray(0.0f);
    if (!to_upper(&wo, &wi))
        return;
    const int count = wavelength_count(s.wl);
    const int groups = lane_groups(count);
    const float mu_o = wo.z, mu_i = wi.z;
    const Vec3 h = wo + wi;
    if (length_squared(h) == 0.0f)
        return;
    const Vec3 wm = normalize(h);
    const float c = std::clamp(dot(wo, wm), 0.0f, 1.0f);
    const MuPos at_mu_i = mu_pos(mu_i);
    // D·G of each lobe: Torrance-Sparrow with GGX and Smith G2, Walter et al. 2007 Eq. 20
    // (the same value as the lobe above when the widths are the same).
    std::array<float, kMaxLayers + 1> dg;
    for (int j = 0; j < s.interfaces; ++j) {
        const TrowbridgeReitz& dist = s.lobe[j].material->distribution;
        dg[j] = j > 0 && same_widths(dist, s.lobe[j - 1].material->distribution)
                    ? dg[j - 1]
                    : dist.d(wm) * (1.0f / (1.0f + o.lambda[j] + dist.lambda(wi))) /
                          (4.0f * mu_o * mu_i);
    }
    for (int g = 0; g < groups; ++g) {
        const int k = kLanes * g;
        // Sum of the glossy lobes from the top interface down; `coupling` is the part of the
        // light that passed the interfaces above, (1 - E(μo)) (1 - E(μi)) per interface.
        V4 sum = splat(0.0f), coupling = splat(1.0f);
        // Dielectric Fresnel of the last indices: layers of one specular colour share it.
        V4 last_eta = splat(-1.0f), last_f = splat(0.0f);
        for (int j = 0; j < s.interfaces; ++j) {
            const Interface& lobe = s.lobe[j];
            const V4 a = load4(lobe.attenuation, k);
            if (dg[j] > 0.0f && is_finite(dg[j])) {
                V4 F;
                if (lobe.material->metal) {
                    F = fresnel_conductor4(c, conductor_lanes(lobe, k));
                } else {
                    const V4 eta = load4(lobe.eta, k);
                    if (!all_equal(eta, last_eta)) {
                        last_eta = eta;
                        last_f = fresnel_dielectric4(c, eta);
                    }
                    // F0 = 0: index-matched, no reflection
                    F = load4(lobe.f0, k) > splat(0.0f) ? last_f : splat(0.0f);
                }
                sum += coupling * a * F * dg[j];
            }
            if (lobe.coupled) {
                const V4 eo = load4(o.e[j], k);
                const V4 ei = interface_albedo4(lobe, at_mu_i, k);
                coupling *= (1.0f - a * eo) * (1.0f - a * ei);
            }
        }
        store4(&(*f)[k], sum + coupling * load4(s.diffuse_lobe, k) * kInvPi);
    }
    // Lanes past `count` stay 0, as the ABI's unused entries.
    for (int i = count; i < kLanes * groups; ++i)
        (*f)[i] = 0.0f;
}

void LayeredModel::eval(const PointState& s, const Outgoing& o, Vec3 wo, Vec3 wi,
                        float* f) const
{
    SpectralArray value;
    if (options_.model == Model::random_walk)
        eval_random_walk(s, wo, wi, &value);
    else
        eval_km(s, o, wo, wi, &value);
    store(value, s.wl, f);
}

float LayeredModel::pdf(const PointState& s, const Outgoing& o, Vec3 wo, Vec3 wi) const
{
    if (!to_upper(&wo, &wi) || !o.sampleable)
        return 0.0f;
    return mixture_pdf(s, o, wi);
}

float LayeredModel::mixture_pdf(const PointState& s, const Outgoing& o, Vec3 wi)
{
    const Vec3 wo = o.wo;
    float pdf = o.p[s.interfaces] * cosine_hemisphere_pdf(wi.z);
    const Vec3 h = wo + wi;
    if (length_squared(h) > 0.0f) {
        const Vec3 wm = normalize(h);
        const float c = dot(wo, wm);
        if (c > 0.0f) {
            float lobe_pdf = 0.0f;
            for (int j = 0; j < s.interfaces; ++j) {
                const TrowbridgeReitz& dist = s.lobe[j].material->distribution;
                // the visible-normal density of the lobe above when the widths are the same
                if (j == 0 || !same_widths(dist, s.lobe[j - 1].material->distribution))
                    lobe_pdf = dist.pdf(wo, wm) / (4.0f * c);
                if (o.p[j] > 0.0f)
                    pdf += o.p[j] * lobe_pdf;
            }
        }
    }
    return is_finite(pdf) ? pdf : 0.0f;
}

int LayeredModel::sample(const PointState& s, const Outgoing& o, Vec3 wo, float u_lobe, Vec2 u,
                         PatinaBsdfSample* out) const
{
    if (wo.z == 0.0f || !o.sampleable)
        return 0;
    const bool below = wo.z < 0.0f;
    const Vec3 w = o.wo;
    // Pick a lobe by u_lobe in proportion to its estimated albedo.
    int chosen = s.interfaces;
    float cdf = 0.0f;
    for (int j = 0; j < s.interfaces; ++j) {
        cdf += o.p[j];
        if (u_lobe < cdf) {
            chosen = j;
            break;
        }
    }
    Vec3 wi;
    if (chosen < s.interfaces) {
        const Vec3 wm = s.lobe[chosen].material->distribution.sample_wm(w, u);
        wi = normalize(reflect(w, wm));
        out->lobe = PATINA_LOBE_REFLECTION | PATINA_LOBE_GLOSSY;
    } else {
        wi = sample_cosine_hemisphere(u);
        out->lobe = PATINA_LOBE_REFLECTION | PATINA_LOBE_DIFFUSE;
    }
    if (!(wi.z > 0.0f))
        return 0;
    // f and pdf exactly as eval and pdf compute them (the same mixture probabilities p).
    const float pdf_value = mixture_pdf(s, o, wi);
    if (below)
        wi.z = -wi.z;
    if (!(pdf_value > 0.0f))
        return 0;
    eval(s, o, wo, wi, out->f);
    out->wi = wi;
    out->pdf = pdf_value;
    out->eta = 1.0f;
    return 1;
}

void LayeredModel::albedo(const PointState& s, Vec3 wo, float* a) const
{
    SpectralArray value;
    const int count = wavelength_count(s.wl);
    if (options_.model == Model::random_walk) {
        albedo_random_walk(s, wo, options_.walk_samples, 0x9e3779b97f4a7c15ULL, &value);
    } else {
        // Sum of the lobe estimates lobe selection uses.
        const float mu = std::abs(wo.z);
        SpectralArray coupling(1.0f);
        for (int j = 0; j < s.interfaces; ++j) {
            const Interface& lobe = s.lobe[j];
            SpectralArray e;
            if (lobe.material->metal)
                e = lobe.hemispherical * albedo_table(lobe.material->albedo_one, mu);
            else
                e = interface_albedo(lobe, mu, count);
            value += coupling * lobe.attenuation * e;
            if (lobe.coupled)
                for (int i = 0; i < count; ++i)
                    coupling[i] *= 1.0f - lobe.attenuation[i] * e[i];
        }
        value += coupling * s.diffuse_albedo;
    }
    store(value, s.wl, a);
}

}  // namespace patina::layered
