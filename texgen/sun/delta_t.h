// ΔT = TT − UT, the difference between the uniform time of the ephemerides and the time
// kept by the Earth's rotation, from the date: the polynomials of Espenak & Meeus (2006).
#pragma once

namespace patina::texgen {

/// ΔT in seconds at decimal year `year` (2000.5 is the middle of 2000), by the piecewise
/// polynomials of F. Espenak and J. Meeus, "Five Millennium Canon of Solar Eclipses:
/// -1999 to +3000", NASA/TP-2006-214141, §2.6 (also on NASA's eclipse web site as
/// "Polynomial Expressions for Delta T"). They fit the observed ΔT to about a second from
/// 1900 to 2005 and extrapolate beyond: 2020 reads 71.6 s against the observed 69.4 s. An
/// error of ΔT shifts the sun by 1.1e-5° per second (its mean motion, 0.9856° a day), so a
/// few seconds are far below the SPA's own 0.0003°.
double delta_t_espenak_meeus(double year);

/// The decimal year of Julian day `jd` (UT): 2000.0 at 2000-01-01 00:00.
double decimal_year_of_julian_day(double jd);

}  // namespace patina::texgen
