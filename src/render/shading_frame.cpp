#include "render/shading_frame.h"

#include <cmath>

namespace patina::render {

namespace {
    PatinaVec3 to_abi(const Imath::V3f& v) { return {v.x, v.y, v.z}; }
}  // namespace

namespace {
    void fill_context(const SurfacePoint& p, PatinaShadingContext& c)
    {
        c.P = to_abi(p.P);
        c.N = to_abi(p.N);
        c.Ng = to_abi(p.Ng);
        c.dPdu = to_abi(p.dPdu);
        c.dPdv = to_abi(p.dPdv);
        c.uv = {p.uv.x, p.uv.y};
        c.primitive_id = p.prim_id;
        c.mesh_id = p.mesh_id;
        c.mode = PATINA_TRANSPORT_RADIANCE;
    }
}  // namespace

ShadingFrame make_shading_frame(const SurfacePoint& p, bool orthonormal)
{
    if (!orthonormal)
        return make_shading_frame(p);
    ShadingFrame f;
    f.n = p.N;
    f.s = p.dPdu;
    f.t = p.dPdv;
    fill_context(p, f.ctx);
    return f;
}

ShadingFrame make_shading_frame(const SurfacePoint& p)
{
    ShadingFrame f;
    f.n = p.N;
    // Tangent from dPdu, made orthogonal to n; any perpendicular when dPdu is degenerate.
    Imath::V3f s = p.dPdu - f.n * f.n.dot(p.dPdu);
    if (s.length2() < 1e-12f) {
        s = std::abs(f.n.x) > 0.9f ? Imath::V3f(0, 1, 0) : Imath::V3f(1, 0, 0);
        s = s - f.n * f.n.dot(s);
    }
    f.s = s.normalized();
    f.t = f.n.cross(f.s);
    fill_context(p, f.ctx);
    return f;
}

}  // namespace patina::render
