// A pinhole look-at camera (issue 3 adds the thin lens).
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
    /// `fov_deg` is the vertical field of view; aspect = width / height.
    Camera(const Imath::V3f& from, const Imath::V3f& to, const Imath::V3f& up, float fov_deg,
           float aspect);

    /// The ray through film position (x, y) in [0,1]^2, (0, 0) = top-left.
    Ray generate(float x, float y) const;

private:
    Imath::V3f origin_{0, 0, 0};
    Imath::V3f forward_{0, 0, -1}, right_{1, 0, 0}, up_{0, 1, 0};
    float tan_half_y_ = 0.4f, tan_half_x_ = 0.4f;
};

}  // namespace patina::render
