# patina-texgen sun: the NREL SPA report's example on the command line (Reda & Andreas 2004,
# Table A5.2: zenith 50.11162, azimuth 194.34024, incidence 25.18700), one "name: value
# unit" line per quantity; bad dates and missing options give one error line.
include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")


set(site --latitude 39.742476 --longitude -105.1786 --elevation 1830.14 --pressure 820
    --temperature 11 --delta-t 67 --timezone -7)
expect_success("${PATINA_TEXGEN}" sun --date 2003-10-17 --time 12:30:30 ${site}
               --slope 30 --surface-azimuth -10)
expect_in("${LAST_STDOUT}" "zenith: 50.11162 deg\n")
expect_in("${LAST_STDOUT}" "azimuth: 194.34024 deg\n")
expect_in("${LAST_STDOUT}" "incidence: 25.18700 deg\n")
expect_in("${LAST_STDOUT}" "declination: -9.31434 deg\n")
expect_in("${LAST_STDOUT}" "julian_day: 2452930.312847 d\n")
foreach(name elevation hour_angle extraterrestrial_normal_irradiance clear_sky_dni
        clear_sky_dhi clear_sky_ghi)
  expect_in("${LAST_STDOUT}" "${name}: ")
endforeach()

# The time may come with the date.
expect_success("${PATINA_TEXGEN}" sun --date 2003-10-17T12:30:30 ${site})
expect_in("${LAST_STDOUT}" "zenith: 50.11162 deg\n")

# At night the clear sky is dark.
expect_success("${PATINA_TEXGEN}" sun --date 2003-10-17 --time 23:00 ${site})
expect_in("${LAST_STDOUT}" "clear_sky_ghi: 0.00 W/m^2\n")

expect_failure("--date" "${PATINA_TEXGEN}" sun --date 2003-13-17 ${site})
expect_failure("--time" "${PATINA_TEXGEN}" sun --date 2003-10-17 --time 25:00 ${site})
expect_failure("already holds a time"
  "${PATINA_TEXGEN}" sun --date 2003-10-17T10:00 --time 11:00 ${site})

# Without --delta-t, ΔT comes from the date (Espenak & Meeus 2006: 64.5 s in October 2003)
# and the report's example still reads the published angles to 0.001 deg.
list(REMOVE_ITEM site --delta-t 67)
expect_success("${PATINA_TEXGEN}" sun --date 2003-10-17 --time 12:30:30 ${site})
expect_in("${LAST_STDOUT}" "delta_t: 64.5")
expect_in("${LAST_STDOUT}" "zenith: 50.111")
expect_in("${LAST_STDOUT}" "azimuth: 194.340")
