// What a lamp spectrum means for a lighting designer and a conservator: its luminous
// efficacy, how much ultraviolet it brings per lumen, and its damage factor (the damaging
// irradiance per lumen). All are ratios to the illuminance, so a forecast can state its
// lighting in lux and find the radiant irradiance the fading model needs.
#pragma once

#include "texgen/fade/illuminant.h"

namespace patina::texgen::forecast {

/// K_m = 683 lm/W, the maximum luminous efficacy of photopic vision (CIE 15:2018 §7.1; the
/// SI definition of the candela at 540 THz).
inline constexpr double kMaxLuminousEfficacy = 683.0;

/// Krochmann's relative spectral damage responsivity s(λ) = exp(-b (λ - 300 nm)) for
/// 300 nm ≤ λ ≤ 600 nm, b = 0.012 /nm: the action spectrum CIE 157:2004 §3 uses for the
/// damage factor of museum objects in general (it lists b from 0.0115 to 0.0385 /nm for
/// particular materials).
inline constexpr double kDamageSlopePerNm = 0.012;

struct LampPhotometry {
    /// Luminous efficacy of the radiation in the lamp's band: 683 ∫ S V dλ / ∫_band S dλ
    /// (lm/W). Its inverse is the band irradiance per lux.
    double luminous_efficacy_lm_per_w = 0.0;
    /// Ultraviolet (300-400 nm) per lumen, µW/lm: ∫_300^400 S dλ / (683 ∫ S V dλ) × 1e6.
    /// Museum guidelines ask for ≤ 75 µW/lm, UV filters bring it under 10.
    double uv_uw_per_lm = 0.0;
    /// Damage factor (CIE 157:2004 Eq. 2): ∫ S s dλ / (683 ∫ S V dλ) with Krochmann's s(λ),
    /// in W/lm: the damaging irradiance per lux (mW/lm = mW m^-2 per lux).
    double damage_factor_w_per_lm = 0.0;
};

/// The photometry of `lamp` (its relative SPD over its band), integrated at 1 nm with the
/// CIE 1931 2° ȳ as V(λ). Throws std::runtime_error when the lamp emits no light
/// (∫ S V = 0), naming it.
LampPhotometry lamp_photometry(const fade::Illuminant& lamp);

}  // namespace patina::texgen::forecast
