// A thin-lens look-at camera (a pinhole when the aperture is 0).
#pragma once

#include <Imath/ImathVec.h>

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

private:
    Imath::V3f origin_{0, 0, 0};
    Imath::V3f forward_{0, 0, -1}, right_{1, 0, 0}, up_{0, 1, 0};
    float tan_half_y_ = 0.4f, tan_half_x_ = 0.4f;
    float aperture_ = 0.0f, focus_ = 1.0f;
};

}  // namespace patina::render
