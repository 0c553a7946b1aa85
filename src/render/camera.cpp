#include "render/camera.h"

#include <cmath>
#include <stdexcept>

namespace patina::render {

Camera::Camera(const Imath::V3f& from, const Imath::V3f& to, const Imath::V3f& up,
               float fov_deg, float aspect)
    : origin_(from)
{
    forward_ = to - from;
    if (forward_.length() <= 0.0f)
        throw std::invalid_argument("camera: 'from' and 'to' are the same point");
    forward_.normalize();
    right_ = forward_.cross(up);
    if (right_.length() <= 1e-6f)
        throw std::invalid_argument("camera: 'up' is parallel to the viewing direction");
    right_.normalize();
    up_ = right_.cross(forward_);
    if (!(fov_deg > 0.0f && fov_deg < 180.0f))
        throw std::invalid_argument("camera: fov_deg must lie in (0, 180)");
    tan_half_y_ = std::tan(0.5f * fov_deg * static_cast<float>(M_PI) / 180.0f);
    tan_half_x_ = tan_half_y_ * aspect;
}

Ray Camera::generate(float x, float y) const
{
    const float sx = (2.0f * x - 1.0f) * tan_half_x_;
    const float sy = (1.0f - 2.0f * y) * tan_half_y_;
    Imath::V3f d = forward_ + sx * right_ + sy * up_;
    return {origin_, d.normalized()};
}

}  // namespace patina::render
