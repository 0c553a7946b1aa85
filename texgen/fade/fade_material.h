// Fading materials (Kimmel et al. 2013, §3.1, §5): a layer of given thickness holding a
// mixture of colorants by volume fraction (Eqs. 12-14) over an opaque substrate of
// reflectance rho*(λ) (Eq. 11). Loaded from TOML files in the shader library
// (shaders/fade/*.toml); the format is described at the top of shaders/fade/paper.toml.
#pragma once

#include "texgen/fade/colorant.h"

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace patina::texgen::fade {

struct FadeMaterial {
    std::string name;
    std::string description;
    double thickness_m = 0.0;
    std::vector<Colorant> colorants;       ///< every colorant, products included
    std::vector<double> initial_fractions; ///< volume fraction per colorant (products: 0)
    TabulatedSpectrum substrate_reflectance = TabulatedSpectrum::constant(0.0);
    std::filesystem::path file;            ///< where it was defined ("" if made in code)

    /// Index of a colorant by name; throws std::runtime_error naming the material if absent.
    size_t colorant_index(const std::string& colorant) const;
    /// Checks the material (thickness > 0, fractions in [0, 1], breakdown products present,
    /// non-negative spectra and rates); throws std::runtime_error naming what is wrong.
    void validate() const;
};

/// A set of fading rates to apply to a material's colorants (Table V's rows).
using RateSet = std::map<std::string, double>;  ///< colorant name -> β (m^3/J) at its reference

/// `material` with the fading rate (β at the colorant's reference wavelength) of each named
/// colorant replaced; throws std::runtime_error for a colorant the material does not hold.
FadeMaterial with_rates(FadeMaterial material, const RateSet& rates);

class FadeLibrary {
public:
    /// Add the colorants, materials and rate sets of one file. A material names colorants
    /// of this or an earlier file. Throws std::runtime_error "file:line: key: problem" for a
    /// TOML syntax error, an unknown or misspelt key, a missing or negative value, knots
    /// not increasing, an unknown colorant or breakdown product, a duplicate name.
    void load(const std::filesystem::path& file);

    const FadeMaterial* find(const std::string& name) const;
    /// As find; throws std::runtime_error listing the known materials if absent.
    const FadeMaterial& material(const std::string& name) const;
    /// `name` with the rates of set `rates` applied to the colorants it holds ("" = none).
    /// Throws std::runtime_error when the set names none of them.
    FadeMaterial material_with_rates(const std::string& name, const std::string& rates) const;
    const Colorant& colorant(const std::string& name) const;
    const RateSet& rate_set(const std::string& name) const;
    std::vector<std::string> material_names() const;

    /// Every *.toml of `fade/` under each directory of $PATINA_SHADER_PATH, then the
    /// shipped `<exe>/../share/patina/shaders/fade/`; sorted by name within a directory.
    static std::vector<std::filesystem::path> default_files();
    /// A library of default_files() (or of `files` when given).
    static FadeLibrary load_files(const std::vector<std::filesystem::path>& files);

private:
    std::map<std::string, Colorant> colorants_;
    std::map<std::string, FadeMaterial> materials_;
    std::map<std::string, RateSet> rate_sets_;
};

}  // namespace patina::texgen::fade
