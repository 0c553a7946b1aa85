// The lat-long environment light (render/environment_light.h): constant maps are D65 white
// times their colour with a uniform density, sample() follows pdf() (chi-square), L / pdf is
// an unbiased estimator, the mapping and rotation conventions, and the error messages.
#include "render/environment_light.h"

#include "core/color_management.h"
#include "host/host.h"
#include "core/image_io.h"
#include "core/rgb_spectrum.h"
#include "core/sampling.h"
#include "core/spectrum.h"

#include "test_util.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace fs = std::filesystem;
namespace pr = patina::render;

namespace {

constexpr double kPi = 3.14159265358979323846;

using patina::test::message_of;

const patina::Host& host()
{
    return patina::default_host();
}

fs::path scratch(const std::string& name)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "environment_light";
    fs::create_directories(dir);
    return dir / name;
}

/// An RGB map as floats, row 0 at the top.
struct Map {
    int width, height;
    std::vector<float> rgb;
    Map(int w, int h, float grey = 0.0f) : width(w), height(h), rgb(3 * size_t(w) * h, grey) {}
    void set(int x, int y, float r, float g, float b)
    {
        float* p = &rgb[3 * (size_t(y) * width + x)];
        p[0] = r;
        p[1] = g;
        p[2] = b;
    }
    fs::path write(const std::string& name) const
    {
        const fs::path p = scratch(name);
        patina::write_image_atomic(p, rgb.data(), width, height, 3, {}, OIIO::TypeDesc::FLOAT);
        return p;
    }
};

/// A bright spot on a colour gradient: non-uniform in both u and v, and chromatic.
Map spot_and_gradient(int w, int h)
{
    Map m(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            m.set(x, y, 0.05f + 0.5f * x / w, 0.2f, 0.05f + 0.8f * y / h);
    for (int y = h / 4; y < h / 4 + 2; ++y)
        for (int x = w / 3; x < w / 3 + 3; ++x)
            m.set(x, y, 200.0f, 150.0f, 80.0f);
    return m;
}

Imath::V3f spherical(double cos_theta, double phi)
{
    // Any fixed world parameterisation will do for the quadratures; +y is the pole.
    const double s = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    return {float(s * std::cos(phi)), float(cos_theta), float(s * std::sin(phi))};
}

float relative_difference(float a, float b)
{
    return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-20f});
}

const PatinaWavelengths kWl = patina::sample_wavelengths_visible(0.37f, 4);
const Imath::V3f kOrigin(0.0f, 0.0f, 0.0f);

} // namespace

// (1) A constant environment: c times the D65 white of luminance 1, a density of 1/(4π).
TEST(EnvironmentLight, ConstantMapIsScaledD65White)
{
    const pr::EnvironmentLight light(host(), {0.5f, 0.5f, 0.5f}, 2.0f);
    // rgb_spectrum.h: emission RGB (1,1,1) is D65 / Y(D65), Y(D65) = ∫ D65 ȳ / ∫ ȳ.
    const double y_d65 = patina::emission_to_xyz(patina::d65)[1];
    patina::Pcg32 rng(7);
    for (int i = 0; i < 200; ++i) {
        const Imath::V3f d =
            spherical(2.0 * rng.uniform_double() - 1.0, 2.0 * kPi * rng.uniform_double());
        const patina::SampledSpectrum L = light.escaped_radiance(d, kWl);
        ASSERT_EQ(L.count, kWl.count);
        for (int k = 0; k < kWl.count; ++k) {
            const float expected = float(0.5 * 2.0 * patina::d65(kWl.lambda_nm[k]) / y_d65);
            EXPECT_LT(relative_difference(L[k], expected), 1e-5f) << kWl.lambda_nm[k] << " nm";
        }
    }
    EXPECT_TRUE(light.is_infinite());
    // power = intensity * ∫ Y dω = 2 * 0.5 * 4π.
    // π r² × ∫ Y dω with r = 1 and Y = 1 over the sphere (pbrt-v4 ImageInfiniteLight::Phi).
    EXPECT_NEAR(light.power(), kPi * 4.0 * kPi, 1e-3 * kPi * 4.0 * kPi);
}

TEST(EnvironmentLight, ConstantColourMatchesItsUplift)
{
    const std::array<float, 3> c = {0.2f, 0.5f, 0.8f};
    const pr::EnvironmentLight light(host(), c, 1.5f);
    const PatinaRgbSpectrum s = host().uplift(c.data(), true);
    for (const Imath::V3f& d : {Imath::V3f(0, 1, 0), Imath::V3f(0, -1, 0), Imath::V3f(1, 0, 0),
                                Imath::V3f(0.3f, -0.2f, -0.9f)}) {
        const patina::SampledSpectrum L = light.escaped_radiance(d, kWl);
        for (int k = 0; k < kWl.count; ++k)
            EXPECT_FLOAT_EQ(L[k], 1.5f * patina::RgbToSpectrum::eval(s, kWl.lambda_nm[k]));
    }
}

// What the integrator evaluates once per path is what escaped_radiance and sample give.
TEST(EnvironmentLight, ConstantRadianceIsWhatEveryQueryGives)
{
    for (const std::array<float, 3>& c :
         {std::array<float, 3>{1.0f, 1.0f, 1.0f}, std::array<float, 3>{0.2f, 0.5f, 0.8f}}) {
        const pr::EnvironmentLight light(host(), c, 1.5f);
        const patina::CieAtWavelengths cie = patina::cie_at_wavelengths(kWl);
        const patina::SampledSpectrum a = light.constant_radiance(kWl);
        const patina::SampledSpectrum b = light.constant_radiance(kWl, cie.d65);
        const patina::SampledSpectrum e = light.escaped_radiance(Imath::V3f(0.3f, -0.2f, -0.9f), kWl);
        const auto ls = light.sample(kOrigin, Imath::V2f(0.3f, 0.6f), kWl);
        ASSERT_TRUE(ls.has_value());
        EXPECT_EQ(ls->pdf, pr::EnvironmentLight::kUniformSpherePdf);
        EXPECT_EQ(ls->wi, pr::EnvironmentLight::sample_uniform_sphere(Imath::V2f(0.3f, 0.6f)));
        for (int k = 0; k < kWl.count; ++k) {
            EXPECT_EQ(a[k], e[k]);
            EXPECT_EQ(a[k], ls->L[k]);
            EXPECT_LT(relative_difference(b[k], a[k]), 1e-6f) << kWl.lambda_nm[k] << " nm";
        }
    }
}

TEST(EnvironmentLight, ConstantDensityIsUniformOverTheSphere)
{
    const pr::EnvironmentLight light(host(), {0.3f, 0.6f, 0.1f});
    const Imath::V3f p(0, 0, 0);
    // Midpoint quadrature in (cos θ, φ) (dω = d cos θ dφ): the density integrates to 1.
    const int n_mu = 2000, n_phi = 64;
    double integral = 0.0, worst_mid_latitude = 0.0;
    for (int i = 0; i < n_mu; ++i) {
        const double mu = -1.0 + (i + 0.5) * 2.0 / n_mu;
        for (int j = 0; j < n_phi; ++j) {
            const double pdf = light.pdf(p, spherical(mu, (j + 0.5) * 2.0 * kPi / n_phi));
            integral += pdf * (2.0 / n_mu) * (2.0 * kPi / n_phi);
            // Within 30° of the horizon the cell discretisation of sin θ is below 0.4 %.
            if (std::abs(mu) <= 0.5)
                worst_mid_latitude = std::max(worst_mid_latitude, std::abs(pdf * 4.0 * kPi - 1.0));
        }
    }
    EXPECT_NEAR(integral, 1.0, 1e-3);
    EXPECT_LT(worst_mid_latitude, 0.01);
    // And sample() agrees: L / pdf ≈ 4π L at mid-latitudes.
    const auto s = light.sample(p, {0.3f, 0.5f}, kWl);
    ASSERT_TRUE(s);
    EXPECT_TRUE(std::isinf(s->distance));
    EXPECT_FALSE(s->is_delta);
    EXPECT_NEAR(s->pdf * 4.0 * kPi, 1.0, 0.01);
}

TEST(EnvironmentLight, FileIsConvertedToTheWorkingSpace)
{
    // A constant lin_rec709 map: each texel is the working-space conversion of c.
    std::array<float, 3> c = {0.8f, 0.3f, 0.1f};
    Map m(8, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x)
            m.set(x, y, c[0], c[1], c[2]);
    const fs::path file = m.write("constant_rec709.exr");
    const pr::EnvironmentLight light(host(), file, "lin_rec709");
    host().colors().convert("lin_rec709", host().colors().working_space(), c.data(), 1);
    const PatinaRgbSpectrum s = host().uplift(c.data(), true);
    const patina::SampledSpectrum L = light.escaped_radiance({0.2f, 0.7f, -0.5f}, kWl);
    for (int k = 0; k < kWl.count; ++k)
        EXPECT_NEAR(L[k], patina::RgbToSpectrum::eval(s, kWl.lambda_nm[k]), 1e-5f);

    // A data space is taken as it is; negatives are clamped to 0.
    Map raw(2, 1);
    raw.set(0, 0, -1.0f, 0.5f, 0.25f);
    raw.set(1, 0, -1.0f, 0.5f, 0.25f);
    const pr::EnvironmentLight data(host(), raw.write("raw.exr"), "raw");
    const pr::EnvironmentLight expected(host(), {0.0f, 0.5f, 0.25f});
    const patina::SampledSpectrum a = data.escaped_radiance({0, 0, 1}, kWl);
    const patina::SampledSpectrum b = expected.escaped_radiance({0, 0, 1}, kWl);
    for (int k = 0; k < kWl.count; ++k)
        EXPECT_FLOAT_EQ(a[k], b[k]);
}

// (2) sample() draws directions with the density pdf() reports: a chi-square test over bins
// in world (cos θ, φ) aligned with the map's texels, so the expected counts are exact.
TEST(EnvironmentLight, SamplesFollowPdfChiSquare)
{
    const int w = 64, h = 32;
    const fs::path file = spot_and_gradient(w, h).write("spot_gradient.exr");
    // A rotation of 5 texel columns keeps the texel edges on the bin edges below.
    const float rotation = 5.0f * 360.0f / w;
    const pr::EnvironmentLight light(host(), file, "lin_rec709", 3.0f, rotation);
    const Imath::V3f p(1, 2, 3);

    // Bins: 32 in φ (2 texel columns each), 16 in θ (2 texel rows), with the map's own
    // world angles θ = acos(y), φ = atan2(-x, z) (header comment).
    const int n_phi = 32, n_theta = 16;
    auto bin_of = [&](const Imath::V3f& d) {
        double phi = std::atan2(-double(d.x), double(d.z));
        if (phi < 0)
            phi += 2.0 * kPi;
        const double theta = std::atan2(std::hypot(double(d.x), double(d.z)), double(d.y));
        const int i = std::min(int(phi / (2.0 * kPi) * n_phi), n_phi - 1);
        const int j = std::min(int(theta / kPi * n_theta), n_theta - 1);
        return j * n_phi + i;
    };
    // Expected probability of each bin: ∫ pdf sin θ dθ dφ by the midpoint rule, 2 points per
    // texel column and 2 per sampling cell row, where pdf sin θ is constant.
    std::vector<double> expected(n_phi * n_theta, 0.0);
    const int sub_phi = 4, sub_theta = 32;
    for (int j = 0; j < n_theta; ++j)
        for (int i = 0; i < n_phi; ++i)
            for (int b = 0; b < sub_theta; ++b)
                for (int a = 0; a < sub_phi; ++a) {
                    const double dtheta = kPi / (n_theta * sub_theta);
                    const double dphi = 2.0 * kPi / (n_phi * sub_phi);
                    const double theta = (j * sub_theta + b + 0.5) * dtheta;
                    const double phi = (i * sub_phi + a + 0.5) * dphi;
                    const Imath::V3f d(float(-std::sin(theta) * std::sin(phi)),
                                       float(std::cos(theta)),
                                       float(std::sin(theta) * std::cos(phi)));
                    expected[j * n_phi + i] += light.pdf(p, d) * std::sin(theta) * dtheta * dphi;
                }
    double total = 0.0;
    for (double e : expected)
        total += e;
    EXPECT_NEAR(total, 1.0, 1e-4);

    // Draw samples; each must also agree with pdf() and escaped_radiance() in its direction.
    const int n = 1'000'000;
    std::vector<double> observed(expected.size(), 0.0);
    patina::Pcg32 rng(2024);
    int pdf_mismatches = 0, radiance_mismatches = 0;
    for (int s = 0; s < n; ++s) {
        const auto ls = light.sample(p, {rng.uniform_float(), rng.uniform_float()}, kWl);
        ASSERT_TRUE(ls);
        ASSERT_NEAR(ls->wi.length(), 1.0f, 1e-5f);
        observed[bin_of(ls->wi)] += 1.0;
        if (relative_difference(ls->pdf, light.pdf(p, ls->wi)) > 1e-3f)
            ++pdf_mismatches;
        const patina::SampledSpectrum L = light.escaped_radiance(ls->wi, kWl);
        if (relative_difference(ls->L[0], L[0]) > 1e-5f)
            ++radiance_mismatches;
    }
    // Only directions within rounding of a cell edge may land in the neighbouring cell.
    EXPECT_LE(pdf_mismatches, n / 10000);
    EXPECT_LE(radiance_mismatches, n / 10000);

    // Pearson's statistic, pooling bins with fewer than 5 expected samples.
    double chi2 = 0.0, pooled_e = 0.0, pooled_o = 0.0;
    int dof = -1;
    for (size_t b = 0; b < expected.size(); ++b) {
        const double e = expected[b] * n;
        if (e < 5.0) {
            pooled_e += e;
            pooled_o += observed[b];
            EXPECT_TRUE(e > 0.0 || observed[b] == 0.0) << "sample in a zero-density bin " << b;
            continue;
        }
        chi2 += (observed[b] - e) * (observed[b] - e) / e;
        ++dof;
    }
    if (pooled_e > 0.0) {
        chi2 += (pooled_o - pooled_e) * (pooled_o - pooled_e) / std::max(pooled_e, 1e-9);
        ++dof;
    }
    // Wilson-Hilferty approximation of the χ² quantile at significance 1e-3 (z = 3.09).
    const double k = dof, z = 3.09;
    const double threshold =
        k * std::pow(1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k)), 3);
    EXPECT_LT(chi2, threshold) << "dof " << dof;
}

// (3) L / pdf is unbiased: E[L cos θ / pdf] over sampled directions equals ∫ L cos θ dω over
// the upper hemisphere, computed by quadrature of escaped_radiance.
TEST(EnvironmentLight, ImportanceSampledIrradianceMatchesQuadrature)
{
    const fs::path file = spot_and_gradient(48, 24).write("spot_gradient_small.exr");
    const pr::EnvironmentLight light(host(), file, "lin_rec709", 1.0f, 40.0f);
    const Imath::V3f p(0, 0, 0);

    // Midpoint quadrature in (cos θ, φ) over the upper hemisphere.
    const int n_mu = 1024, n_phi = 2048;
    std::vector<double> quadrature(kWl.count, 0.0);
    for (int i = 0; i < n_mu; ++i) {
        const double mu = (i + 0.5) / n_mu;
        for (int j = 0; j < n_phi; ++j) {
            const patina::SampledSpectrum L =
                light.escaped_radiance(spherical(mu, (j + 0.5) * 2.0 * kPi / n_phi), kWl);
            for (int k = 0; k < kWl.count; ++k)
                quadrature[k] += L[k] * mu * (1.0 / n_mu) * (2.0 * kPi / n_phi);
        }
    }

    const int n = 400'000;
    std::vector<double> estimate(kWl.count, 0.0);
    patina::Pcg32 rng(99);
    for (int s = 0; s < n; ++s) {
        const auto ls = light.sample(p, {rng.uniform_float(), rng.uniform_float()}, kWl);
        if (!ls || ls->wi.y <= 0.0f)
            continue;
        for (int k = 0; k < kWl.count; ++k)
            estimate[k] += ls->L[k] * ls->wi.y / ls->pdf / n;
    }
    for (int k = 0; k < kWl.count; ++k)
        EXPECT_NEAR(estimate[k], quadrature[k], 0.01 * quadrature[k]) << kWl.lambda_nm[k] << " nm";
}

// (4) The mapping: the top rows are the zenith; the centre column looks along -z, u grows
// towards +x; rotation turns the map counter-clockwise seen from above.
TEST(EnvironmentLight, TopRowsAreTheZenith)
{
    Map m(16, 8, 0.01f);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 16; ++x)
            m.set(x, y, 5.0f, 5.0f, 5.0f);
    const pr::EnvironmentLight light(host(), m.write("bright_top.exr"), "raw");
    const float up = light.escaped_radiance({0, 1, 0}, kWl)[0];
    const float down = light.escaped_radiance({0, -1, 0}, kWl)[0];
    const float horizon = light.escaped_radiance({1, 0, 0}, kWl)[0];
    EXPECT_NEAR(up / down, 500.0f, 0.5f);
    EXPECT_NEAR(horizon / down, 1.0f, 1e-5f);
    // Importance sampling sends almost every sample upwards.
    int upward = 0;
    patina::Pcg32 rng(5);
    for (int s = 0; s < 1000; ++s)
        upward +=
            light.sample(kOrigin, {rng.uniform_float(), rng.uniform_float()}, kWl)->wi.y > 0.7f;
    EXPECT_GT(upward, 950);
}

TEST(EnvironmentLight, CentreColumnLooksAlongMinusZAndRotationTurnsCounterClockwise)
{
    // An odd-sized map whose centre texel (8, 4) contains (u, v) = (0.5, 0.5).
    Map centre(17, 9, 0.01f);
    centre.set(8, 4, 10.0f, 10.0f, 10.0f);
    const fs::path file = centre.write("spot_centre.exr");
    auto bright = [](const pr::EnvironmentLight& l, Imath::V3f d) {
        return l.escaped_radiance(d, kWl)[0] > 1.0f;
    };
    const Imath::V3f px(1, 0, 0), nx(-1, 0, 0), pz(0, 0, 1), nz(0, 0, -1);
    const pr::EnvironmentLight still(host(), file, "raw");
    EXPECT_TRUE(bright(still, nz));
    EXPECT_FALSE(bright(still, px) || bright(still, nx) || bright(still, pz));

    // Seen from above (+y towards the viewer) -z is "up the page" and +x "right": a quarter
    // turn counter-clockwise takes -z to -x.
    const pr::EnvironmentLight turned(host(), file, "raw", 1.0f, 90.0f);
    EXPECT_TRUE(bright(turned, nx));
    EXPECT_FALSE(bright(turned, nz) || bright(turned, px) || bright(turned, pz));
    const pr::EnvironmentLight back(host(), file, "raw", 1.0f, -90.0f);
    EXPECT_TRUE(bright(back, px));
    // The samples follow the spot.
    Imath::V3f mean(0, 0, 0);
    patina::Pcg32 rng(11);
    for (int s = 0; s < 1000; ++s)
        mean += turned.sample(kOrigin, {rng.uniform_float(), rng.uniform_float()}, kWl)->wi;
    EXPECT_GT((mean / 1000.0f).dot(nx), 0.8f);

    // u = 0.75 is +x: a spot in column 12 of 17 (u in [0.706, 0.765)).
    Map right(17, 9, 0.01f);
    right.set(12, 4, 10.0f, 10.0f, 10.0f);
    const pr::EnvironmentLight east(host(), right.write("spot_right.exr"), "raw");
    EXPECT_TRUE(bright(east, px));
    EXPECT_FALSE(bright(east, nz));

    // The helpers state the same convention.
    EXPECT_LT((still.uv_to_direction(0.5f, 0.5f) - nz).length(), 1e-6f);
    EXPECT_LT((still.uv_to_direction(0.75f, 0.5f) - px).length(), 1e-6f);
    EXPECT_LT((still.uv_to_direction(0.0f, 0.5f) - pz).length(), 1e-6f);
    EXPECT_GT(still.uv_to_direction(0.3f, 0.0f).y, 0.99999f);
    EXPECT_LT((turned.uv_to_direction(0.5f, 0.5f) - nx).length(), 1e-6f);
    const Imath::V2f uv = turned.direction_to_uv(turned.uv_to_direction(0.3f, 0.7f));
    EXPECT_NEAR(uv.x, 0.3f, 1e-6f);
    EXPECT_NEAR(uv.y, 0.7f, 1e-6f);
}

// (5) Errors name the file, the colour space and the bad texel.
TEST(EnvironmentLight, MissingFileIsNamed)
{
    const fs::path missing = scratch("no_such_sky.exr");
    const std::string msg =
        message_of<std::runtime_error>([&] { pr::EnvironmentLight(host(), missing, "raw"); });
    EXPECT_NE(msg.find(missing.string()), std::string::npos) << msg;
}

TEST(EnvironmentLight, UnknownColourSpaceIsNamed)
{
    const fs::path file = Map(4, 2, 1.0f).write("unknown_space.exr");
    const std::string msg = message_of<std::runtime_error>(
        [&] { pr::EnvironmentLight(host(), file, "not_a_colour_space"); });
    EXPECT_NE(msg.find("not_a_colour_space"), std::string::npos) << msg;
    EXPECT_NE(msg.find(file.string()), std::string::npos) << msg;
}

TEST(EnvironmentLight, NonFiniteTexelIsNamed)
{
    Map m(6, 4, 0.5f);
    m.set(3, 2, 0.5f, std::nanf(""), 0.5f);
    const fs::path file = m.write("nan_texel.exr");
    const std::string msg =
        message_of<std::runtime_error>([&] { pr::EnvironmentLight(host(), file, "lin_rec709"); });
    EXPECT_NE(msg.find(file.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("(3, 2)"), std::string::npos) << msg;
    EXPECT_NE(msg.find("NaN"), std::string::npos) << msg;

    Map inf(6, 4, 0.5f);
    inf.set(5, 0, INFINITY, 0.5f, 0.5f);
    const std::string inf_msg = message_of<std::runtime_error>(
        [&] { pr::EnvironmentLight(host(), inf.write("inf_texel.exr"), "raw"); });
    EXPECT_NE(inf_msg.find("(5, 0)"), std::string::npos) << inf_msg;
}

TEST(EnvironmentLight, BadIntensityOrRotationIsRefused)
{
    const fs::path file = Map(4, 2, 1.0f).write("bad_arguments.exr");
    EXPECT_NE(message_of<std::invalid_argument>([&] {
                  pr::EnvironmentLight(host(), file, "raw", -1.0f);
              }).find("intensity"),
              std::string::npos);
    EXPECT_NE(message_of<std::invalid_argument>([&] {
                  pr::EnvironmentLight(host(), file, "raw", 1.0f, NAN);
              }).find("rotation"),
              std::string::npos);
}

// Not a timing gate: loads 1024 x 512 maps and reports the load time, checking texels against
// their own uplift. The first map has a distinct colour per texel (one uplift each); the
// second repeats a row gradient on every row (one uplift per distinct colour).
TEST(EnvironmentLight, LoadsLargeMaps)
{
    const int w = 1024, h = 512;
    Map distinct(w, h), repeated(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            distinct.set(x, y, 0.1f + x * 1e-3f, 0.3f + y * 1e-3f, 0.2f + (x ^ y) * 1e-4f);
            repeated.set(x, y, 0.1f + x * 1e-3f, 0.3f, 0.2f);
        }
    for (const auto& [map, name] :
         {std::pair{&distinct, "large_distinct.exr"}, std::pair{&repeated, "large_repeated.exr"}}) {
        const fs::path file = map->write(name);
        const auto start = std::chrono::steady_clock::now();
        const pr::EnvironmentLight light(host(), file, "lin_rec709");
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        RecordProperty(name, std::to_string(seconds));
        std::printf("EnvironmentLight: %dx%d map %s loaded in %.3f s\n", w, h, name, seconds);
        ASSERT_EQ(light.width(), w);
        ASSERT_EQ(light.height(), h);
        // Texel (x, y) seen through its centre direction is its own converted colour.
        for (const auto& [x, y] :
             {std::pair{0, 0}, std::pair{517, 200}, std::pair{1023, 511}, std::pair{300, 511}}) {
            std::array<float, 3> c;
            for (int k = 0; k < 3; ++k)
                c[k] = map->rgb[3 * (size_t(y) * w + x) + k];
            host().colors().convert("lin_rec709", host().colors().working_space(), c.data(), 1);
            const PatinaRgbSpectrum s = host().uplift(c.data(), true);
            const patina::SampledSpectrum L =
                light.escaped_radiance(light.uv_to_direction((x + 0.5f) / w, (y + 0.5f) / h), kWl);
            for (int k = 0; k < kWl.count; ++k)
                EXPECT_FLOAT_EQ(L[k], patina::RgbToSpectrum::eval(s, kWl.lambda_nm[k]))
                    << "texel " << x << ", " << y;
        }
        const auto s = light.sample(kOrigin, {0.25f, 0.75f}, kWl);
        ASSERT_TRUE(s);
        EXPECT_NEAR(s->pdf, light.pdf(kOrigin, s->wi), 1e-4f * s->pdf);
    }
}
