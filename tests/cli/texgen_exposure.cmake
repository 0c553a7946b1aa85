# patina-texgen exposure: a clear-sky bake and an EPW bake of a small plane write the map and
# its stack.toml entry (units, illuminant and its spectrum); a broken EPW row is reported
# with its file and line; the site options and --epw exclude each other.
include("${CMAKE_CURRENT_LIST_DIR}/lib/expect.cmake")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")


write_unit_square_obj("${WORK_DIR}/square.obj")

set(site --latitude 39.742476 --longitude -105.1786 --elevation 1830 --timezone -7)
expect_success("${PATINA_TEXGEN}" exposure --mesh "${WORK_DIR}/square.obj"
  --out "${WORK_DIR}/clear" --resolution 16 --quiet ${site}
  --start 2003-06-21 --end 2003-06-22 --components --sky-samples 64)
if(NOT EXISTS "${WORK_DIR}/clear/exposure.exr")
  message(FATAL_ERROR "no exposure.exr written")
endif()
file(READ "${WORK_DIR}/clear/stack.toml" stack)
expect_in("${stack}" "coverage = 'coverage.A'")
expect_in("${stack}" "[maps.exposure]")
expect_in("${stack}" "units = 'J/m^2'")
expect_in("${stack}" "'exposure', 'direct', 'sky'")
expect_in("${stack}" "illuminant = 'D65'")
expect_in("${stack}" "illuminant_spectrum = '360:46.6383 ")
expect_in("${stack}" "sky = 'CIE S 011 type 12")

# An EPW fragment (Chicago O'Hare TMY3 header and two rows of 20 June); --average gives
# W/m^2 in the 'irradiance' channel, written per vertex here.
set(header "LOCATION,Chicago Ohare Intl Ap,IL,USA,TMY3,725300,41.98,-87.92,-6.0,201.0
DESIGN CONDITIONS,0
TYPICAL/EXTREME PERIODS,0
GROUND TEMPERATURES,0
HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0
COMMENTS 1,test
COMMENTS 2,
DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31
")
set(tail "0,0,0,0,200,5.0,5,3,24.1,77777,9,999999999,379,0.3670,0,88,999.000,999.0,99.0")
set(flags "?9?9?9?9E0?9?9?9?9*9*9*9*9*9")
set(row12 "1979,6,20,12,0,${flags},30.0,21.1,59,98700,1253,1323,425,858,520,367,${tail}")
set(row13 "1979,6,20,13,0,${flags},31.1,21.7,57,98500,1240,1323,428,853,551,335,${tail}")
file(WRITE "${WORK_DIR}/good.epw" "${header}${row12}\n${row13}\n")
expect_success("${PATINA_TEXGEN}" exposure --mesh "${WORK_DIR}/square.obj"
  --per-vertex "${WORK_DIR}/exposure.ply" --quiet --epw "${WORK_DIR}/good.epw" --average
  --sky overcast)
if(NOT EXISTS "${WORK_DIR}/exposure.ply")
  message(FATAL_ERROR "no per-vertex PLY written")
endif()

# A row with a missing direct normal value (9999) on line 10.
string(REPLACE ",853,551,335," ",853,9999,335," broken13 "${row13}")
file(WRITE "${WORK_DIR}/broken.epw" "${header}${row12}\n${broken13}\n")
expect_failure("broken.epw:10: direct normal radiation (field 15) is missing"
  "${PATINA_TEXGEN}" exposure --mesh "${WORK_DIR}/square.obj" --out "${WORK_DIR}/broken"
  --resolution 8 --quiet --epw "${WORK_DIR}/broken.epw")
# A row with too few fields on line 9.
file(WRITE "${WORK_DIR}/short.epw" "${header}1979,6,20,12,0,x,30.0\n")
expect_failure("short.epw:9: data row has 7 fields, expected 35"
  "${PATINA_TEXGEN}" exposure --mesh "${WORK_DIR}/square.obj" --out "${WORK_DIR}/broken"
  --resolution 8 --quiet --epw "${WORK_DIR}/short.epw")
if(EXISTS "${WORK_DIR}/broken/exposure.exr")
  message(FATAL_ERROR "a failed bake left a map behind")
endif()

expect_failure("--latitude cannot be combined with --epw"
  "${PATINA_TEXGEN}" exposure --mesh "${WORK_DIR}/square.obj" --out "${WORK_DIR}/x"
  --epw "${WORK_DIR}/good.epw" --latitude 40)
expect_failure("--timezone is required without --epw"
  "${PATINA_TEXGEN}" exposure --mesh "${WORK_DIR}/square.obj" --out "${WORK_DIR}/x"
  --latitude 40 --longitude 10 --start 2003-06-21 --end 2003-06-22)
expect_failure("--sky: 'cloudy' is not a sky"
  "${PATINA_TEXGEN}" exposure --mesh "${WORK_DIR}/square.obj" --out "${WORK_DIR}/x"
  ${site} --start 2003-06-21 --end 2003-06-22 --sky cloudy)
expect_failure("--end (2003-06-20T00:00:00) must come after --start"
  "${PATINA_TEXGEN}" exposure --mesh "${WORK_DIR}/square.obj" --out "${WORK_DIR}/x"
  ${site} --start 2003-06-21 --end 2003-06-20)
