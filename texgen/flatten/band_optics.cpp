#include "texgen/flatten/band_optics.h"

#include "core/spectrum.h"

#include <patina/shading/fresnel.h>
#include <patina/shading/microfacet.h>
#include <patina/shading/layer_stack.h>
#include <patina/shading/spectral.h>

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace patina::texgen {

namespace {

    /// `values` over `lambda_nm` at the band nodes, interpolated as layered_km resamples a
    /// table (linear, constant beyond the ends); all 0 for an empty table.
    Bands at_bands(const formats::MaterialOptics& o, const std::vector<double>& values,
                   const char* what)
    {
        Bands out{};
        if (values.empty())
            return out;
        if (values.size() != o.lambda_nm.size())
            throw std::runtime_error(fmt::format(
                "material '{}': {} has {} values for {} wavelengths", o.name, what,
                values.size(), o.lambda_nm.size()));
        const std::vector<float> lambda(o.lambda_nm.begin(), o.lambda_nm.end());
        const std::vector<float> v(values.begin(), values.end());
        const PatinaTabulatedSpectrum table{static_cast<int>(v.size()), lambda.data(), v.data()};
        for (int i = 0; i < kBandCount; ++i)
            out[i / shading::simd::kLanes][i % shading::simd::kLanes] =
                patina_tabulated_eval(&table, band_wavelength(i));
        return out;
    }

    float& node(Bands& b, int i) { return b[i / shading::simd::kLanes][i % shading::simd::kLanes]; }

}  // namespace

Bands constant_bands(float value)
{
    Bands b;
    b.fill(shading::simd::splat(value));
    return b;
}

BandMaterial band_material(const formats::MaterialOptics& o)
{
    BandMaterial m;
    m.name = o.name;
    m.metal = o.metal;
    m.roughness = static_cast<float>(o.roughness);
    if (o.metal) {
        Bands n = at_bands(o, o.n, "n"), k = at_bands(o, o.k, "k");
        for (int i = 0; i < kBandCount; ++i) {
            node(m.specular, i) = shading::fresnel_conductor_normal(node(n, i), node(k, i));
            node(m.base_reflectance, i) = shading::base_reflectance_metal(node(n, i), node(k, i));
        }
        return m;
    }
    m.absorption = at_bands(o, o.absorption_per_um, "absorption_per_um");
    m.scattering = at_bands(o, o.scattering_per_um, "scattering_per_um");
    m.specular = at_bands(o, o.specular, "specular");
    for (int i = 0; i < kBandCount; ++i)
        node(m.base_reflectance, i) =
            shading::base_reflectance_dielectric(node(m.absorption, i), node(m.scattering, i));
    return m;
}

namespace {

    BandStack make_band_stack(const std::string& base, const std::vector<std::string>& layers,
                              const std::map<std::string, formats::MaterialOptics>& optics,
                              const std::filesystem::path& manifest)
    {
        BandStack stack;
        auto find = [&](const std::string& name, const std::string& what) {
            if (const auto it = stack.materials.find(name); it != stack.materials.end())
                return &it->second;
            const auto it = optics.find(name);
            if (it == optics.end())
                throw std::runtime_error(fmt::format(
                    "patina stack '{}': {} material '{}' has no optics in [patina.materials]",
                    manifest.string(), what, name));
            try {
                return &stack.materials.emplace(name, band_material(it->second)).first->second;
            } catch (const std::runtime_error& e) {
                throw std::runtime_error(
                    fmt::format("patina stack '{}': {}", manifest.string(), e.what()));
            }
        };
        stack.base = find(base, "base");
        for (size_t i = 0; i < layers.size(); ++i)
            stack.layers.push_back(find(layers[i], fmt::format("layer {}", i + 1)));
        return stack;
    }

}  // namespace

BandStack band_stack(const formats::PatinaTable& patina, const std::filesystem::path& manifest)
{
    std::vector<std::string> layers;
    for (const formats::PatinaLayer& l : patina.layers)
        layers.push_back(l.material);
    return make_band_stack(patina.base, layers, patina.materials, manifest);
}

BandStack band_stack(const PatinaStackFiles& stack)
{
    std::vector<std::string> layers;
    for (const StackLayerFiles& l : stack.layers)
        layers.push_back(l.material);
    return make_band_stack(stack.base, layers, stack.materials, stack.manifest);
}

void tabulate_lobe_albedos(BandStack& stack, const BandsToRgb& to_rgb)
{
    for (auto& [name, m] : stack.materials) {
        // As layered_km compiles the material: roughness at least 0.03, α = r².
        const float alpha =
            shading::TrowbridgeReitz::roughness_to_alpha(std::max(m.roughness, 0.03f));
        std::array<float, shading::kF0Nodes * shading::kAlbedoNodes> table;
        std::array<float, shading::kAlbedoNodes> one;
        shading::tabulate_ggx_albedo(shading::TrowbridgeReitz(alpha, alpha), table, one);
        for (int g = 0; g < shading::kGaussNodes; ++g) {
            const float mu = shading::kGaussMu[g];
            Bands e{};
            for (int i = 0; i < kBandCount; ++i)
                node(e, i) = m.metal ? node(m.base_reflectance, i) * shading::albedo_at(one, mu)
                                     : shading::albedo_at(table, node(m.specular, i), mu);
            const Imath::V3f c = to_rgb(e);
            m.lobe_albedo[static_cast<size_t>(g)] = shading::simd::V4{c.x, c.y, c.z, 0.0f};
        }
    }
}

BandsToRgb::BandsToRgb(const ColorManager& colors)
{
    // XYZ of each node's hat function (the polyline's share of that node) under D65.
    std::array<std::array<double, 3>, kBandCount> xyz{};
    double white_y = 0.0;
    for (int l = static_cast<int>(kLambdaMinNm); l <= static_cast<int>(kLambdaMaxNm); ++l) {
        const float lambda = static_cast<float>(l);
        const double e = d65(lambda);
        const double cmf[3] = {cie_x(lambda) * e, cie_y(lambda) * e, cie_z(lambda) * e};
        white_y += cmf[1];
        const float x = (lambda - kBandStartNm) / kBandStepNm;
        int i = static_cast<int>(std::floor(x));
        double t = x - i;
        if (i < 0) {
            i = 0;
            t = 0.0;
        } else if (i >= kBandCount - 1) {
            i = kBandCount - 2;
            t = 1.0;
        }
        for (int c = 0; c < 3; ++c) {
            xyz[i][c] += (1.0 - t) * cmf[c];
            xyz[i + 1][c] += t * cmf[c];
        }
    }
    // To linear Rec.709 through OCIO (a linear map: each node's XYZ by itself).
    std::array<float, 3 * kBandCount> rgb;
    for (int i = 0; i < kBandCount; ++i)
        for (int c = 0; c < 3; ++c)
            rgb[3 * i + c] = static_cast<float>(xyz[i][c] / white_y);
    colors.convert("CIE-XYZ-D65", "lin_rec709", rgb.data(), kBandCount);
    for (int c = 0; c < 3; ++c) {
        double white = 0.0;
        for (int i = 0; i < kBandCount; ++i)
            white += rgb[3 * i + c];
        for (int i = 0; i < kBandCount; ++i) {
            weights_[c][i] = static_cast<float>(rgb[3 * i + c] / white);
            node(rows_[c], i) = weights_[c][i];
        }
    }
}

Imath::V3f BandsToRgb::operator()(const Bands& r) const
{
    Imath::V3f out;
    for (int c = 0; c < 3; ++c) {
        shading::simd::V4 sum = rows_[c][0] * r[0];
        for (int g = 1; g < kBandGroups; ++g)
            sum += rows_[c][g] * r[g];
        out[c] = (sum[0] + sum[1]) + (sum[2] + sum[3]);
    }
    return out;
}

}  // namespace patina::texgen
