// The layered Kubelka-Munk BSDF of a patina stack (Dorsey & Hanrahan 1996 §4), compiled from
// a stack.toml for fast evaluation: every material resampled onto one 5 nm grid, the
// directional albedo of each interface's GGX lobe tabulated over cos θ. Per shading point
// and wavelength, `setup` looks up the layer thicknesses and composites the layers (§4.1,
// §4.2); `eval`, `pdf` and `sample` then sum one diffuse lobe and one glossy lobe per
// interface (§4.3). The model and its deviations from the paper are described in
// plugins/layered/README.md and at the top of layered.cpp.
//
// LayeredModel is immutable after construction and every member function is reentrant and
// allocation-free; the plugin's C functions are thin wrappers around it (bench/
// layered_shading.cpp calls it directly to measure the cost of the ABI).
#pragma once

#include "stack_file.h"

#include <patina/abi.h>
#include <patina/shading/ggx_albedo.h>
#include <patina/shading/layer_stack.h>
#include <patina/shading/microfacet.h>
#include <patina/shading/spectral.h>

#include <array>
#include <vector>

namespace patina::layered {

using shading::SpectralArray;
using shading::Vec2;
using shading::Vec3;

/// Most layers a stack may hold (the interfaces are one more).
inline constexpr int kMaxLayers = 16;
/// The common wavelength grid: 360-830 nm every 5 nm.
inline constexpr int kGridSize = 95;
inline constexpr float kGridStartNm = 360.0f;
inline constexpr float kGridStepNm = 5.0f;
/// The directional albedo tables (patina/shading/ggx_albedo.h).
using shading::dielectric_fresnel;
using shading::eta_of_f0;
using shading::kAlbedoNodes;
using shading::kGaussMeanWeight;
using shading::kGaussMu;
using shading::kGaussNodes;
using shading::kGaussWeight;
using shading::kF0MaxSqrt;
using shading::kF0MinSqrt;
using shading::kF0Nodes;

enum class Model { kubelka_munk, random_walk };

using Grid = std::array<float, kGridSize>;

/// One material on the common grid.
struct CompiledMaterial {
    bool metal = false;
    Grid absorption{};  ///< K per µm
    Grid scattering{};  ///< S per µm
    Grid specular{};    ///< F0 of its top surface (dielectric interfaces)
    Grid eta{}, kappa{}; ///< metal: n, k
    /// What the diffuse compositing sees below the layers: R_inf of a thick dielectric base,
    /// or the hemispherical reflectance 2 ∫ F(μ) μ dμ of a smooth metal (see README).
    Grid base_reflectance{};
    shading::TrowbridgeReitz distribution{1.0f, 1.0f};
    float roughness = 0.5f;
    /// Directional albedo E(F0, μ) of its GGX lobe with the exact dielectric Fresnel of the
    /// index η that has normal reflectance F0, over √F0 = kF0MinSqrt ... kF0MaxSqrt and
    /// μ = i / (kAlbedoNodes - 1) (row q); albedo_one is the row F = 1 (metal estimate).
    std::array<float, kF0Nodes * kAlbedoNodes> albedo{};
    std::array<float, kAlbedoNodes> albedo_one{};
    /// The rows of `albedo` interpolated in μ at the kGaussNodes nodes (row q: nodes
    /// q * kGaussNodes ...), with the very float operations interface_albedo does, so the
    /// quadrature of ḡ reads them instead of interpolating per point.
    std::array<float, kF0Nodes * kGaussNodes> albedo_gauss{};
};

/// Grid position of a wavelength: index and weight for linear interpolation.
struct GridPos {
    int i = 0;
    float t = 0.0f;
};

/// One glossy lobe of a shading point, from the top interface down.
struct Interface {
    const CompiledMaterial* material = nullptr;
    float fade = 1.0f;          ///< shading::interface_fade of its layer
    bool coupled = true;        ///< its reflection is taken out of what passes below it
    SpectralArray attenuation;  ///< fade · T_above², T_above the KM transmittance above (§4.3)
    SpectralArray f0;           ///< normal reflectance F0 (dielectric) or n (metal)
    SpectralArray eta;          ///< dielectric: the index with reflectance F0
    SpectralArray kappa;        ///< metal k
    SpectralArray hemispherical; ///< metal: hemispherical reflectance (lobe selection)
    /// Where F0 falls in the material's albedo table, per wavelength (found once in setup).
    std::array<int, PATINA_MAX_WAVELENGTHS> albedo_row{};
    SpectralArray albedo_row_t, albedo_scale;
};

/// Everything a shading point needs, computed once by setup (uv, wavelengths).
struct PointState {
    PatinaWavelengths wl{};
    int interfaces = 0;
    std::array<Interface, kMaxLayers + 1> lobe{};
    SpectralArray diffuse;  ///< KM R_d of the stack over the base (the diffuse part)
    SpectralArray diffuse_lobe;   ///< R_d / (1 - R_d ḡ): the diffuse lobe is this / π, coupled
    SpectralArray diffuse_albedo; ///< the diffuse lobe's albedo over (1 - g(μo))
    /// For the random walk: layer thicknesses (µm) and materials, top to bottom.
    int layers = 0;
    std::array<float, kMaxLayers> thickness_um{};
    std::array<const CompiledMaterial*, kMaxLayers> layer_material{};
    const CompiledMaterial* base = nullptr;
    float u = 0.0f, v = 0.0f;
};

/// What depends on the point and wo only (not wi), computed once by LayeredModel::outgoing:
/// eval, pdf and sample at one wo share it (a renderer's light sample, its pdf and the BSDF
/// sample all leave the point towards the same wo).
struct Outgoing {
    Vec3 wo;  ///< wo in the upper hemisphere (z = |wo.z|)
    /// Per lobe: E(μo) (a dielectric's directional albedo; a metal's hemispherical reflectance
    /// times its F = 1 albedo, for lobe selection only) and the Smith Λ(wo) of its distribution.
    std::array<SpectralArray, kMaxLayers + 1> e;
    std::array<float, kMaxLayers + 1> lambda{};
    /// Lobe selection probabilities (glossy lobes, then the diffuse one); sampleable is false
    /// when every estimate is 0 (pdf and sample then return 0).
    std::array<float, kMaxLayers + 2> p{};
    bool sampleable = false;
};

/// Where a layer's thickness comes from: a channel of a texture (null: thickness 0).
struct ThicknessSource {
    const PatinaTexture* texture = nullptr;
    int channel = 0;
};

struct ModelOptions {
    Model model = Model::kubelka_munk;
    float thickness_scale = 1.0f;
    int walk_samples = 64;
};

class LayeredModel {
public:
    /// `sources[l]` is the thickness map channel of stack.layers[l] (bottom to top). Layers
    /// reading one texture share one lookup of the channels they span. Throws
    /// std::runtime_error for a stack deeper than kMaxLayers.
    LayeredModel(const StackFile& stack, const std::vector<ThicknessSource>& sources,
                 const PatinaHost* host, const ModelOptions& options);

    /// Layer thicknesses at ctx->uv and the KM compositing (§4.1, §4.2) at wl.
    void setup(const PatinaShadingContext* ctx, const PatinaWavelengths& wl,
               PointState* state) const;
    /// As setup, with given thicknesses (µm, bottom to top) instead of texture lookups.
    void setup_thickness(const float* thickness_um, const PatinaWavelengths& wl,
                         PointState* state) const;

    /// The wo-dependent terms of the point (for wo on either side; wo.z = 0 leaves the
    /// point unsampleable).
    static void outgoing(const PointState& s, Vec3 wo, Outgoing* o);

    /// eval, pdf and sample take the Outgoing of their wo (from outgoing(s, wo, ...)).
    void eval(const PointState& s, const Outgoing& o, Vec3 wo, Vec3 wi, float* f) const;
    float pdf(const PointState& s, const Outgoing& o, Vec3 wo, Vec3 wi) const;
    int sample(const PointState& s, const Outgoing& o, Vec3 wo, float u_lobe, Vec2 u,
               PatinaBsdfSample* out) const;
    void albedo(const PointState& s, Vec3 wo, float* albedo) const;

    /// The Kubelka-Munk model whatever `options.model` says (the reference compares both).
    void eval_km(const PointState& s, const Outgoing& o, Vec3 wo, Vec3 wi,
                 SpectralArray* f) const;
    /// The random-walk reference: f estimated with `walk_samples` walks (random_walk.cpp).
    void eval_random_walk(const PointState& s, Vec3 wo, Vec3 wi, SpectralArray* f) const;
    /// Directional albedo by analog random walks (`walks` of them per wavelength).
    void albedo_random_walk(const PointState& s, Vec3 wo, int walks, uint64_t seed,
                            SpectralArray* albedo) const;

    size_t layer_count() const { return layers_.size(); }
    const ModelOptions& options() const { return options_; }

    /// E(μ) of a dielectric interface at the point's wavelengths.
    static SpectralArray interface_albedo(const Interface& i, float mu, int count);

private:
    /// The mixture density of o.p (wi in the upper hemisphere).
    static float mixture_pdf(const PointState& s, const Outgoing& o, Vec3 wi);

    std::vector<CompiledMaterial> materials_;
    const CompiledMaterial* base_ = nullptr;
    std::vector<const CompiledMaterial*> layers_;  ///< bottom to top
    /// One texture lookup of channels [first, first + count) per distinct texture (at most
    /// kMaxFetchChannels; a wider span is split), and per layer the fetch and offset of its
    /// channel (fetch -1: no texture, thickness 0).
    static constexpr int kMaxFetchChannels = 16;
    struct Fetch {
        const PatinaTexture* texture = nullptr;
        int first = 0, count = 0;
    };
    std::vector<Fetch> fetches_;
    std::vector<std::array<int, 2>> layer_fetch_;  ///< {fetch, offset} per layer
    const PatinaHost* host_ = nullptr;
    ModelOptions options_;
};

/// Grid lookup helpers shared with random_walk.cpp.
GridPos grid_pos(float lambda_nm);
inline float grid_eval(const Grid& g, GridPos p)
{
    return g[p.i] + p.t * (g[p.i + 1] - g[p.i]);
}
/// Linear interpolation in a kAlbedoNodes table over μ in [0, 1].
inline float albedo_table(const std::array<float, kAlbedoNodes>& table, float mu)
{
    return shading::albedo_at(table, mu);
}
/// Bilinear interpolation of CompiledMaterial::albedo at (F0, μ).
inline float albedo_table(const CompiledMaterial& m, float f0, float mu)
{
    return shading::albedo_at(m.albedo, f0, mu);
}

}  // namespace patina::layered
