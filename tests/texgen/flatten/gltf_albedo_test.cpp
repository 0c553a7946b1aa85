// The glTF BRDF's directional albedo tables (gltf_albedo.h) against closed forms.
#include "texgen/flatten/gltf_albedo.h"

#include <gtest/gtest.h>

#include <cmath>

namespace patina::texgen {
namespace {

using shading::kGaussMu;
using shading::kGaussNodes;

TEST(GltfAlbedo, TablesMeetTheirClosedForms)
{
    const GltfAlbedo& m = gltf_albedo_model();
    const int top = kGaussNodes - 1;  // μ = 0.98
    // A smooth mirror with F = 1 reflects everything (E1 -> 1 as r -> 0).
    EXPECT_NEAR(m.e1(0.03f, top), 1.0, 2e-3);
    // Lambert under 1 − Fs(0.04, v·h) near normal view: about 1 − 0.04 − a grazing share.
    EXPECT_GT(m.kd(top), 0.90);
    EXPECT_LT(m.kd(top), 0.96);
    // Burley's diffuse at r = 0 seen head-on: 1 − ½ · 2 ∫ (1 − μ)⁵ μ dμ = 1 − 1/42 (a Beta
    // integral) times (1 − ½ (1 − μv)⁵), μv = 0.98.
    const double fv = std::pow(1.0 - kGaussMu[top], 5.0);
    EXPECT_NEAR(m.kb(0.03f, top), (1.0 - 1.0 / 42.0) * (1.0 - 0.5 * fv), 2e-3);
    // Energy: a white dielectric without coat seen head-on reflects at most everything
    // (Khronos; at grazing the reference model is known to gain energy: its diffuse is
    // reduced by 1 − F(v·h), not by the specular lobe's albedo).
    for (float r : {0.1f, 0.5f, 0.9f}) {
        const GltfAlbedo::Terms t = m.terms(GltfTarget::khronos, r, 0.0f, 0.0f, 0.5f);
        EXPECT_LE(t.Pd[top] + t.Ps[top] + t.Q[top], 1.0f + 1e-3f) << r;
    }
}

}  // namespace
}  // namespace patina::texgen
