// The shading context handed to plugins at a surface point, and the local frame (+z = the
// shading normal, x along dPdu) in which BSDFs and emitters see directions (abi.h §3).
#pragma once

#include "core/embree_scene.h"

#include <patina/abi.h>

#include <Imath/ImathVec.h>

namespace patina::render {

/// The shading context of a surface point, and the local frame its BSDF works in.
struct ShadingFrame {
    PatinaShadingContext ctx{};
    Imath::V3f s, t, n;  ///< orthonormal; n = shading normal

    Imath::V3f to_local(const Imath::V3f& v) const { return {v.dot(s), v.dot(t), v.dot(n)}; }
    Imath::V3f to_world(const Imath::V3f& v) const { return v.x * s + v.y * t + v.z * n; }
};

ShadingFrame make_shading_frame(const SurfacePoint& p);
/// The same for a point whose (dPdu, dPdv, N) is already orthonormal (what
/// EmbreeScene::interpolate_shading reports): the frame is (dPdu, dPdv, N) as it is, not
/// re-orthogonalised (equal to make_shading_frame's up to rounding).
ShadingFrame make_shading_frame(const SurfacePoint& p, bool orthonormal);

}  // namespace patina::render
