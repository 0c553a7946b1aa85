// The fading model as a scientist's tool (docs/fading.md "Depth profiles"): run the layered
// simulation (Kimmel et al. 2013, §4) under a constant irradiance for a number of time
// steps and keep, at chosen times, every colorant's volume fraction per sublayer (how the
// fade moves into the layer: figure 5) and the layer's reflectance.
#pragma once

#include "texgen/fade/fading_simulation.h"
#include "texgen/fade/illuminant.h"

#include <filesystem>
#include <string>
#include <vector>

namespace patina::texgen::fade {

struct ProfileRun {
    double irradiance_w_m2 = 0.0;  ///< in the illuminant's band
    double time_step_s = 0.0;
    int steps = 0;
    int sublayers = 100;
    bool both_sides = false;
    std::vector<double> times_s;   ///< when to keep the state; each a whole number of steps
};

struct ProfileSnapshot {
    double time_s = 0.0;
    std::vector<double> fractions;     ///< [sublayer * colorants + j], top sublayer first
    std::vector<double> reflectance;   ///< per grid wavelength, over the substrate
};

struct DepthProfiles {
    std::vector<std::string> colorants;
    double thickness_m = 0.0;
    int sublayers = 0;
    std::vector<double> wavelength_nm;
    std::vector<ProfileSnapshot> snapshots;  ///< t = 0 first, then `times_s` in order
};

/// Runs the simulation (double precision, Eq. 35 steps). Throws std::runtime_error naming
/// the option for a time step or irradiance that is not > 0, steps < 1, or a time that is
/// negative, past steps × time step, or not a whole number of steps (within 1e-6 of one).
DepthProfiles run_depth_profiles(const FadeMaterial& material, const Illuminant& illuminant,
                                 const WavelengthGrid& grid, const ProfileRun& run);

/// CSV: time_s, sublayer, depth_um (the sublayer's middle), then one fraction column per
/// colorant; a row per snapshot and sublayer.
std::string profiles_csv(const DepthProfiles& p);
/// CSV: wavelength_nm, then one reflectance column per snapshot (named by its time, s).
std::string reflectance_csv(const DepthProfiles& p);
/// A PNG of every colorant that changes: its fraction over depth, one curve per snapshot,
/// relative to its fraction at t = 0 (1 = unfaded). Throws like write_reflectance_plot.
void write_profiles_plot(const std::filesystem::path& path, const DepthProfiles& p,
                         const std::string& title);

}  // namespace patina::texgen::fade
