// A copper-clad tower for the samples (Dorsey & Hanrahan 1996 §5.3, figure 12): a square
// shaft under a pyramid roof, uv-mapped with one island per face so that patterns grown on
// the surface must cross seams.
#pragma once

#include "core/mesh.h"

namespace patina::texgen {

struct TowerOptions {
    float width = 1.0f;         ///< side of the square shaft (m)
    float shaft_height = 2.0f;  ///< m
    float roof_height = 1.6f;   ///< apex above the top of the shaft (m)
    float eave = 0.1f;          ///< how far the roof overhangs the shaft (m)
    int subdivisions = 24;      ///< cells along each side of a face
};

/// A tower standing on y = 0 centred on `base` (x, z): four walls (outward normals, no
/// floor) and a pyramid roof of four faces with a soffit under the overhang. Vertex normals
/// are the flat face normals; uvs put the walls side by side in v in [0.02, 0.47] and the
/// roof faces above them in v in [0.52, 0.98], each face its own island with gaps between.
TriangleMesh make_tower(const Imath::V3f& base, const TowerOptions& options = {});

}  // namespace patina::texgen
