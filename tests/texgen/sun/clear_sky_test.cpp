// Extraterrestrial irradiance, Kasten-Young air mass and the Ineichen-Perez clear sky.
#include "texgen/sun/clear_sky.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pt = patina::texgen;

TEST(ClearSky, ExtraterrestrialFollowsTheInverseSquareLaw)
{
    EXPECT_DOUBLE_EQ(pt::extraterrestrial_normal_irradiance(1.0), 1361.0);
    // Perihelion (~0.98329 AU) and aphelion (~1.01671 AU): +3.4% and -3.3%.
    EXPECT_NEAR(pt::extraterrestrial_normal_irradiance(0.98329), 1407.7, 0.1);
    EXPECT_NEAR(pt::extraterrestrial_normal_irradiance(1.01671), 1316.6, 0.1);
}

TEST(ClearSky, KastenYoungAirMass)
{
    // Kasten & Young 1989: 1/(sin e + 0.50572 (e + 6.07995)^-1.6364), e = 90 - z in deg;
    // 37.92 at the horizon (their stated value), ~1.994 at z = 60.
    EXPECT_NEAR(pt::relative_air_mass(0.0), 0.99971, 1e-5);
    EXPECT_NEAR(pt::relative_air_mass(60.0), 1.99429, 1e-5);
    EXPECT_NEAR(pt::relative_air_mass(90.0 - 1e-9), 37.92, 0.01);
    EXPECT_EQ(pt::relative_air_mass(90.0), 0.0);
    EXPECT_EQ(pt::relative_air_mass(120.0), 0.0);
}

TEST(ClearSky, IneichenPerezHandValues)
{
    // Ineichen & Perez 2002 §2 evaluated by hand (double precision, see the formulas in
    // clear_sky.cpp): sea level, TL 3, I0 1361.
    //   z = 0: AM 0.999712, Gc = 0.868 I0 exp(-0.0387 AM 3) = 1051.891,
    //          Bnc = 0.827 I0 exp(-0.09 AM 2) = 940.185 (below the Gc bound 955.440).
    pt::ClearSkyParameters p;
    p.linke_turbidity = 3.0;
    const pt::ClearSkyIrradiance zenith = pt::ineichen_perez(0.0, 1361.0, p);
    EXPECT_NEAR(zenith.ghi, 1051.891, 1e-3);
    EXPECT_NEAR(zenith.dni, 940.185, 1e-3);
    EXPECT_NEAR(zenith.dhi, 111.706, 1e-3);
    const pt::ClearSkyIrradiance z60 = pt::ineichen_perez(60.0, 1361.0, p);
    EXPECT_NEAR(z60.ghi, 468.589, 1e-3);
    EXPECT_NEAR(z60.dni, 786.075, 1e-3);
    // 1830 m (Golden, CO), TL 4, z = 30: the altitude terms cg1, cg2, fh1, fh2.
    p.linke_turbidity = 4.0;
    p.elevation_m = 1830.0;
    const pt::ClearSkyIrradiance high = pt::ineichen_perez(30.0, 1361.0, p);
    EXPECT_NEAR(high.ghi, 937.003, 1e-3);
    EXPECT_NEAR(high.dni, 865.983, 1e-3);
    EXPECT_NEAR(high.dhi, 187.040, 1e-3);
}

TEST(ClearSky, IdentitiesHorizonAndMonotonicity)
{
    pt::ClearSkyParameters p;
    for (double tl : {2.0, 3.0, 5.0}) {
        for (double h : {0.0, 1500.0}) {
            p.linke_turbidity = tl;
            p.elevation_m = h;
            double previous_ghi = 1e30, previous_dni = 1e30;
            for (double z = 0.0; z < 90.0; z += 0.5) {
                const pt::ClearSkyIrradiance c = pt::ineichen_perez(z, 1361.0, p);
                // GHI = DNI cos z + DHI, all non-negative, DNI below the extraterrestrial.
                EXPECT_NEAR(c.ghi, c.dni * std::cos(z * M_PI / 180.0) + c.dhi, 1e-9);
                EXPECT_GE(c.dhi, 0.0);
                EXPECT_GT(c.dni, 0.0);
                EXPECT_LT(c.dni, 1361.0);
                // Monotone: a lower sun never gives more global or direct irradiance.
                EXPECT_LE(c.ghi, previous_ghi) << "z " << z;
                EXPECT_LE(c.dni, previous_dni) << "z " << z;
                previous_ghi = c.ghi;
                previous_dni = c.dni;
            }
            for (double z : {90.0, 95.0, 180.0}) {
                const pt::ClearSkyIrradiance c = pt::ineichen_perez(z, 1361.0, p);
                EXPECT_EQ(c.ghi, 0.0);
                EXPECT_EQ(c.dni, 0.0);
                EXPECT_EQ(c.dhi, 0.0);
            }
        }
    }
    // More turbid air: less direct, more diffuse at the same sun.
    p.elevation_m = 0.0;
    p.linke_turbidity = 2.0;
    const pt::ClearSkyIrradiance clean = pt::ineichen_perez(30.0, 1361.0, p);
    p.linke_turbidity = 6.0;
    const pt::ClearSkyIrradiance hazy = pt::ineichen_perez(30.0, 1361.0, p);
    EXPECT_GT(clean.dni, hazy.dni);
    EXPECT_LT(clean.dhi, hazy.dhi);
}
