// The environment light: radiance arriving from infinitely far away, given by a lat-long
// (equirectangular) image, importance-sampled by luminance: pbrt-v3 §14.2.4 "Infinite Area
// Lights" (the lat-long map; pbrt-v4 §12.5.2 switched to an equal-area map, not used here).
//
// Mapping (plain equirectangular; +y is up):
//   - texture coordinates (u, v) in [0, 1]^2 with (0, 0) the top-left corner of the image and
//     v running down the rows (the image convention, not the mesh convention of v up);
//   - theta = pi v is the angle from +y: the top row is the zenith, the bottom row the nadir;
//   - phi = 2 pi u, and the unrotated direction is
//         d(u, v) = (-sin theta sin phi, cos theta, sin theta cos phi),
//     so the centre column (u = 0.5) looks along -z, the direction a default camera looks;
//     u = 0.75 is +x, u = 0.25 is -x, and the left/right seam (u = 0 / 1) lies along +z,
//     behind the default camera. Seen from inside the sphere the image is not mirrored: a
//     viewer looking along -z sees the image's left half on its left.
//   - This is the OpenEXR / USD DomeLight lat-long layout (centre column +z, u = 0.25 +x)
//     turned half a turn about +y: a map authored for that layout renders the same here with
//     rotation_deg = 180.
//   - rotation_deg turns the map about +y, counter-clockwise seen from above (looking down
//     -y; the right-hand rule about +y): with rotation_deg = 90 the centre column looks
//     along -x instead of -z.
//
// Radiance is the *nearest* texel (no bilinear filtering): piecewise-constant radiance over
// the same cells as the piecewise-constant sampling density keeps sampling and MIS exact.
// Magnified maps seen directly by the camera therefore look blocky; use a map at least as
// fine as the view needs.
#pragma once

#include "render/light.h"

#include "core/sampling.h"

#include <patina/abi.h>

#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace patina {
class Host;
struct ImageData;
} // namespace patina

namespace patina::render {

class EnvironmentLight : public Light {
public:
    /// Load a lat-long map from `file` (any OpenImageIO-readable image, typically EXR).
    /// Channels R, G, B are used (by name; else the first three; a one- or two-channel image
    /// is a grey from its first channel); alpha is ignored. `colorspace` is the map's
    /// declared colour space in the host's OCIO config: texels are converted once to the
    /// working space (data spaces such as "raw" are taken as they are), negative values are
    /// clamped to 0, and each texel is uplifted once to an emission spectrum (D65 of
    /// luminance 1 for working-space (1, 1, 1)). Radiance is that spectrum times
    /// `intensity`. Throws std::runtime_error naming the file for a missing or unreadable
    /// file, an unknown colour space, or a NaN/Inf texel (with its (x, y), x from the left,
    /// y from the top row); std::invalid_argument for a negative or non-finite intensity or
    /// a non-finite rotation. `host` is used only during construction.
    EnvironmentLight(const Host& host, const std::filesystem::path& file,
                     std::string_view colorspace, float intensity = 1.0f,
                     float rotation_deg = 0.0f);

    /// A constant environment of working-space colour `working_rgb` (the same code path as a
    /// 1x1 map): radiance = uplift(working_rgb) * intensity in every direction.
    EnvironmentLight(const Host& host, const std::array<float, 3>& working_rgb,
                     float intensity = 1.0f);

    /// A map already in memory (procedural skies, tests); `source_name` stands in for the
    /// file name in messages. Same rules as the file constructor.
    EnvironmentLight(const Host& host, ImageData image, std::string_view colorspace,
                     float intensity, float rotation_deg, std::string source_name);

    std::optional<LightSample> sample(const Imath::V3f& p, Imath::V2f u,
                                      const PatinaWavelengths& wl) const override;
    float pdf(const Imath::V3f& p, const Imath::V3f& wi,
              const LightHit* hit = nullptr) const override;
    bool is_infinite() const override { return true; }
    SampledSpectrum escaped_radiance(const Imath::V3f& dir,
                                     const PatinaWavelengths& wl) const override;
    /// Emitted power through a scene of bounding radius r (pbrt-v4 ImageInfiniteLight::Phi):
    /// π r² × intensity × ∫ Y dω (Y the texels' working-space luminance), comparable with the sun's and the area lights' power.
    float power() const override { return kPi * scene_radius_ * scene_radius_ * power_; }
    void set_scene_radius(float radius) { scene_radius_ = radius; }

    /// The map's (u, v) (see the header comment) seen along world direction `dir` (any
    /// non-zero length), rotation included.
    Imath::V2f direction_to_uv(const Imath::V3f& dir) const;
    /// The unit world direction of map coordinates (u, v), rotation included.
    Imath::V3f uv_to_direction(float u, float v) const;

    /// A 1x1 map: a uniform sky, sampled uniformly over the sphere without the 2D table.
    bool is_constant() const { return width_ == 1 && height_ == 1; }
    /// The radiance of a constant map (is_constant()) at wl, the same in every direction:
    /// what sample() and escaped_radiance() return for it, so that an integrator can
    /// evaluate it once per path instead of once per query.
    SampledSpectrum constant_radiance(const PatinaWavelengths& wl) const
    {
        return radiance_of(texels_[0], wl);
    }
    /// The same, given D65 (core/spectrum.h d65) at wl, as cie_at_wavelengths looks it up
    /// for the film: a grey sky then needs no table look-up of its own.
    /// Inline: the integrator asks once per path.
    SampledSpectrum constant_radiance(const PatinaWavelengths& wl,
                                      const SampledSpectrum& d65_at_wl) const
    {
        if (!constant_grey_)
            return radiance_of(texels_[0], wl);
        // radiance_of's grey emission: grey * d65 * (1 / Y of D65), with d65 given.
        return d65_at_wl * constant_grey_scale_;
    }
    /// The direction sample() draws for a constant map from `u`: uniform over the sphere
    /// (pbrt-v4 SampleUniformSphere), with the density kUniformSpherePdf.
    static Imath::V3f sample_uniform_sphere(Imath::V2f u);
    static constexpr float kUniformSpherePdf = 1.0f / (4.0f * 3.14159265358979f);
    int width() const { return width_; }
    int height() const { return height_; }
    float intensity() const { return intensity_; }
    float rotation_deg() const { return rotation_deg_; }
    /// The file name (or the source name) used in messages.
    const std::string& source_name() const { return source_name_; }

private:
    /// Throws for a bad intensity, rotation or colour space (before any file is read).
    void check_arguments(const Host& host, std::string_view colorspace) const;
    /// Takes the image's pixels over (packs R, G, B in place): no full-size copy.
    void build(const Host& host, ImageData image, std::string_view colorspace);
    /// The uplifted spectrum of the texel containing (u, v).
    const PatinaRgbSpectrum& texel_at(float u, float v) const;
    SampledSpectrum radiance_of(const PatinaRgbSpectrum& s, const PatinaWavelengths& wl) const;

    std::string source_name_;
    int width_ = 0, height_ = 0;
    float intensity_ = 1.0f;
    float rotation_deg_ = 0.0f;
    float cos_rot_ = 1.0f, sin_rot_ = 0.0f;
    float power_ = 0.0f;  ///< intensity × ∫ Y dω
    float scene_radius_ = 1.0f;
    static constexpr float kPi = 3.14159265358979f;
    std::vector<PatinaRgbSpectrum> texels_; ///< row-major, row 0 = the top (zenith) row
    Distribution2D distribution_;           ///< over (u, v), density ∝ luminance * sin theta
    /// A constant grey map: its radiance is D65 at the wavelengths times this scale.
    bool constant_grey_ = false;
    float constant_grey_scale_ = 0.0f;
};

} // namespace patina::render
