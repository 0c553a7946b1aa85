#include "texgen/stone/quarry.h"

#include "core/sampling.h"
#include "texgen/growth/solid_noise.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::texgen::stone {

using Imath::V3d;

StoneKind stone_kind_from_name(const std::string& name)
{
    if (name == "granite")
        return StoneKind::granite;
    if (name == "marble")
        return StoneKind::marble;
    if (name == "sandstone")
        return StoneKind::sandstone;
    throw std::runtime_error(
        fmt::format("unknown stone '{}': use granite, marble or sandstone", name));
}

const char* stone_kind_name(StoneKind kind)
{
    switch (kind) {
    case StoneKind::granite: return "granite";
    case StoneKind::marble: return "marble";
    default: return "sandstone";
    }
}

namespace {

    double kozeny_carman(double k0, double phi)
    {
        return k0 * phi * phi * phi / ((1.0 - phi) * (1.0 - phi));
    }

    double unit_hash(uint64_t a, uint64_t b, uint64_t c, uint64_t d)
    {
        return double(hash_values(a, b, c, d) >> 11) * 0x1p-53;
    }

    // One SolidNoise per thread would be cheap too, but the noise is immutable: share it.
    const SolidNoise& noise_for(uint64_t seed)
    {
        thread_local uint64_t cached_seed = ~uint64_t(0);
        thread_local std::unique_ptr<SolidNoise> noise;
        if (!noise || cached_seed != seed) {
            noise = std::make_unique<SolidNoise>(seed);
            cached_seed = seed;
        }
        return *noise;
    }

} // namespace

Quarry::Quarry(const QuarryOptions& options) : options_(options)
{
    if (!(options.feature_size > 0.0))
        throw std::runtime_error(fmt::format("quarry: feature size must be > 0 (got {} m)",
                                             options.feature_size));
    up_ = options.up.length() > 0 ? options.up.normalized() : V3d(0, 1, 0);
    noise_seed_ = hash_values(options.seed, 0x5707e);
}

StoneSample Quarry::at(const V3d& p) const
{
    switch (options_.kind) {
    case StoneKind::granite: return granite(p);
    case StoneKind::marble: return marble(p);
    default: return sandstone(p);
    }
}

StoneSample Quarry::granite(const V3d& world) const
{
    // Worley cellular texture: the nearest and second-nearest jittered feature points of the
    // integer cells around p; the nearest one's hash picks the grain's mineral.
    const V3d p = world / options_.feature_size;
    const int cx = int(std::floor(p.x)), cy = int(std::floor(p.y)), cz = int(std::floor(p.z));
    double f1 = 1e30, f2 = 1e30;
    uint64_t nearest = 0;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const uint64_t x = uint64_t(int64_t(cx + dx)), y = uint64_t(int64_t(cy + dy)),
                               z = uint64_t(int64_t(cz + dz));
                const V3d q(cx + dx + unit_hash(options_.seed, x, y, z * 3 + 0),
                            cy + dy + unit_hash(options_.seed, x, y, z * 3 + 1),
                            cz + dz + unit_hash(options_.seed, x, y, z * 3 + 2));
                const double d = (q - p).length2();
                if (d < f1) {
                    f2 = f1;
                    f1 = d;
                    nearest = hash_values(options_.seed, x, y, z);
                } else if (d < f2) {
                    f2 = d;
                }
            }
    const double pick = double(nearest >> 11) * 0x1p-53;
    const double boundary = std::sqrt(f2) - std::sqrt(f1); // 0 on a grain boundary
    StoneSample s;
    // Red granite: 35% quartz, 45% feldspar, 12% biotite, 8% hornblende.
    if (pick < 0.35) {        // quartz: inert, clear grey
        s.porosity = 0.005f;
        s.colour = {0.42f, 0.41f, 0.40f};
    } else if (pick < 0.80) { // feldspar: weathers to clay, pink
        s.porosity = 0.012f;
        s.mineral[kSoluble] = 0.6f;
        s.colour = {0.55f, 0.30f, 0.24f};
    } else if (pick < 0.92) { // biotite mica: iron-bearing, black
        s.porosity = 0.02f;
        s.mineral[kSoluble] = 0.2f;
        s.mineral[kIron] = 0.25f;
        s.colour = {0.05f, 0.045f, 0.04f};
    } else {                  // hornblende: iron-bearing, dark green-black
        s.porosity = 0.01f;
        s.mineral[kIron] = 0.15f;
        s.colour = {0.07f, 0.08f, 0.06f};
    }
    if (boundary < 0.08) // micro-cracks between grains
        s.porosity += 0.02f;
    s.mineral[kSalt] = 0.002f;
    s.permeability = float(kozeny_carman(options_.kozeny_carman_k0, s.porosity));
    return s;
}

StoneSample Quarry::marble(const V3d& world) const
{
    const SolidNoise& noise = noise_for(noise_seed_);
    const V3d p = world / options_.feature_size;
    const double turb = noise.turbulence(p.x * 0.5, p.y * 0.5, p.z * 0.5, 5);
    // Veins: sin(x + a turbulence) near zero (Perlin 1985's marble).
    const double vein = std::abs(std::sin((p.x + p.y * 0.3) * 0.5 * M_PI + 6.0 * turb));
    const double in_vein = std::clamp((0.25 - vein) / 0.25, 0.0, 1.0);
    StoneSample s;
    s.porosity = float(0.01 + 0.03 * in_vein);
    s.mineral[kSoluble] = float(0.95 - 0.25 * in_vein);
    s.mineral[kIron] = float(0.004 + 0.03 * in_vein);
    s.mineral[kSalt] = 0.002f;
    const float grey = float(0.80 - 0.45 * in_vein);
    s.colour = {grey, grey * 0.99f, grey * 0.96f};
    s.permeability = float(kozeny_carman(options_.kozeny_carman_k0, s.porosity));
    return s;
}

StoneSample Quarry::sandstone(const V3d& world) const
{
    const SolidNoise& noise = noise_for(noise_seed_);
    const V3d p = world / options_.feature_size;
    // Bedding planes: the height along `up`, distorted by turbulence, in beds of one
    // feature size; the planes are the top part of each bed, full over 0.14 of the bed and
    // fading out over 0.08 more on each side (a plateau, not a peak: thin peaks alias into
    // dashes on a voxel grid of a few voxels per bed).
    const double turb = noise.turbulence(p.x * 0.25, p.y * 0.25, p.z * 0.25, 4);
    const double h = p.dot(up_) + 1.5 * turb;
    const double phase = h - std::floor(h);
    const double edge = std::clamp((0.15 - std::abs(phase - 0.8)) / 0.08, 0.0, 1.0);
    const double plane = edge * edge * (3.0 - 2.0 * edge);
    StoneSample s;
    s.porosity = float(0.12 + 0.16 * plane);
    s.mineral[kSoluble] = float(0.20 + 0.05 * plane); // carbonate and clay cement
    s.mineral[kIron] = float(0.01 + 0.05 * plane);
    s.mineral[kSalt] = 0.004f;
    s.colour = Imath::V3f(float(0.62 - 0.15 * plane), float(0.50 - 0.16 * plane),
                          float(0.36 - 0.14 * plane));
    s.permeability = float(kozeny_carman(options_.kozeny_carman_k0, s.porosity));
    return s;
}

} // namespace patina::texgen::stone
