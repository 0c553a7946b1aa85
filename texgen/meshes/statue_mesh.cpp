#include "texgen/meshes/statue_mesh.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace patina::texgen {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

float smoothstep(float a, float b, float x)
{
    const float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// Radius of the profile at height t in [0, 1], as a fraction of the height: plinth with a
// bevel, a ledge stepping in to the column, the column, shoulders narrowing to a neck, and a
// spherical head (centre 0.85, radius 0.15) closing at the top.
float profile_radius(float t)
{
    if (t < 0.06f)
        return 0.30f;
    if (t < 0.08f)
        return 0.30f - 0.03f * (t - 0.06f) / 0.02f;
    if (t < 0.09f)
        return 0.27f - 0.07f * (t - 0.08f) / 0.01f;
    if (t < 0.62f)
        return 0.20f;
    if (t < 0.70f)
        return 0.20f - 0.135f * smoothstep(0.62f, 0.70f, t);
    if (t < 0.72f)
        return 0.065f + (0.0748f - 0.065f) * (t - 0.70f) / 0.02f;
    const float dy = t - 0.85f;
    return std::sqrt(std::max(0.0f, 0.15f * 0.15f - dy * dy));
}

// How strongly the flutes cut the column at height t: full on the column, fading at its ends.
float flute_weight(float t)
{
    return smoothstep(0.10f, 0.14f, t) * (1.0f - smoothstep(0.57f, 0.61f, t));
}

}  // namespace

TriangleMesh make_statue(const Imath::V3f& base, const StatueOptions& o)
{
    if (!(o.height > 0.0f) || o.rings < 8 || o.segments < 8 || o.flutes < 0 ||
        !(o.flute_depth >= 0.0f && o.flute_depth < 0.5f))
        throw std::runtime_error(fmt::format(
            "make_statue: need height > 0, rings >= 8, segments >= 8, flutes >= 0 and "
            "flute_depth in [0, 0.5) (got {}, {}, {}, {}, {})",
            o.height, o.rings, o.segments, o.flutes, o.flute_depth));
    const int n_rows = o.rings + 1;
    const int n_cols = o.segments + 1;

    // Ring heights: uniform in arc length along the (unfluted) profile, so texels and
    // triangles are spread evenly over the silhouette.
    constexpr int kFine = 4096;
    std::vector<float> arc(kFine + 1, 0.0f);
    for (int i = 1; i <= kFine; ++i) {
        const float t0 = static_cast<float>(i - 1) / kFine, t1 = static_cast<float>(i) / kFine;
        arc[i] = arc[i - 1] + std::hypot(t1 - t0, profile_radius(t1) - profile_radius(t0));
    }
    std::vector<float> ring_t(n_rows);
    for (int r = 0; r < n_rows; ++r) {
        const float s = arc.back() * static_cast<float>(r) / static_cast<float>(o.rings);
        const auto it = std::lower_bound(arc.begin(), arc.end(), s);
        const int i = std::clamp(static_cast<int>(it - arc.begin()), 1, kFine);
        const float f = (s - arc[i - 1]) / std::max(arc[i] - arc[i - 1], 1e-12f);
        ring_t[r] = (static_cast<float>(i - 1) + std::clamp(f, 0.0f, 1.0f)) / kFine;
    }
    ring_t.front() = 0.0f;
    ring_t.back() = 1.0f;

    TriangleMesh m;
    m.name = "statue";
    const auto point = [&](float t, float phi) {
        float r = profile_radius(t);
        if (o.flutes > 0) {
            const float groove = std::pow(0.5f + 0.5f * std::cos(o.flutes * phi), 6.0f);
            r *= 1.0f - o.flute_depth * flute_weight(t) * groove;
        }
        return base + o.height * Imath::V3f(r * std::sin(phi), t, r * std::cos(phi));
    };
    // Surface of revolution: row r at height ring_t[r] (bottom to top), column c at angle phi.
    for (int r = 0; r < n_rows; ++r)
        for (int c = 0; c < n_cols; ++c) {
            const float phi = 2.0f * kPi * static_cast<float>(c % o.segments) / o.segments;
            m.positions.push_back(point(ring_t[r], phi));
            m.uvs.emplace_back(static_cast<float>(c) / o.segments,
                               0.26f + 0.74f * static_cast<float>(r) / o.rings);
        }
    const auto id = [&](int r, int c) { return static_cast<uint32_t>(r * n_cols + c); };
    for (int r = 0; r < o.rings; ++r)
        for (int c = 0; c < o.segments; ++c) {
            // Counter-clockwise in (u, v) with v up and u around towards +x: outward.
            const uint32_t a = id(r, c), b = id(r, c + 1), d = id(r + 1, c), e = id(r + 1, c + 1);
            m.indices.insert(m.indices.end(), {a, b, e});
            if (r + 1 < o.rings)  // the top row collapses onto the apex
                m.indices.insert(m.indices.end(), {a, e, d});
        }
    // Smooth normals over the closed surface: weld the seam column and the apex for the
    // averaging, then give every copy the same normal.
    compute_vertex_normals(m);
    for (int r = 0; r < n_rows; ++r) {
        const Imath::V3f n = (m.normals[id(r, 0)] + m.normals[id(r, o.segments)]).normalized();
        m.normals[id(r, 0)] = m.normals[id(r, o.segments)] = n;
    }
    for (int c = 0; c < n_cols; ++c)
        m.normals[id(o.rings, c)] = Imath::V3f(0.0f, 1.0f, 0.0f);

    // Bottom disc, facing down, in its own uv square.
    const auto centre = static_cast<uint32_t>(m.positions.size());
    m.positions.push_back(base);
    m.normals.emplace_back(0.0f, -1.0f, 0.0f);
    m.uvs.emplace_back(0.125f, 0.125f);
    for (int c = 0; c < o.segments; ++c) {
        const float phi = 2.0f * kPi * static_cast<float>(c) / o.segments;
        m.positions.push_back(point(0.0f, phi));
        m.normals.emplace_back(0.0f, -1.0f, 0.0f);
        m.uvs.emplace_back(0.125f + 0.12f * std::cos(phi), 0.125f + 0.12f * std::sin(phi));
    }
    for (int c = 0; c < o.segments; ++c) {
        const uint32_t a = centre + 1 + c, b = centre + 1 + (c + 1) % o.segments;
        m.indices.insert(m.indices.end(), {centre, b, a});
    }
    return m;
}

}  // namespace patina::texgen
