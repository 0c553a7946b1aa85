// The quarry (Dorsey et al. 1999 §4.2): fresh stone from solid procedural textures, per
// voxel: minerals, porosity and permeability.
//   - granite: cellular grains (Worley 1996) of quartz, feldspar, biotite mica and
//     hornblende; mica and hornblende carry iron; grain boundaries are micro-cracked (more
//     porous);
//   - marble: calcite with veins from Perlin's turbulence (Perlin 1985: sin(x + a turb(x)));
//     veins hold iron-bearing impurities and are more porous;
//   - sandstone: bedding planes (planes normal to `up` distorted by turbulence) of higher
//     porosity and iron content in a cemented quartz matrix.
// Permeability follows porosity by the Kozeny-Carman relation K = K0 phi^3 / (1 - phi)^2,
// so porous beds carry water faster (the paper: "water penetrates further in sandstone than
// in granite").
#pragma once

#include "texgen/slabs/slab_lattice.h"

#include <Imath/ImathVec.h>

#include <cstdint>
#include <string>
#include <vector>

namespace patina::texgen::stone {

enum class StoneKind { granite, marble, sandstone };

/// "granite", "marble", "sandstone"; throws std::runtime_error listing them otherwise.
StoneKind stone_kind_from_name(const std::string& name);
const char* stone_kind_name(StoneKind kind);

struct QuarryOptions {
    StoneKind kind = StoneKind::sandstone;
    uint64_t seed = 1;
    double feature_size = 0.02;  ///< grain size, vein spacing or bed thickness (m)
    Imath::V3d up{0.0, 1.0, 0.0};
    double kozeny_carman_k0 = 1.0; ///< K0 of K = K0 phi^3 / (1 - phi)^2
};

/// Mineral species carried by the simulation: 0 the soluble binder (calcite, feldspar
/// turning to clay, sandstone cement), 1 iron (oxidises to yellow-brown), 2 salts.
constexpr int kSpecies = 3;
constexpr int kSoluble = 0, kIron = 1, kSalt = 2;

/// The fresh stone at one point.
struct StoneSample {
    float porosity = 0.0f;
    float permeability = 0.0f;
    float mineral[kSpecies] = {0.0f, 0.0f, 0.0f}; ///< volume fractions of the solid
    Imath::V3f colour{0.5f, 0.5f, 0.5f};            ///< linear albedo of the fresh stone
};

class Quarry {
public:
    explicit Quarry(const QuarryOptions& options);
    /// Deterministic in (options, p).
    StoneSample at(const Imath::V3d& p) const;
    const QuarryOptions& options() const { return options_; }

private:
    StoneSample granite(const Imath::V3d& p) const;
    StoneSample marble(const Imath::V3d& p) const;
    StoneSample sandstone(const Imath::V3d& p) const;

    QuarryOptions options_;
    Imath::V3d up_;
    uint64_t noise_seed_;
};

} // namespace patina::texgen::stone
