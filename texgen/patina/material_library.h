// The layer materials a patina script names (`new copper`, `coat marine patina 3 ...`):
// TOML files in the shader library (shaders/patina/*.toml). Each material is given the way
// Dorsey & Hanrahan 1996 give theirs (§4.1): the colour of an optically thick layer R_inf,
// an assumed backscattering S, and K from K/S = (1 - R_inf)^2 / (2 R_inf); a mixture mixes
// K and S of its components by volume fraction. The file format is described at the top of
// shaders/patina/copper.toml and in docs/patina-script.md.
//
// Every material is also resolved spectrally (what a renderer needs, written into stack.toml
// by stack_writer): K, S and the specular colour on a 360-830 nm grid, R_inf uplifted from its
// colour (core/rgb_spectrum.h, in the OCIO working space) unless the file gives an `r_inf`
// table, and a metal's complex index n + ik from its `n` and `k` tables.
#pragma once

#include "core/color_management.h"

#include <Imath/ImathVec.h>

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace patina::texgen {

/// The wavelength grid of the spectral description: 360-830 nm every 10 nm.
inline constexpr int kSpectralSamples = 48;
inline constexpr float kSpectralStartNm = 360.0f;
inline constexpr float kSpectralStepNm = 10.0f;

/// A material's optics per wavelength of the grid (kSpectralSamples values each).
struct SpectralOptics {
    std::vector<float> lambda_nm;
    std::vector<float> r_infinity;  ///< R_inf of a thick layer (layers only)
    std::vector<float> absorption;  ///< K per µm (0 for metals)
    std::vector<float> scattering;  ///< S per µm (0 for metals)
    std::vector<float> specular;    ///< normal-incidence reflectance of its top surface
    std::vector<float> n, k;        ///< complex index n + ik (metals only)
};

struct PatinaMaterial {
    std::string name;                 ///< canonical name (the TOML key)
    std::vector<std::string> aliases; ///< other names scripts may use ("tarnish 1")
    bool is_metal = false;            ///< a base metal: opaque, reflects `color`
    /// Linear Rec.709: R_inf of a thick layer, or a metal's normal-incidence reflectance.
    Imath::V3f color{0.5f};
    /// KM absorption and backscattering per µm, per linear Rec.709 channel (0 for metals).
    Imath::V3f absorption{0.0f};
    Imath::V3f scattering{0.0f};
    float roughness = 0.5f;
    Imath::V3f specular{0.04f};       ///< linear normal-incidence specular colour
    std::string description;
    std::filesystem::path file;       ///< where it was defined
    SpectralOptics spectral;          ///< the same optics per wavelength
};

class MaterialLibrary {
public:
    MaterialLibrary() = default;

    /// Add every material of a library file. Colours are converted to linear Rec.709 with
    /// `colors` (OCIO) from their `color_space` (default "srgb_texture"). Throws
    /// std::runtime_error naming the file and the key for: a TOML syntax error (with its
    /// line), an unknown key, a colour outside (0, 1], a negative or missing scattering, a
    /// mixture naming an unknown material or fractions not summing to 1 (within 1e-3), a
    /// name already defined (in this or an earlier file), a metal without `n` and `k`
    /// tables, a table whose length differs from `wavelengths_nm` or whose wavelengths do not
    /// increase.
    void load(const std::filesystem::path& file, const ColorManager& colors);

    /// The material a name or alias denotes, or nullptr.
    const PatinaMaterial* find(const std::string& name) const;
    const PatinaMaterial& at(const std::string& name) const;
    /// Every name and alias, for the script parser and its "did you mean" messages.
    std::set<std::string> names() const;
    const std::vector<PatinaMaterial>& materials() const { return materials_; }

    /// The library files found by default: every *.toml of `patina/` under each directory
    /// of $PATINA_SHADER_PATH (colon-separated), then the shipped
    /// `<exe>/../share/patina/shaders/patina/`; sorted by name within a directory.
    static std::vector<std::filesystem::path> default_files();

    /// The default files and then `extra` (the commands' --materials), loaded. Throws when
    /// there is no file at all, naming where they were looked for and the option.
    static MaterialLibrary load_default(const std::vector<std::filesystem::path>& extra,
                                        const ColorManager& colors);

private:
    std::vector<PatinaMaterial> materials_;
    std::map<std::string, size_t> by_name_;
};

}  // namespace patina::texgen
