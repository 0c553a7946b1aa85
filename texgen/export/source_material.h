// A mesh's own material as a glTF material: the source file's base colour and base colour
// texture, on the artist's uvs (TEXCOORD_0). What export writes for a material kept free of
// patina and what unwrap writes for every material, so an artist's look survives both.
#pragma once

#include "core/mesh.h"
#include "texgen/export/gltf_document.h"

#include <Imath/ImathVec.h>

#include <string>

namespace patina::texgen {

/// Adds a material `name` to `doc` (metallic 0) with `colour` as its baseColorFactor and,
/// unless empty, `texture` (a file beside the mesh or an image embedded in it) as its
/// baseColorTexture, an 8-bit PNG of the codes it had. Returns the material's index.
int add_source_material(gltf::Document& doc, const std::string& name, const Imath::V4f& colour,
                        const MaterialTexture& texture);

}  // namespace patina::texgen
