#include "render/environment_light.h"

#include <patina/shading/fast_trig.h>

#include "core/color_management.h"
#include "host/host.h"
#include "core/image_io.h"
#include "core/rgb_spectrum.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>

namespace patina::render {

namespace {

    constexpr double kPi = 3.14159265358979323846;
    constexpr float kPiF = static_cast<float>(kPi);
    constexpr float kTwoPiF = static_cast<float>(2.0 * kPi);

    // The sampling density is constant over a cell in (u, v) and its weight uses sin(theta)
    // at the cell's centre row; a map with few rows (a 1x1 constant) is split into at least
    // this many rows so the density stays close to uniform in solid angle away from the poles
    // (cot(theta) * pi / (2 * 256) relative: 0.35 % at 30° from the horizon).
    constexpr int kMinSamplingRows = 256;
    // Larger maps are sampled through a max-downsampled grid: Distribution2D keeps a float
    // and a double per cell, 12 bytes x 8192 x 4096 would be 400 MB.
    constexpr int kMaxSamplingColumns = 4096;
    constexpr int kMaxSamplingRows = 2048;
    // A texel that is not black gets at least this fraction of the mean luminance as its
    // sampling weight, so a colour of (near) zero luminance is still found by light sampling.
    constexpr double kLuminanceFloor = 1e-3;
    // Distinct colours remembered while uplifting (about 40 bytes each); colours met after
    // the cache is full are uplifted without being remembered.
    constexpr size_t kMaxCachedColours = size_t(1) << 18;

    using RgbBits = std::array<uint32_t, 3>;
    struct RgbBitsHash {
        size_t operator()(const RgbBits& k) const
        {
            return static_cast<size_t>(mix_bits((uint64_t(k[0]) << 32 | k[1]) ^ mix_bits(k[2])));
        }
    };

    // Texels [first, last) of `texels` that overlap cell i of `cells` equal cells.
    struct TexelRange {
        int first, last;
    };
    TexelRange texels_of_cell(int i, int cells, int texels)
    {
        const int64_t n = texels, c = cells;
        const int first = static_cast<int>(i * n / c);
        const int last = static_cast<int>(((i + 1) * n + c - 1) / c);
        return {first, std::max(last, first + 1)};
    }

    // The three channel indices holding R, G, B (a grey image repeats its first channel).
    std::array<int, 3> rgb_channels(const ImageData& image)
    {
        const int r = image.channel("R"), g = image.channel("G"), b = image.channel("B");
        if (r >= 0 && g >= 0 && b >= 0)
            return {r, g, b};
        if (image.channels >= 3)
            return {0, 1, 2};
        const int y = image.channel("Y") >= 0 ? image.channel("Y") : 0;
        return {y, y, y};
    }

    ImageData constant_image(const std::array<float, 3>& rgb)
    {
        ImageData image;
        image.width = image.height = 1;
        image.channels = 3;
        image.pixels = {rgb[0], rgb[1], rgb[2]};
        image.channel_names = {"R", "G", "B"};
        return image;
    }

    ImageData read_map(const std::filesystem::path& file)
    {
        try {
            return read_image(file);
        } catch (const std::exception& e) {
            throw std::runtime_error(fmt::format("environment map: {}", e.what()));
        }
    }

} // namespace

EnvironmentLight::EnvironmentLight(const Host& host, const std::filesystem::path& file,
                                   std::string_view colorspace, float intensity, float rotation_deg)
    : source_name_(file.string()), intensity_(intensity), rotation_deg_(rotation_deg)
{
    // Check the cheap arguments before reading a possibly large file.
    check_arguments(host, colorspace);
    build(host, read_map(file), colorspace);
}

EnvironmentLight::EnvironmentLight(const Host& host, const std::array<float, 3>& working_rgb,
                                   float intensity)
    : source_name_("<constant environment>"), intensity_(intensity)
{
    build(host, constant_image(working_rgb), host.colors().working_space());
}

EnvironmentLight::EnvironmentLight(const Host& host, ImageData image,
                                   std::string_view colorspace, float intensity, float rotation_deg,
                                   std::string source_name)
    : source_name_(std::move(source_name)), intensity_(intensity), rotation_deg_(rotation_deg)
{
    build(host, std::move(image), colorspace);
}

void EnvironmentLight::check_arguments(const Host& host, std::string_view colorspace) const
{
    const ColorManager& colors = host.colors();
    if (!std::isfinite(intensity_) || intensity_ < 0.0f)
        throw std::invalid_argument(
            fmt::format("environment map '{}': intensity {} must be finite and >= 0", source_name_,
                        intensity_));
    if (!std::isfinite(rotation_deg_))
        throw std::invalid_argument(fmt::format(
            "environment map '{}': rotation_deg {} must be finite", source_name_, rotation_deg_));
    if (!colors.has_colorspace(colorspace))
        throw std::runtime_error(
            fmt::format("environment map '{}': unknown colour space '{}' in OCIO config '{}'",
                        source_name_, colorspace, colors.config_path().string()));
}

void EnvironmentLight::build(const Host& host, ImageData image, std::string_view colorspace)
{
    check_arguments(host, colorspace);
    const ColorManager& colors = host.colors();
    if (image.width <= 0 || image.height <= 0 || image.channels <= 0)
        throw std::runtime_error(fmt::format("environment map '{}': empty image", source_name_));
    if (image.pixels.size() != static_cast<size_t>(image.width) * image.height * image.channels)
        throw std::invalid_argument(fmt::format(
            "environment map '{}': {} pixel values for {} x {} x {} channels", source_name_,
            image.pixels.size(), image.width, image.height, image.channels));

    const double rot = rotation_deg_ * kPi / 180.0;
    cos_rot_ = static_cast<float>(std::cos(rot));
    sin_rot_ = static_cast<float>(std::sin(rot));
    width_ = image.width;
    height_ = image.height;
    const size_t n = static_cast<size_t>(width_) * height_;

    // Gather R, G, B, refusing NaN/Inf: a bad texel would otherwise turn into a plausible
    // (black or white) patch of sky. The first bad one in scanline order is named. When the
    // image holds R, G, B as its first channels, they are packed in place: a production
    // HDRI (16384 x 8192) is not copied.
    const std::array<int, 3> ch = rgb_channels(image);
    const size_t nc = static_cast<size_t>(image.channels);
    const bool in_place = nc >= 3 && ch[0] == 0 && ch[1] == 1 && ch[2] == 2;
    std::vector<float> rgb;
    if (!in_place)
        rgb.resize(3 * n);
    float* packed = in_place ? image.pixels.data() : rgb.data();
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const size_t i = static_cast<size_t>(y) * width_ + x;
            for (int c = 0; c < 3; ++c) {
                // (In place, the source i*nc + c never lies below the destination 3i + c.)
                const float v = image.pixels[i * nc + static_cast<size_t>(ch[c])];
                if (!std::isfinite(v))
                    throw std::runtime_error(fmt::format(
                        "environment map '{}': texel ({}, {}) is {} (channel {})", source_name_, x,
                        y, std::isnan(v) ? "NaN" : "infinite", "RGB"[c]));
                packed[3 * i + c] = v;
            }
        }
    if (in_place) {
        image.pixels.resize(3 * n);  // (keeps the allocation: no copy)
        rgb = std::move(image.pixels);
    } else {
        image.pixels = {};
    }

    // Convert once to the working space (data spaces are not colours: used as they are),
    // then clamp what falls outside the working gamut or below zero.
    if (!colors.is_data(colorspace)) {
        const ColorConversion to_working = colors.conversion(colorspace, colors.working_space());
        if (!to_working.is_identity())
            tbb::parallel_for(0, height_, [&](int y) {
                to_working.apply(&rgb[3 * static_cast<size_t>(y) * width_],
                                 static_cast<size_t>(width_));
            });
    }
    // (v > 0 also folds -0 into +0, so equal colours have equal bits below.)
    for (float& v : rgb)
        v = std::isfinite(v) && v > 0.0f ? v : 0.0f;

    // Luminance (Y of the working-space RGB) per texel, and its integral over the sphere:
    // a texel row spans the solid angle (2 pi / W) (cos theta0 - cos theta1). Computed where
    // it is needed (twice), not stored: a double per texel is 1 GiB for a 16k map.
    const Matrix3 m = colors.working_rgb_to_xyz();
    const auto luminance = [&](size_t i) {
        const float* c = &rgb[3 * i];
        return std::max(0.0, double(m[3]) * c[0] + double(m[4]) * c[1] + double(m[5]) * c[2]);
    };
    double y_integral = 0.0;
    for (int y = 0; y < height_; ++y) {
        const double cos0 = std::cos(kPi * y / height_), cos1 = std::cos(kPi * (y + 1) / height_);
        const double texel_solid_angle = 2.0 * kPi / width_ * (cos0 - cos1);
        for (int x = 0; x < width_; ++x)
            y_integral += luminance(static_cast<size_t>(y) * width_ + x) * texel_solid_angle;
    }
    power_ = static_cast<float>(intensity_ * y_integral);

    // Sampling weight per texel: its luminance, floored for texels that are not black.
    const double floor = std::max(kLuminanceFloor * y_integral / (4.0 * kPi),
                                  double(std::numeric_limits<float>::min()));
    std::vector<float> weight(n);
    for (size_t i = 0; i < n; ++i) {
        const bool black = rgb[3 * i] == 0.0f && rgb[3 * i + 1] == 0.0f && rgb[3 * i + 2] == 0.0f;
        weight[i] = black ? 0.0f : static_cast<float>(std::max(luminance(i), floor));
    }

    // Uplift every distinct colour once (a fit costs a few microseconds; hashing a texel far
    // less): flat sky, black ground, clipped highlights and synthetic maps repeat colours.
    // A colour's spectrum is fitted straight into its first texel; the others copy it.
    if (n > std::numeric_limits<uint32_t>::max())
        throw std::runtime_error(fmt::format("environment map '{}': {} x {} texels is too many",
                                             source_name_, width_, height_));
    std::vector<uint32_t> colour_of(n);
    std::vector<uint32_t> first_texel; // of each distinct colour, in scanline order
    {
        std::unordered_map<RgbBits, uint32_t, RgbBitsHash> seen;
        seen.reserve(std::min(n, kMaxCachedColours));
        for (size_t i = 0; i < n; ++i) {
            RgbBits key;
            std::memcpy(key.data(), &rgb[3 * i], sizeof key);
            const auto it = seen.find(key);
            if (it != seen.end()) {
                colour_of[i] = it->second;
                continue;
            }
            colour_of[i] = static_cast<uint32_t>(first_texel.size());
            first_texel.push_back(static_cast<uint32_t>(i));
            if (seen.size() < kMaxCachedColours)
                seen.emplace(key, colour_of[i]);
        }
    }
    texels_.resize(n);
    tbb::parallel_for(size_t(0), first_texel.size(), [&](size_t k) {
        texels_[first_texel[k]] = host.uplift(&rgb[3 * size_t(first_texel[k])], true);
    });
    rgb = {};
    for (size_t i = 0; i < n; ++i)
        texels_[i] = texels_[first_texel[colour_of[i]]];
    colour_of = {};
    first_texel = {};

    // The sampling grid: rows split up to kMinSamplingRows (whole texels per cell), large maps
    // max-downsampled so every cell over a non-black texel keeps a non-zero density.
    const int nu = std::min(width_, kMaxSamplingColumns);
    const int nv = height_ < kMinSamplingRows
                       ? height_ * ((kMinSamplingRows + height_ - 1) / height_)
                       : std::min(height_, kMaxSamplingRows);
    std::vector<float> cells(static_cast<size_t>(nu) * nv);
    tbb::parallel_for(0, nv, [&](int j) {
        // Lat-long to sphere Jacobian (pbrt-v3 §14.2.4): dω = 2π² sin θ du dv; weighting by
        // sin θ makes the (u, v) density follow radiance per solid angle.
        const float sin_theta = static_cast<float>(std::sin(kPi * (j + 0.5) / nv));
        const TexelRange ty = texels_of_cell(j, nv, height_);
        for (int i = 0; i < nu; ++i) {
            const TexelRange tx = texels_of_cell(i, nu, width_);
            float w = 0.0f;
            for (int y = ty.first; y < ty.last; ++y)
                for (int x = tx.first; x < tx.last; ++x)
                    w = std::max(w, weight[static_cast<size_t>(y) * width_ + x]);
            cells[static_cast<size_t>(j) * nu + i] = w * sin_theta;
        }
    });
    distribution_ = Distribution2D(cells, nu, nv);

    // A grey uniform sky is D65 times one number: take it once here, not per path.
    const PatinaRgbSpectrum& s0 = texels_[0];
    constant_grey_ = is_constant() && RgbToSpectrum::is_grey(s0) && s0.illuminant;
    if (constant_grey_)
        constant_grey_scale_ = intensity_ * patina_rgb_spectrum_eval(&s0, 0.0f) *
                               RgbToSpectrum::d65_to_unit_luminance();
}

Imath::V3f EnvironmentLight::sample_uniform_sphere(Imath::V2f u)
{
    // pbrt-v4 SampleUniformSphere, with +y as the polar axis.
    const float z = 1.0f - 2.0f * u.x;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    // cos and sin of φ = 2π u.y by polynomial (patina/shading/fast_trig.h), not libm.
    float cos_phi, sin_phi;
    shading::sincos_turn(u.y, cos_phi, sin_phi);
    return {r * cos_phi, z, r * sin_phi};
}

Imath::V2f EnvironmentLight::direction_to_uv(const Imath::V3f& dir) const
{
    // Undo the rotation about +y (rotate by -rotation_deg), then invert d(u, v).
    const float x = cos_rot_ * dir.x - sin_rot_ * dir.z;
    const float z = sin_rot_ * dir.x + cos_rot_ * dir.z;
    // atan2 forms need no unit length and stay accurate near the poles.
    float phi = std::atan2(-x, z);
    if (phi < 0.0f)
        phi += kTwoPiF;
    const float theta = std::atan2(std::sqrt(x * x + z * z), dir.y);
    return {std::min(phi / kTwoPiF, 1.0f), std::min(theta / kPiF, 1.0f)};
}

Imath::V3f EnvironmentLight::uv_to_direction(float u, float v) const
{
    const float theta = kPiF * v, phi = kTwoPiF * u;
    const float sin_theta = std::sin(theta);
    const float x = -sin_theta * std::sin(phi), z = sin_theta * std::cos(phi);
    // Rotate about +y by rotation_deg: counter-clockwise seen from above.
    return {cos_rot_ * x + sin_rot_ * z, std::cos(theta), -sin_rot_ * x + cos_rot_ * z};
}

const PatinaRgbSpectrum& EnvironmentLight::texel_at(float u, float v) const
{
    const int x = std::clamp(static_cast<int>(u * width_), 0, width_ - 1);
    const int y = std::clamp(static_cast<int>(v * height_), 0, height_ - 1);
    return texels_[static_cast<size_t>(y) * width_ + x];
}

SampledSpectrum EnvironmentLight::radiance_of(const PatinaRgbSpectrum& s,
                                              const PatinaWavelengths& wl) const
{
    // The exact path for greys (a white sky): one sigmoid for all wavelengths.
    if (RgbToSpectrum::is_grey(s)) {
        const float grey = intensity_ * patina_rgb_spectrum_eval(&s, 0.0f);
        if (!s.illuminant)
            return SampledSpectrum(wl.count, grey);
        return SampledSpectrum::from_function(
            wl, [&](float lambda) { return grey * RgbToSpectrum::unit_d65(lambda); });
    }
    return SampledSpectrum::from_function(
        wl, [&](float lambda) { return intensity_ * RgbToSpectrum::eval(s, lambda); });
}

std::optional<LightSample> EnvironmentLight::sample(const Imath::V3f&, Imath::V2f u,
                                                    const PatinaWavelengths& wl) const
{
    if (is_constant()) {
        // A uniform sky: uniform directions over the sphere.
        LightSample ls;
        ls.wi = sample_uniform_sphere(u);
        ls.distance = std::numeric_limits<float>::infinity();
        ls.L = radiance_of(texels_[0], wl);
        ls.pdf = kUniformSpherePdf;
        return ls;
    }
    // Choose (u, v) by the luminance distribution, then map it to a direction.
    const Distribution2D::Sample s = distribution_.sample(u.x, u.y);
    const float sin_theta = std::sin(kPiF * s.v);
    if (!(s.pdf > 0.0f) || !(sin_theta > 0.0f))
        return std::nullopt;
    LightSample ls;
    ls.wi = uv_to_direction(s.u, s.v);
    ls.distance = std::numeric_limits<float>::infinity();
    ls.L = radiance_of(texel_at(s.u, s.v), wl);
    // Solid-angle density (pbrt-v3 §14.2.4): p(ω) = p(u, v) / (2π² sin θ).
    ls.pdf = s.pdf / (2.0f * kPiF * kPiF * sin_theta);
    return ls;
}

float EnvironmentLight::pdf(const Imath::V3f&, const Imath::V3f& wi, const LightHit*) const
{
    const float len = wi.length();
    if (!(len > 0.0f) || !std::isfinite(len))
        return 0.0f;
    if (is_constant())
        return kUniformSpherePdf;
    const Imath::V2f uv = direction_to_uv(wi);
    // sin θ from the direction itself (the rotation about +y leaves it unchanged).
    const float sin_theta = std::sqrt(wi.x * wi.x + wi.z * wi.z) / len;
    if (!(sin_theta > 0.0f))
        return 0.0f;
    // pbrt-v3 §14.2.4: p(ω) = p(u, v) / (2π² sin θ), the same cells sample() draws from.
    return distribution_.pdf(uv.x, uv.y) / (2.0f * kPiF * kPiF * sin_theta);
}

SampledSpectrum EnvironmentLight::escaped_radiance(const Imath::V3f& dir,
                                                   const PatinaWavelengths& wl) const
{
    if (!std::isfinite(dir.x) || !std::isfinite(dir.y) || !std::isfinite(dir.z) ||
        dir.length2() == 0.0f)
        return SampledSpectrum(wl.count, 0.0f);
    if (is_constant())
        return radiance_of(texels_[0], wl);
    const Imath::V2f uv = direction_to_uv(dir);
    return radiance_of(texel_at(uv.x, uv.y), wl);
}

} // namespace patina::render
