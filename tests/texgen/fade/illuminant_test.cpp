// Illuminants for fading: CIE tables and A's closed form, and the dose normalisation.
#include "texgen/fade/illuminant.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace patina::texgen::fade;

namespace {

// The values of a colord CGATS .sp file (when colord-data is installed), and its start.
std::vector<double> colord_values(const std::string& name, double& start_nm)
{
    std::ifstream in("/usr/share/colord/illuminant/CIE-" + name + ".sp");
    std::vector<double> v;
    std::string line;
    bool data = false;
    while (std::getline(in, line)) {
        if (line.rfind("SPECTRAL_START_NM", 0) == 0)
            start_nm = std::stod(line.substr(17));
        if (line == "END_DATA")
            break;
        if (data) {
            std::istringstream s(line);
            double x;
            while (s >> x)
                v.push_back(x * 100.0);
        }
        if (line == "BEGIN_DATA")
            data = true;
    }
    return v;
}

}  // namespace

TEST(Illuminant, TablesMatchCie)
{
    // CIE 15:2004: D65 is 100 at 560 nm, 117.812 at 460 nm, 3.2945 at 310 nm; F11 has its
    // green mercury/terbium line at 545 nm (72.84).
    const Illuminant d65 = illuminant_by_name("d65");
    EXPECT_NEAR(d65.relative.at(560.0), 100.0, 1e-9);
    EXPECT_NEAR(d65.relative.at(460.0), 117.812, 1e-9);
    EXPECT_NEAR(d65.relative.at(310.0), 3.2945, 1e-9);
    EXPECT_EQ(d65.relative.at(200.0), 0.0);
    EXPECT_NEAR(illuminant_by_name("fluorescent").relative.at(545.0), 72.84, 1e-9);
    // Cross-check every table against Debian's colord-data when it is installed.
    for (const char* name : {"D65", "F2", "F11"}) {
        double start = 0.0;
        const std::vector<double> ref = colord_values(name, start);
        if (ref.empty())
            continue;
        const Illuminant il = illuminant_by_name(name);
        for (size_t i = 0; i < ref.size(); ++i)
            EXPECT_NEAR(il.relative.at(start + 5.0 * i), ref[i], 1e-6) << name << " " << i;
    }
    // A from Planck (CIE 15:2004: 2848 K with c2 = 1.435e-2 m K): 100 at 560 nm; S_A(400)/S_A(700) from the
    // formula: (700/400)^5 (e^{c2/(700 T)} - 1)/(e^{c2/(400 T)} - 1).
    const Illuminant a = illuminant_by_name("A");
    EXPECT_NEAR(a.relative.at(560.0), 100.0, 1e-3);
    const double c2 = 1.435e-2, T = 2848.0;  // = 2856 K with c2 = 1.4388e-2
    const double ratio = std::pow(700.0 / 400.0, 5) * std::expm1(c2 / (700e-9 * T)) /
                         std::expm1(c2 / (400e-9 * T));
    EXPECT_NEAR(a.relative.at(400.0) / a.relative.at(700.0), ratio, 1e-4 * ratio);
    EXPECT_THROW(illuminant_by_name("D50x"), std::runtime_error);
}

TEST(Illuminant, SpectralIrradianceIntegratesToTheBandIrradiance)
{
    // On a 1 nm grid over the band, the trapezoid sum of E(λ) is the irradiance given.
    for (const char* name : {"D65", "A", "F11"}) {
        const Illuminant il = illuminant_by_name(name);
        const WavelengthGrid g = WavelengthGrid::uniform(il.band_min_nm, il.band_max_nm, 1.0);
        const std::vector<double> e = il.spectral_irradiance(g, 37.0);
        const std::vector<double> w = g.trapezoid_weights();
        double sum = 0.0;
        for (size_t i = 0; i < e.size(); ++i)
            sum += w[i] * e[i];
        EXPECT_NEAR(sum, 37.0, 1e-9) << name;
    }
    const Illuminant t = illuminant_from_table("exposure map", {400, 500, 600}, {1, 1, 1});
    const std::vector<double> e = t.spectral_irradiance(WavelengthGrid{{450.0, 700.0}}, 200.0);
    EXPECT_NEAR(e[0], 1.0, 1e-12);  // 200 W/m^2 over 200 nm
    EXPECT_EQ(e[1], 0.0);
    EXPECT_THROW(illuminant_from_table("x", {500, 400}, {1, 1}), std::runtime_error);
}
