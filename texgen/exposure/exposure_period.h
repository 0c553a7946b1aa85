// The period an exposure map integrates over, as a sequence of time steps, each with the
// sun's direction and the direct-normal and diffuse-horizontal irradiance during the step:
// from the clear-sky model at a site (NREL SPA + Ineichen-Perez) or from the rows of an
// EnergyPlus weather file. A clear-sky period computes its steps as they are consumed, so
// that neither memory nor anything but the consumer's time grows with its length.
#pragma once

#include "core/image_io.h"
#include "texgen/sun/clear_sky.h"
#include "texgen/sun/date_time.h"
#include "texgen/sun/epw.h"
#include "texgen/sun/solar_position.h"

#include <Imath/ImathVec.h>

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

namespace patina::texgen {

struct IrradianceStep {
    double jd_ut = 0;       ///< middle of the step (UT Julian day)
    double duration_s = 0;  ///< length of the step
    Imath::V3d sun;         ///< unit direction towards the sun (world: +y up, north -z)
    double dni = 0;         ///< direct normal irradiance, W/m^2 (0 with the sun down)
    double dhi = 0;         ///< diffuse horizontal irradiance, W/m^2
};

/// Receives the steps of a period, one at a time, in time order.
using StepSink = std::function<void(const IrradianceStep&)>;

struct ExposurePeriod {
    /// Hands the steps to the sink, in time order; a step may have no irradiance at all.
    std::function<void(const StepSink&)> for_each_step;
    size_t step_bound = 0;   ///< steps for_each_step visits (for progress)
    double duration_s = 0;   ///< the whole period (for average irradiance)
    /// EPW direct-normal energy (J/m^2) of intervals during which the sun never rose above
    /// the horizon at any sub-step (sunrise/sunset rows), which no direction can carry.
    double dropped_direct = 0;
    Metadata parameters;  ///< site, period, model: for the map header
};

/// Standard-atmosphere pressure at `elevation_m` (ICAO: 1013.25 (1 - 2.25577e-5 h)^5.25588),
/// mbar; SPA's refraction uses it when no measured pressure is given.
double standard_pressure_mbar(double elevation_m);

struct ClearSkyPeriodOptions {
    SolarSite site;
    double timezone_hours = 0;  ///< of `start` and `end`
    DateTime start, end;
    double step_minutes = 10;
    ClearSkyParameters clear_sky;  ///< its elevation_m is taken from `site`
};

/// Largest number of steps of a clear-sky period: 10^8 (1900 years at the default
/// 10-minute step, 190 years at 1 minute); each step is one evaluation of the SPA.
inline constexpr double kMaxPeriodSteps = 1e8;

/// Midpoint steps of `step_minutes` (the last one shortened to end at `end`) with the
/// sun from the SPA and the irradiance from ineichen_perez(), computed as for_each_step
/// visits them. Throws if end <= start, the step is not positive, or the period has more
/// than kMaxPeriodSteps steps (naming --step-minutes and the limit).
ExposurePeriod clear_sky_period(const ClearSkyPeriodOptions& options);

struct EpwPeriodOptions {
    /// Rows whose interval lies within [start, end) by month, day and time of day (the
    /// year is ignored: typical-year files mix years); start > end wraps over New Year.
    std::optional<DateTime> start, end;
    /// Sub-steps per row: each row's interval is split into steps of about this length
    /// so the sun's direction follows its path through the hour.
    double step_minutes = 10;
    std::optional<double> delta_t_s;  ///< TT − UT, s; unset: from the date (sun/delta_t.h)
};

/// The rows of `file` in range, each split into sub-steps: the row's diffuse energy evenly
/// over its sub-steps, its direct-normal energy evenly over the sub-steps with the sun
/// above the horizon (so the row's energies are kept exactly). The site, time zone and
/// elevation come from the LOCATION line; refraction uses each row's pressure and dry bulb
/// temperature when present. Throws "file:line: ..." for a missing irradiation value in
/// range, and if no row is in range.
ExposurePeriod epw_period(const EpwFile& file, const EpwPeriodOptions& options);

}  // namespace patina::texgen
