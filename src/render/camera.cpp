#include "render/camera.h"

#include <cmath>
#include <stdexcept>

namespace patina::render {

Camera::Camera(const Imath::V3f& from, const Imath::V3f& to, const Imath::V3f& up,
               float fov_deg, float aspect, float aperture_radius, float focus_distance)
    : origin_(from)
{
    forward_ = to - from;
    if (forward_.length() <= 0.0f)
        throw std::invalid_argument("camera: 'from' and 'to' are the same point");
    const float target_distance = forward_.length();
    forward_.normalize();
    right_ = forward_.cross(up);
    if (right_.length() <= 1e-6f)
        throw std::invalid_argument("camera: 'up' is parallel to the viewing direction");
    right_.normalize();
    up_ = right_.cross(forward_);
    if (!(fov_deg > 0.0f && fov_deg < 180.0f))
        throw std::invalid_argument("camera: fov_deg must lie in (0, 180)");
    if (!(aperture_radius >= 0.0f) || !(focus_distance >= 0.0f))
        throw std::invalid_argument("camera: aperture_radius and focus_distance must be >= 0");
    tan_half_y_ = std::tan(0.5f * fov_deg * static_cast<float>(M_PI) / 180.0f);
    tan_half_x_ = tan_half_y_ * aspect;
    aperture_ = aperture_radius;
    focus_ = focus_distance > 0.0f ? focus_distance : target_distance;
}

Camera::Raster Camera::raster(int width, int height) const
{
    // generate()'s forward + sx right + sy up with sx, sy linear in the pixel position.
    Raster r;
    r.origin = origin_;
    r.base = forward_ - tan_half_x_ * right_ + tan_half_y_ * up_;
    r.dx = (2.0f * tan_half_x_ / static_cast<float>(width)) * right_;
    r.dy = (-2.0f * tan_half_y_ / static_cast<float>(height)) * up_;
    return r;
}

Ray Camera::generate(float x, float y, Imath::V2f lens) const
{
    const float sx = (2.0f * x - 1.0f) * tan_half_x_;
    const float sy = (1.0f - 2.0f * y) * tan_half_y_;
    const Imath::V3f d = forward_ + sx * right_ + sy * up_;
    if (aperture_ <= 0.0f)
        return {origin_, d.normalized()};
    // Thin lens (pbrt-v4 §5.2.3): the ray from a point on the lens disc through the point of
    // the pinhole ray on the plane of focus. Concentric disc mapping keeps strata compact.
    const Imath::V3f focus_point = origin_ + d * focus_;  // d has unit forward component
    float a = 2.0f * lens.x - 1.0f, b = 2.0f * lens.y - 1.0f, r = 0.0f, phi = 0.0f;
    if (a != 0.0f || b != 0.0f) {
        constexpr float kPiOver4 = static_cast<float>(M_PI) / 4.0f;
        if (std::abs(a) > std::abs(b)) {
            r = a;
            phi = kPiOver4 * (b / a);
        } else {
            r = b;
            phi = 2.0f * kPiOver4 - kPiOver4 * (a / b);
        }
    }
    const Imath::V3f lens_point =
        origin_ + aperture_ * r * (std::cos(phi) * right_ + std::sin(phi) * up_);
    return {lens_point, (focus_point - lens_point).normalized()};
}

}  // namespace patina::render
