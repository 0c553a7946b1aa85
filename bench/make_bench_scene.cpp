// Writes the scene of bench/render_vs_embree.sh: a lumpy "statue" (a displaced UV sphere of
// about 69k triangles, the size of the Stanford bunny) standing on a ground plane, as one
// OBJ file with smooth vertex normals and a diffuse MTL material (Kd 0.8, no specular, no
// transmission) that both patina-render (through Assimp) and Embree's tutorial path tracer
// (its own OBJ loader) read.
//
//   bench_make_bench_scene OUT.obj [RINGS SEGMENTS]
//
// writes OUT.obj and OUT.mtl beside it and prints the triangle count on stdout. Deterministic:
// the displacement is a fixed set of bumps plus hashed value noise, no random state.
#include "core/mesh.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <map>
#include <string>
#include <tuple>

namespace {

using Imath::V3f;

// Hashed value noise on the integer lattice, smoothly interpolated, in [-1, 1].
float lattice(int x, int y, int z)
{
    uint32_t h = static_cast<uint32_t>(x) * 73856093u ^ static_cast<uint32_t>(y) * 19349663u ^
                 static_cast<uint32_t>(z) * 83492791u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return static_cast<float>(h & 0xffffu) / 32767.5f - 1.0f;
}

float value_noise(const V3f& p)
{
    const float fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
    const int x = static_cast<int>(fx), y = static_cast<int>(fy), z = static_cast<int>(fz);
    const auto smooth = [](float t) { return t * t * (3.0f - 2.0f * t); };
    const float tx = smooth(p.x - fx), ty = smooth(p.y - fy), tz = smooth(p.z - fz);
    const auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
    const float c00 = lerp(lattice(x, y, z), lattice(x + 1, y, z), tx);
    const float c10 = lerp(lattice(x, y + 1, z), lattice(x + 1, y + 1, z), tx);
    const float c01 = lerp(lattice(x, y, z + 1), lattice(x + 1, y, z + 1), tx);
    const float c11 = lerp(lattice(x, y + 1, z + 1), lattice(x + 1, y + 1, z + 1), tx);
    return lerp(lerp(c00, c10, ty), lerp(c01, c11, ty), tz);
}

// Four octaves of value noise (fractional Brownian motion), roughly in [-1, 1].
float fbm(V3f p)
{
    float sum = 0.0f, amplitude = 0.5f;
    for (int octave = 0; octave < 4; ++octave) {
        sum += amplitude * value_noise(p);
        p *= 2.03f;
        amplitude *= 0.5f;
    }
    return sum;
}

// Radius of the statue along unit direction d: a head and two "ears" on top, a haunch at
// the back, a flattened base, and small-scale noise so no two triangles shade alike.
float statue_radius(const V3f& d)
{
    struct Bump {
        V3f dir;
        float height, width;
    };
    static const Bump kBumps[] = {
        {V3f(0.35f, 0.85f, 0.40f).normalized(), 0.90f, 0.020f},  // ear
        {V3f(-0.30f, 0.88f, 0.35f).normalized(), 0.80f, 0.018f}, // ear
        {V3f(0.0f, 0.45f, 0.90f).normalized(), 0.30f, 0.120f},   // head
        {V3f(0.0f, 0.10f, -1.0f).normalized(), 0.25f, 0.200f},   // haunch
        {V3f(0.9f, -0.2f, 0.3f).normalized(), 0.15f, 0.080f},    // paw
        {V3f(-0.9f, -0.2f, 0.3f).normalized(), 0.15f, 0.080f},   // paw
    };
    float r = 1.0f;
    for (const Bump& b : kBumps)
        r += b.height * std::exp(-(1.0f - d.dot(b.dir)) / b.width);
    // Flatten the bottom so it sits on the ground.
    if (d.y < -0.6f)
        r *= 0.6f / -d.y * 0.95f + 0.05f;
    return r + 0.10f * fbm(d * 5.0f + V3f(11.3f, 3.7f, 5.1f));
}

patina::TriangleMesh make_statue(int rings, int segments)
{
    const patina::TriangleMesh sphere = patina::make_uv_sphere(V3f(0, 0, 0), 1.0f, rings, segments);

    // Weld the seam and the pole copies (same point up to rounding), so the vertex normals
    // come out smooth across them.
    patina::TriangleMesh m;
    m.name = "statue";
    m.material_name = "diffuse";
    std::map<std::tuple<long, long, long>, uint32_t> index_of;
    std::vector<uint32_t> remap(sphere.positions.size());
    for (size_t i = 0; i < sphere.positions.size(); ++i) {
        const V3f& p = sphere.positions[i];
        const auto key = std::make_tuple(std::lround(p.x * 1e5f), std::lround(p.y * 1e5f),
                                         std::lround(p.z * 1e5f));
        const auto [it, added] =
            index_of.try_emplace(key, static_cast<uint32_t>(m.positions.size()));
        if (added) {
            const V3f d = p.normalized();
            // Displace, then stretch upwards a little; the base rests at about y = 0.
            V3f q = d * statue_radius(d);
            q.y = q.y * 1.15f + 0.62f;
            m.positions.push_back(q);
        }
        remap[i] = it->second;
    }
    for (uint32_t idx : sphere.indices)
        m.indices.push_back(remap[idx]);
    patina::compute_vertex_normals(m);
    return m;
}

void write_obj(const std::filesystem::path& obj, const patina::TriangleMesh& statue,
               const patina::TriangleMesh& ground)
{
    const std::filesystem::path mtl = std::filesystem::path(obj).replace_extension(".mtl");
    {
        std::FILE* f = std::fopen(mtl.c_str(), "w");
        if (!f)
            throw std::runtime_error(fmt::format("cannot write '{}'", mtl.string()));
        // Diffuse only: no specular lobe, fully opaque (no transmission in Embree's OBJ model).
        std::fputs("newmtl diffuse\nKa 0 0 0\nKd 0.8 0.8 0.8\nKs 0 0 0\nNs 1\nd 1\nillum 1\n", f);
        std::fclose(f);
    }
    std::FILE* f = std::fopen(obj.c_str(), "w");
    if (!f)
        throw std::runtime_error(fmt::format("cannot write '{}'", obj.string()));
    std::fprintf(f, "# bench/make_bench_scene.cpp: statue on a ground plane\nmtllib %s\n",
                 mtl.filename().c_str());
    uint32_t base = 1; // OBJ indices are 1-based and global across objects
    for (const patina::TriangleMesh* m : {&statue, &ground}) {
        std::fprintf(f, "o %s\nusemtl diffuse\n", m->name.c_str());
        for (const V3f& p : m->positions)
            std::fprintf(f, "v %.6f %.6f %.6f\n", p.x, p.y, p.z);
        for (const V3f& n : m->normals)
            std::fprintf(f, "vn %.6f %.6f %.6f\n", n.x, n.y, n.z);
        for (size_t t = 0; t < m->triangle_count(); ++t) {
            const uint32_t a = m->indices[3 * t] + base, b = m->indices[3 * t + 1] + base,
                           c = m->indices[3 * t + 2] + base;
            std::fprintf(f, "f %u//%u %u//%u %u//%u\n", a, a, b, b, c, c);
        }
        base += static_cast<uint32_t>(m->positions.size());
    }
    if (std::fclose(f) != 0)
        throw std::runtime_error(fmt::format("error writing '{}'", obj.string()));
}

} // namespace

int main(int argc, char** argv)
{
    if (argc != 2 && argc != 4) {
        std::fprintf(stderr,
                     "usage: %s OUT.obj [RINGS SEGMENTS]   (default 150 232: 69138 triangles)\n",
                     argv[0]);
        return 2;
    }
    try {
        const int rings = argc == 4 ? std::stoi(argv[2]) : 150;
        const int segments = argc == 4 ? std::stoi(argv[3]) : 232;
        const patina::TriangleMesh statue = make_statue(rings, segments);
        // A 40 x 40 ground plane at y = 0 (two triangles), normals up.
        patina::TriangleMesh ground = patina::make_plane(V3f(0, 0, 0), 40.0f, 1);
        ground.name = "ground";
        if (!ground.has_normals())
            ground.normals.assign(ground.positions.size(), V3f(0, 1, 0));
        write_obj(argv[1], statue, ground);
        std::printf("%zu\n", statue.triangle_count() + ground.triangle_count());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make_bench_scene: error: %s\n", e.what());
        return 1;
    }
}
