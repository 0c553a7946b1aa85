// The renderer's shortcuts agree with the general code: the shading frame taken as it is
// from an orthonormal (dPdu, dPdv, N), and pinhole rays from per-frame raster terms.
#include "render/camera.h"
#include "render/shading_frame.h"

#include "core/embree_scene.h"
#include "core/mesh.h"

#include <gtest/gtest.h>

#include <cmath>

namespace patina::render {
namespace {

    TEST(ShadingFrameTest, OrthonormalFrameAsItIsMatchesTheGeneralFrame)
    {
        TriangleMesh sphere = make_uv_sphere(Imath::V3f(0), 1.0f, 24, 48);
        sphere.uvs.clear();  // no uvs: the frame about N is orthonormal already
        EmbreeScene scene;
        scene.add_mesh(sphere);
        scene.commit();
        int hits = 0;
        for (int i = 0; i < 200; ++i) {
            const float a = 0.031f * static_cast<float>(i), b = 0.017f * static_cast<float>(i);
            const Imath::V3f o(4.0f * std::cos(a) * std::cos(b), 4.0f * std::sin(b),
                               4.0f * std::sin(a) * std::cos(b));
            const Imath::V3f d = (Imath::V3f(0.1f, -0.2f, 0.05f) - o).normalized();
            const auto hit = scene.intersect(o, d);
            ASSERT_TRUE(hit);
            ++hits;
            SurfacePoint sp;
            ASSERT_TRUE(scene.interpolate_shading(*hit, d, sp));
            const ShadingFrame general = make_shading_frame(sp);
            const ShadingFrame lean = make_shading_frame(sp, true);
            EXPECT_EQ(lean.n, general.n);
            EXPECT_NEAR((lean.s - general.s).length(), 0.0f, 1e-6f);
            EXPECT_NEAR((lean.t - general.t).length(), 0.0f, 1e-6f);
            EXPECT_EQ(lean.ctx.P.x, general.ctx.P.x);
            EXPECT_EQ(lean.ctx.N.z, general.ctx.N.z);
            EXPECT_EQ(lean.ctx.dPdu.y, general.ctx.dPdu.y);
            EXPECT_EQ(lean.ctx.uv.x, general.ctx.uv.x);
            EXPECT_EQ(lean.ctx.primitive_id, general.ctx.primitive_id);
            EXPECT_EQ(lean.ctx.mode, general.ctx.mode);
            // Not orthonormal: the general frame is used.
            const ShadingFrame fallback = make_shading_frame(sp, false);
            EXPECT_EQ(fallback.s, general.s);
        }
        EXPECT_EQ(hits, 200);
    }

    TEST(ShadingFrameTest, PinholeRasterRaysMatchGenerate)
    {
        const Camera camera({0.0f, 2.4f, 8.0f}, {0.0f, 0.9f, 0.0f}, {0.0f, 1.0f, 0.0f}, 30.0f,
                            640.0f / 480.0f);
        ASSERT_TRUE(camera.is_pinhole());
        const Camera::Raster raster = camera.raster(640, 480);
        for (float py : {0.0f, 0.5f, 123.25f, 479.9f})
            for (float px : {0.0f, 17.5f, 320.0f, 639.99f}) {
                const Ray a = camera.generate(px / 640.0f, py / 480.0f);
                const Ray b = raster.ray(px, py);
                EXPECT_EQ(a.origin, b.origin);
                EXPECT_NEAR((a.dir - b.dir).length(), 0.0f, 1e-6f) << px << " " << py;
                EXPECT_NEAR(b.dir.length(), 1.0f, 1e-6f);
            }
        EXPECT_FALSE(Camera({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 40.0f, 1.0f, 0.1f).is_pinhole());
    }

}  // namespace
}  // namespace patina::render
