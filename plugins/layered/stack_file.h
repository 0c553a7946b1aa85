// What the layered plugin reads from a patina stack.toml (written by `patina-texgen patina`,
// texgen/patina/stack_writer.cpp): the base material, the layers bottom to top with their
// thickness maps, and the resolved optical description of every material the stack uses
// ([patina.materials."<name>"]: K, S, specular per wavelength, roughness, and n, k for a
// metal). Read once in create; nothing here runs during shading.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace patina::layered {

/// One material as stack.toml describes it, on its own wavelength table (nm).
struct MaterialOptics {
    std::string name;
    bool metal = false;
    std::vector<float> lambda_nm;
    std::vector<float> absorption_per_um; ///< KM K (empty for a metal)
    std::vector<float> scattering_per_um; ///< KM S (empty for a metal)
    std::vector<float> specular;          ///< normal-incidence reflectance of its top surface
    std::vector<float> n, k;              ///< complex index n + ik of a metal (else empty)
    float roughness = 0.5f;               ///< perceptual roughness of its top surface
};

struct StackLayer {
    std::string material;
    /// The thickness map (µm); a UDIM map's `<UDIM>` pattern ("thickness.<UDIM>.exr").
    std::filesystem::path map_file;
    /// The map's channel holding this layer's thickness: the layer's `channel` (an index, or
    /// a name listed in the map's `channels`), 0 when not given. Layers sharing one
    /// multi-channel map are read with one texture lookup.
    int channel = 0;
};

struct StackFile {
    std::filesystem::path path;
    std::string base;
    std::vector<StackLayer> layers; ///< bottom to top
    std::map<std::string, MaterialOptics> materials;
};

/// Reads `path`. Throws std::runtime_error naming the file, the line and the key for a TOML
/// syntax error, a missing [patina] table, a layer without a map, a map missing from
/// [maps], a material missing from [patina.materials] or a malformed table in it.
StackFile read_stack_file(const std::filesystem::path& path);

}  // namespace patina::layered
