// The faded pigment layer of a fade stack, as the spectral_km shader holds it: the table of
// the layer's two-flux reflectances and transmittance over (dose row, wavelength), the
// substrate under it, and the dose map that says which row a surface point is at.
//
// A fade stack is a folder written by `patina-texgen fade`: fade.toml, the table
// (fade_table.exr: rows = doses, columns = wavelengths) and the dose map (dose.exr: the
// fractional table row and the dose per texel). Its format is formats/fade_stack/fade_stack.h.
//
// Everything is read in create (host->read_image, host->open_texture); lookups are
// allocation-free.
#pragma once

#include <patina/abi.h>
#include <patina/shading/kubelka_munk.h>

#include <string>
#include <vector>

namespace patina::spectral_km {

/// The Kubelka-Munk description of the layer at one dose and wavelength.
struct LayerState {
    float r_top = 0.0f;     ///< reflectance of the layer alone, lit from above
    float t = 0.0f;         ///< diffuse transmittance of the layer
    float r_bottom = 0.0f;  ///< reflectance of the layer alone, lit from below
};

/// Reflectance of a layer over a substrate of reflectance rho: the sum of the light paths
/// bouncing between the two (Kubelka 1948; Kimmel et al. 2013 Eq. 11 with Eqs. 25-27 for
/// one layer): R = R_top + T² ρ / (1 − R_bottom ρ) (patina/shading/kubelka_munk.h).
inline float composite(const LayerState& layer, float rho)
{
    return shading::km_reflectance_over<float>({layer.r_top, layer.r_bottom, layer.t}, rho);
}

class FadeTable {
public:
    /// Reads fade.toml at `path` and the files it names. Returns an empty string on
    /// success, else what is wrong (naming the file and key).
    std::string load(const PatinaHost* host, const char* path);

    int rows() const { return rows_; }
    int columns() const { return columns_; }
    const std::vector<float>& wavelengths_nm() const { return lambda_nm_; }
    /// Replace the substrate reflectance (one value per column, in [0, 1]).
    void set_substrate(std::vector<float> reflectance) { substrate_ = std::move(reflectance); }
    const std::vector<float>& substrate() const { return substrate_; }
    const PatinaTexture* dose_map() const { return dose_map_; }

    /// The layer at a fractional row (clamped to the table) and wavelength (clamped to the
    /// table's range), bilinear in both; *rho receives the substrate there.
    LayerState at(float row, float lambda_nm, float* rho) const;
    /// R of the layer over its substrate at (row, lambda): composite(at(...), rho).
    float reflectance(float row, float lambda_nm) const;

private:
    int rows_ = 0;
    int columns_ = 0;
    std::vector<float> lambda_nm_;
    bool uniform_ = false;       // wavelengths evenly spaced: O(1) column search
    float lambda0_ = 0.0f, inv_step_ = 0.0f;
    std::vector<float> r_top_, t_, r_bottom_;  // rows x columns, row-major
    std::vector<float> substrate_;             // per column
    const PatinaTexture* dose_map_ = nullptr;
};

}  // namespace patina::spectral_km
