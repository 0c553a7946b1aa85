// A thin-lens look-at camera (a pinhole when the aperture is 0).
#pragma once

#include <Imath/ImathVec.h>

#include <cmath>

namespace patina::render {

struct Ray {
    Imath::V3f origin;
    Imath::V3f dir;  ///< unit length
};

class Camera {
public:
    Camera() = default;
    /// `fov_deg` is the vertical field of view; aspect = width / height. `aperture_radius`
    /// (scene units) 0 is a pinhole; otherwise points at `focus_distance` along the view
    /// direction are sharp (0 = the distance from `from` to `to`).
    Camera(const Imath::V3f& from, const Imath::V3f& to, const Imath::V3f& up, float fov_deg,
           float aspect, float aperture_radius = 0.0f, float focus_distance = 0.0f);

    /// The ray through film position (x, y) in [0,1]^2, (0, 0) = top-left, through the lens
    /// point chosen by `lens` in [0,1)^2 (ignored by a pinhole).
    Ray generate(float x, float y, Imath::V2f lens = {0.5f, 0.5f}) const;

    void set_aspect(float aspect) { tan_half_x_ = tan_half_y_ * aspect; }

    /// True for a pinhole (aperture 0): generate() ignores `lens`.
    bool is_pinhole() const { return aperture_ <= 0.0f; }
    /// A pinhole's rays through the pixel positions of a width x height film, set up once:
    /// the unnormalised direction through pixel position (px, py) (pixels from the top-left
    /// corner, fractions included) is base + px dx + py dy, generate()'s direction through
    /// (px / width, py / height) up to rounding.
    struct Raster {
        Imath::V3f origin, base, dx, dy;
        Ray ray(float px, float py) const
        {
            const Imath::V3f d = base + px * dx + py * dy;
            return {origin, d * (1.0f / std::sqrt(d.dot(d)))};
        }
    };
    Raster raster(int width, int height) const;

private:
    Imath::V3f origin_{0, 0, 0};
    Imath::V3f forward_{0, 0, -1}, right_{1, 0, 0}, up_{0, 1, 0};
    float tan_half_y_ = 0.4f, tan_half_x_ = 0.4f;
    float aperture_ = 0.0f, focus_ = 1.0f;
};

}  // namespace patina::render
