// What the exposure baker traces against, accumulated once over every time step of the
// period so that the cost per surface sample does not grow with the period's length:
//  - sun bins: the sun's direct-normal energy binned by direction (rings of the bin size
//    in zenith, azimuth segments of about the same arc), each with the energy-weighted
//    mean direction;
//  - sky cells: the upper hemisphere cut into n x n cells of equal solid angle (the
//    Shirley-Chiu concentric square-to-disk map lifted to the hemisphere by the Lambert
//    equal-area projection), each holding the time integral of the CIE sky's radiance
//    averaged over the cell, scaled at every step so that the whole sky gives that step's
//    diffuse horizontal irradiance.
#pragma once

#include "texgen/exposure/exposure_period.h"
#include "texgen/sun/cie_sky.h"

#include <Imath/ImathVec.h>

#include <vector>

namespace patina::texgen {

struct SunBin {
    /// Sum over the bin's steps of DNI dt s (J/m^2 times a unit vector): N . weighted is
    /// the bin's direct exposure of an unshadowed surface with normal N facing every
    /// direction in it.
    Imath::V3d weighted;
    double energy = 0;     ///< sum of DNI dt, J/m^2 at normal incidence
    Imath::V3f direction;  ///< unit energy-weighted mean direction (the shadow ray)
};

struct ExposureSky {
    std::vector<SunBin> sun_bins;  ///< non-empty bins, in bin order
    int sky_resolution = 0;        ///< n: n x n sky cells
    /// Per cell (row-major in the square): the time integral of the cell's mean sky
    /// radiance, J/(m^2 sr).
    std::vector<double> sky_radiance_time;
    double cell_solid_angle = 0;  ///< 2 pi / n^2
    double duration_s = 0;        ///< the period's length
    double direct_normal = 0;     ///< sum of DNI dt, J/m^2
    double diffuse_horizontal = 0;  ///< sum of DHI dt, J/m^2
    int non_empty_sky_cells = 0;
    size_t steps = 0;             ///< the period's steps with some irradiance
};

/// The unit direction (+y up) of the point (u, v) in [0, 1]^2 of the equal-area
/// hemisphere map the sky cells tile.
Imath::V3d hemisphere_direction(double u, double v);

struct AccumulationOptions {
    double sun_bin_deg = 0.5;  ///< angular size of a sun bin
    int sky_cells = 256;       ///< about this many sky cells (n = round(sqrt))
    bool progress = false;     ///< progress of the period's steps on stderr
};

/// Accumulate `period` under `sky`, one step at a time as the period computes them (no step
/// is kept: memory does not grow with the period), polling for cancellation. Sky radiance
/// uses 4 x 4 points per cell, and the sky distribution is evaluated once per 2-degree bin
/// of sun directions (a clear sky changes little over 2 degrees of sun motion). Throws on a
/// bin size outside (0, 10] degrees or fewer than 4 sky cells.
ExposureSky accumulate_exposure(const ExposurePeriod& period, const CieSky& sky,
                                const AccumulationOptions& options);

}  // namespace patina::texgen
