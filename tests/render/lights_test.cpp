// Lights for next-event estimation: the sun (disc and delta), emissive meshes, and the
// power-proportional light sampler, checked against closed-form irradiances.
#include "render/area_light.h"
#include "render/distant_light.h"
#include "render/environment_light.h"
#include "render/light_sampler.h"

#include "host/host.h"
#include "host/plugin_registry.h"
#include "core/rgb_spectrum.h"
#include "core/sampling.h"
#include "host/shader_instance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace pr = patina::render;
using Imath::V2f;
using Imath::V3f;
using patina::SampledSpectrum;

namespace {

constexpr double kPi = std::numbers::pi;

double radians(double deg)
{
    return deg * kPi / 180.0;
}

PatinaRgbSpectrum sun_colour()
{
    const float rgb[3] = {1.0f, 0.85f, 0.7f};
    return patina::default_host().uplift(rgb, true);
}

// Angle between two directions, accurate for tiny angles too (atan2 of |a×b| and a·b).
double angle_between(const V3f& a, const V3f& b)
{
    const double ax = a.x, ay = a.y, az = a.z, bx = b.x, by = b.y, bz = b.z;
    const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), ax * bx + ay * by + az * bz);
}

// Unit direction at angle `theta` from unit `axis`, rotated about it by `phi`.
V3f around(const V3f& axis, double theta, double phi)
{
    const V3f helper = std::abs(axis.x) < 0.9f ? V3f(1, 0, 0) : V3f(0, 1, 0);
    const V3f s = axis.cross(helper).normalized(), t = axis.cross(s);
    const V3f w = static_cast<float>(std::sin(theta) * std::cos(phi)) * s +
                  static_cast<float>(std::sin(theta) * std::sin(phi)) * t +
                  static_cast<float>(std::cos(theta)) * axis;
    return w.normalized();
}

} // namespace

// ---------------------------------------------------------------------------------------
// DistantLight
// ---------------------------------------------------------------------------------------

// A horizontal Lambertian point of reflectance R under a sun at elevation e reflects
// Lo = R/π × E × sin e, for a point sun and for a disc wholly above the horizon alike
// (∫cone ω dω = π sin² θmax × axis, so ∫ L cos θ dω = E × (axis · n)).
TEST(DistantLight, LambertPointReflectsRSinElevationOverPi)
{
    const float R = 0.6f, E = 800.0f;
    const double e = radians(35.0);
    const V3f to_sun(static_cast<float>(std::cos(e)), 0.0f, static_cast<float>(std::sin(e)));
    const V3f n(0, 0, 1), p(1, 2, 3);
    const PatinaWavelengths wl = patina::sample_wavelengths_visible(0.37f, 4);
    const PatinaRgbSpectrum spectrum = sun_colour();
    for (const float diameter : {0.0f, 0.53f, 20.0f}) {
        const pr::DistantLight sun(to_sun, diameter, spectrum, E);
        EXPECT_EQ(sun.is_delta(), diameter == 0.0f);
        patina::Pcg32 rng(11);
        const int n_samples = diameter == 0.0f ? 1 : 20000;
        double sum[PATINA_MAX_WAVELENGTHS] = {};
        for (int k = 0; k < n_samples; ++k) {
            const V2f u(rng.uniform_float(), rng.uniform_float());
            const auto ls = sun.sample(p, u, wl);
            ASSERT_TRUE(ls);
            EXPECT_EQ(ls->is_delta, diameter == 0.0f);
            EXPECT_TRUE(std::isinf(ls->distance));
            // Lo = ∫ f L cos θ dω with f = R/π, one sample at a time
            for (int i = 0; i < wl.count; ++i)
                sum[i] += R / kPi * ls->L[i] * std::max(0.0f, ls->wi.dot(n)) / ls->pdf;
        }
        for (int i = 0; i < wl.count; ++i) {
            const double expected =
                R / kPi * E * patina::RgbToSpectrum::eval(spectrum, wl.lambda_nm[i]) * std::sin(e);
            EXPECT_NEAR(sum[i] / n_samples, expected, 0.005 * expected)
                << "diameter " << diameter << " deg, lambda " << wl.lambda_nm[i];
        }
    }
}

// Directions from the cone sampler lie inside the disc, pdf() agrees with sample(), the
// density is uniform (a quarter-ish of the samples within half the angle), and pdf()
// integrates to 1 over the sphere.
TEST(DistantLight, ConeSamplingStaysInsideAndPdfIntegratesToOne)
{
    const V3f to_sun = V3f(0.3f, -0.5f, 0.8f).normalized();
    const PatinaWavelengths wl = patina::sample_wavelengths_visible(0.5f, 4);
    for (const float diameter : {0.53f, 20.0f, 120.0f}) {
        const pr::DistantLight sun(to_sun, diameter, sun_colour(), 1.0f);
        const double theta_max = radians(diameter / 2.0);
        const double expected_pdf = 1.0 / (2.0 * kPi * (1.0 - std::cos(theta_max)));
        patina::Pcg32 rng(3);
        const int n_samples = 100000;
        int within_half = 0;
        for (int k = 0; k < n_samples; ++k) {
            const V2f u(rng.uniform_float(), rng.uniform_float());
            const auto ls = sun.sample(V3f(0), u, wl);
            ASSERT_TRUE(ls);
            const double theta = angle_between(ls->wi, to_sun);
            ASSERT_LE(theta, theta_max * (1.0 + 1e-4)) << "diameter " << diameter;
            ASSERT_EQ(sun.pdf(V3f(0), ls->wi), ls->pdf);
            within_half += theta < theta_max / 2.0;
        }
        // Uniform in solid angle: P(θ < θmax/2) = (1 − cos(θmax/2)) / (1 − cos θmax)
        const double p_half = (1.0 - std::cos(theta_max / 2.0)) / (1.0 - std::cos(theta_max));
        EXPECT_NEAR(static_cast<double>(within_half) / n_samples, p_half, 0.006);
        EXPECT_NEAR(sun.pdf(V3f(0), to_sun), expected_pdf, 1e-4 * expected_pdf);

        // ∫ pdf dω by the midpoint rule in the sun's polar coordinates, over twice the cone
        const int n_theta = 4000, n_phi = 16;
        const double d_theta = std::min(2.0 * theta_max, kPi) / n_theta;
        double integral = 0.0;
        for (int i = 0; i < n_theta; ++i)
            for (int j = 0; j < n_phi; ++j) {
                const double theta = (i + 0.5) * d_theta, phi = (j + 0.5) * 2.0 * kPi / n_phi;
                integral += sun.pdf(V3f(0), around(to_sun, theta, phi)) * std::sin(theta) *
                            d_theta * (2.0 * kPi / n_phi);
            }
        EXPECT_NEAR(integral, 1.0, 2e-3) << "diameter " << diameter;
    }
}

// Escaped rays see L = E / (π sin² θmax) inside the disc (so that ∫ L cos θ dω = E facing
// the sun) and nothing outside; a point sun is never seen by an escaped ray.
TEST(DistantLight, EscapedRadianceInsideTheDiscOnly)
{
    const V3f to_sun = V3f(-0.2f, 0.9f, 0.1f).normalized();
    const float E = 1000.0f, diameter = 0.53f;
    const double theta_max = radians(diameter / 2.0);
    const PatinaWavelengths wl = patina::sample_wavelengths_visible(0.2f, 4);
    const PatinaRgbSpectrum spectrum = sun_colour();
    const pr::DistantLight sun(to_sun, diameter, spectrum, E);
    EXPECT_TRUE(sun.is_infinite());
    const double L = E / (kPi * std::sin(theta_max) * std::sin(theta_max));
    for (const double phi : {0.0, 1.0, 4.0}) {
        const auto inside = sun.escaped_radiance(around(to_sun, 0.9 * theta_max, phi), wl);
        const auto outside = sun.escaped_radiance(around(to_sun, 1.1 * theta_max, phi), wl);
        for (int i = 0; i < wl.count; ++i) {
            const double expected = L * patina::RgbToSpectrum::eval(spectrum, wl.lambda_nm[i]);
            EXPECT_NEAR(inside[i], expected, 1e-5 * expected);
            EXPECT_EQ(outside[i], 0.0f);
        }
        EXPECT_EQ(sun.pdf(V3f(0), around(to_sun, 1.1 * theta_max, phi)), 0.0f);
    }
    EXPECT_TRUE(sun.escaped_radiance(-to_sun, wl).is_black());

    const pr::DistantLight point_sun(to_sun, 0.0f, spectrum, E);
    EXPECT_TRUE(point_sun.escaped_radiance(to_sun, wl).is_black());
    EXPECT_EQ(point_sun.pdf(V3f(0), to_sun), 0.0f);
}

TEST(DistantLight, RejectsBadParameters)
{
    const PatinaRgbSpectrum s = sun_colour();
    EXPECT_THROW(pr::DistantLight(V3f(0), 0.5f, s, 1.0f), std::invalid_argument);
    EXPECT_THROW(pr::DistantLight(V3f(0, 0, 1), -1.0f, s, 1.0f), std::invalid_argument);
    EXPECT_THROW(pr::DistantLight(V3f(0, 0, 1), 180.0f, s, 1.0f), std::invalid_argument);
    EXPECT_THROW(pr::DistantLight(V3f(0, 0, 1), 0.5f, s, -1.0f), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------
// AreaLight
// ---------------------------------------------------------------------------------------

namespace {

// Form factor from a differential area to a parallel rectangle of sides x, y at distance c,
// the element's normal through one corner: Howell's catalogue of configuration factors,
// B-3. F = 1/(2π) [X/√(1+X²) atan(Y/√(1+X²)) + Y/√(1+Y²) atan(X/√(1+Y²))], X = x/c, Y = y/c.
double corner_form_factor(double x, double y, double c)
{
    const double X = std::abs(x) / c, Y = std::abs(y) / c;
    const double ax = std::sqrt(1.0 + X * X), ay = std::sqrt(1.0 + Y * Y);
    const double f = (X / ax * std::atan(Y / ax) + Y / ay * std::atan(X / ay)) / (2.0 * kPi);
    // Signed by quadrant, so rectangles add and subtract by superposition
    return (x < 0 ? -f : f) * (y < 0 ? -1.0 : 1.0);
}

// Form factor from an upward-facing element at the origin to the rectangle
// [x0, x1] × [y0, y1] in the plane z = c facing it.
double rectangle_form_factor(double x0, double x1, double y0, double y1, double c)
{
    return corner_form_factor(x1, y1, c) - corner_form_factor(x0, y1, c) -
           corner_form_factor(x1, y0, c) + corner_form_factor(x0, y0, c);
}

// The rectangle [x0, x1] × [y0, y1] at height z facing down (-z), as a fan of four
// triangles of unequal area around an off-centre vertex, so that choosing triangles by
// area matters; no vertex normals (Ng from the winding).
patina::TriangleMesh down_facing_rectangle(float x0, float x1, float y0, float y1, float z)
{
    patina::TriangleMesh m;
    m.name = "lamp";
    m.positions = {V3f(x0 + 0.3f * (x1 - x0), y0 + 0.7f * (y1 - y0), z), V3f(x0, y0, z),
                   V3f(x1, y0, z), V3f(x1, y1, z), V3f(x0, y1, z)};
    // (centre, next corner, corner): clockwise seen from above, so the normal is -z
    m.indices = {0, 2, 1, 0, 3, 2, 0, 4, 3, 0, 1, 4};
    return m;
}

class AreaLightTest : public ::testing::Test {
protected:
    void SetUp() override { registry.load_directory(PATINA_TEST_PLUGIN_DIR); }

    std::shared_ptr<const patina::ShaderInstance> shader(std::string_view type,
                                                         std::string_view params)
    {
        return patina::create_shader_instance(registry, type, toml::parse(params), "lamp");
    }

    // The emitter's radiance along its normal (uniform for the basic Lambertian emitter).
    static SampledSpectrum normal_radiance(const patina::ShaderInstance& e,
                                           const PatinaWavelengths& wl)
    {
        PatinaShadingContext ctx{};
        float out[PATINA_MAX_WAVELENGTHS] = {};
        e.emitter()->emit(e.get(), &ctx, PatinaVec3{0, 0, 1}, &wl, out);
        return SampledSpectrum::from_array(wl.count, out);
    }

    // Irradiance ∫ L cos θ dω on a surface at p with normal n, estimated with sample().
    static SampledSpectrum irradiance(const pr::Light& light, const V3f& p, const V3f& n,
                                      const PatinaWavelengths& wl, int n_samples)
    {
        patina::Pcg32 rng(5);
        double sum[PATINA_MAX_WAVELENGTHS] = {}; // double: a float sum drifts by 1e-3
        for (int k = 0; k < n_samples; ++k) {
            const V2f u(rng.uniform_float(), rng.uniform_float());
            if (const auto ls = light.sample(p, u, wl))
                for (int i = 0; i < wl.count; ++i)
                    sum[i] += ls->L[i] * std::max(0.0f, ls->wi.dot(n)) / ls->pdf;
        }
        SampledSpectrum E(wl.count, 0.0f);
        for (int i = 0; i < wl.count; ++i)
            E[i] = static_cast<float>(sum[i] / n_samples);
        return E;
    }

    patina::PluginRegistry registry{patina::default_host().c_host()};
};

} // namespace

// A point below a uniformly emitting square (coaxial) or rectangle (off-axis, triangles of
// unequal area) receives E = π L F, F the form factor of Howell's B-3 by superposition.
TEST_F(AreaLightTest, IrradianceMatchesTheRectangleFormFactor)
{
    const auto lamp = shader("emitter", "color = [1.0, 0.9, 0.8]\nintensity = 3.0");
    const PatinaWavelengths wl = patina::sample_wavelengths_visible(0.61f, 4);
    const SampledSpectrum L = normal_radiance(*lamp, wl);
    struct Case {
        float x0, x1, y0, y1, c;
        V3f p;
    };
    for (const Case& k : {Case{-1.0f, 1.0f, -1.0f, 1.0f, 1.5f, V3f(0)},
                          Case{-1.0f, 1.0f, -0.5f, 0.5f, 1.0f, V3f(0)},
                          Case{-0.7f, 1.3f, -0.3f, 0.7f, 0.8f, V3f(0)},
                          Case{0.5f, 2.0f, 0.2f, 1.2f, 1.0f, V3f(0)}}) {
        patina::EmbreeScene scene;
        // Shift the lamp instead of the point so that the closed form stays at the origin
        const int id = scene.add_mesh(down_facing_rectangle(k.x0, k.x1, k.y0, k.y1, k.c));
        scene.commit();
        const pr::AreaLight light(scene, id, lamp, patina::default_host().c_host());
        EXPECT_NEAR(light.total_area(), (k.x1 - k.x0) * (k.y1 - k.y0), 1e-5);
        const SampledSpectrum E = irradiance(light, k.p, V3f(0, 0, 1), wl, 100000);
        const double expected = kPi * rectangle_form_factor(k.x0, k.x1, k.y0, k.y1, k.c);
        for (int i = 0; i < wl.count; ++i)
            EXPECT_NEAR(E[i] / L[i], expected, 0.01 * expected)
                << "rectangle [" << k.x0 << ", " << k.x1 << "] x [" << k.y0 << ", " << k.y1
                << "] at " << k.c;
    }
}

// The coaxial square of the catalogue: F = 4 × corner(a/2, a/2) with the plugin's own
// two-triangle quad (vertex normals, uv) subdivided into a 3 x 3 grid.
TEST_F(AreaLightTest, IrradianceUnderASubdividedSquare)
{
    const auto lamp = shader("emitter", "intensity = 2.0");
    const PatinaWavelengths wl = patina::sample_wavelengths_visible(0.13f, 4);
    patina::EmbreeScene scene;
    const float a = 2.0f, h = 1.0f;
    const int id = scene.add_mesh(patina::make_plane(V3f(0, 0, h), a, 3, V3f(0, 0, -1)));
    scene.commit();
    const pr::AreaLight light(scene, id, lamp);
    const SampledSpectrum E = irradiance(light, V3f(0), V3f(0, 0, 1), wl, 100000);
    const SampledSpectrum L = normal_radiance(*lamp, wl);
    // F = 4 F_B3(1, 1) = 0.5541 for a/2 = h (Howell B-3: X = Y = 1)
    const double F = 4.0 * corner_form_factor(a / 2, a / 2, h);
    EXPECT_NEAR(F, 0.5541, 1e-4);
    for (int i = 0; i < wl.count; ++i)
        EXPECT_NEAR(E[i] / L[i], kPi * F, 0.01 * kPi * F);
}

// pdf() at the point a ray along the sampled direction finds equals the density sample()
// reported, as MIS needs.
TEST_F(AreaLightTest, SamplePdfEqualsPdfAtTheHit)
{
    const auto lamp = shader("emitter", "");
    const PatinaWavelengths wl = patina::sample_wavelengths_visible(0.4f, 4);
    patina::EmbreeScene scene;
    const int id = scene.add_mesh(down_facing_rectangle(-0.7f, 1.3f, -0.3f, 0.7f, 0.8f));
    scene.commit();
    const pr::AreaLight light(scene, id, lamp);
    const V3f p(0.1f, -0.2f, 0.0f);
    patina::Pcg32 rng(9);
    for (int k = 0; k < 2000; ++k) {
        const auto ls = light.sample(p, V2f(rng.uniform_float(), rng.uniform_float()), wl);
        ASSERT_TRUE(ls);
        const auto hit = scene.intersect(p, ls->wi);
        ASSERT_TRUE(hit);
        EXPECT_EQ(hit->mesh_id, id);
        EXPECT_NEAR(hit->t, ls->distance, 1e-4f * ls->distance);
        const patina::SurfacePoint sp = scene.interpolate(*hit, p, ls->wi);
        const pr::LightHit lh{sp.P, sp.Ng, sp.prim_id};
        EXPECT_NEAR(light.pdf(p, ls->wi, &lh), ls->pdf, 1e-4f * ls->pdf);
    }
    EXPECT_EQ(light.pdf(p, V3f(0, 0, 1)), 0.0f); // no hit, no density
    EXPECT_FALSE(light.is_infinite());
    EXPECT_TRUE(light.escaped_radiance(V3f(0, 0, 1), wl).is_black());
}

// Behind a one-sided emitter there is nothing to sample; a two-sided one lights both sides
// alike (the mirror point above sees the same irradiance as the point below).
TEST_F(AreaLightTest, BackSideOfAOneSidedEmitterGivesNothing)
{
    const PatinaWavelengths wl = patina::sample_wavelengths_visible(0.8f, 4);
    patina::EmbreeScene scene;
    const int id = scene.add_mesh(down_facing_rectangle(-1.0f, 1.0f, -1.0f, 1.0f, 1.0f));
    scene.commit();
    const pr::AreaLight one_sided(scene, id, shader("emitter", "two_sided = false"));
    const pr::AreaLight two_sided(scene, id, shader("emitter", "two_sided = true"));
    const V3f above(0, 0, 2), below(0, 0, 0);
    patina::Pcg32 rng(2);
    for (int k = 0; k < 1000; ++k) {
        const V2f u(rng.uniform_float(), rng.uniform_float());
        EXPECT_FALSE(one_sided.sample(above, u, wl));
        EXPECT_TRUE(one_sided.sample(below, u, wl));
        EXPECT_TRUE(two_sided.sample(above, u, wl));
    }
    const SampledSpectrum e_below = irradiance(two_sided, below, V3f(0, 0, 1), wl, 20000);
    const SampledSpectrum e_above = irradiance(two_sided, above, V3f(0, 0, -1), wl, 20000);
    for (int i = 0; i < wl.count; ++i)
        EXPECT_NEAR(e_above[i], e_below[i], 1e-3f * e_below[i]);
    // One side emits half the power of two
    EXPECT_NEAR(two_sided.power(), 2.0f * one_sided.power(), 1e-4f * two_sided.power());
}

// A mesh whose triangles are all degenerate (collinear vertices) has no area to sample.
TEST_F(AreaLightTest, ZeroAreaMeshGivesNothing)
{
    patina::TriangleMesh line;
    line.name = "line";
    line.positions = {V3f(0, 0, 1), V3f(1, 0, 1), V3f(2, 0, 1)};
    line.indices = {0, 1, 2};
    patina::EmbreeScene scene;
    const int id = scene.add_mesh(line);
    scene.commit();
    const pr::AreaLight light(scene, id, shader("emitter", ""));
    const PatinaWavelengths wl = patina::sample_wavelengths_visible(0.5f, 4);
    EXPECT_EQ(light.total_area(), 0.0);
    EXPECT_EQ(light.power(), 0.0f);
    EXPECT_FALSE(light.sample(V3f(0), V2f(0.3f, 0.6f), wl));
    const pr::LightHit hit{V3f(0.5f, 0, 1), V3f(0, 0, -1), 0};
    EXPECT_EQ(light.pdf(V3f(0), V3f(0, 0, 1), &hit), 0.0f);
}

TEST_F(AreaLightTest, RejectsAShaderThatIsNotAnEmitter)
{
    patina::EmbreeScene scene;
    const int id = scene.add_mesh(patina::make_quad(V3f(0), 1.0f));
    scene.commit();
    EXPECT_THROW(pr::AreaLight(scene, id, shader("lambert", "")), std::invalid_argument);
    EXPECT_THROW(pr::AreaLight(scene, id, nullptr), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------
// LightSampler
// ---------------------------------------------------------------------------------------

// Lights are chosen in proportion to power(): the pmf says so, sums to 1, and sample()
// follows it. A two-sided lamp of intensity 1 and area 4 has 8/3 the power of a one-sided
// lamp of intensity 3 and area 1.
class LightSamplerTest : public AreaLightTest {};

TEST_F(LightSamplerTest, PmfIsProportionalToPower)
{
    patina::EmbreeScene scene;
    const int small = scene.add_mesh(patina::make_quad(V3f(0, 0, 3), 1.0f, V3f(0, 0, -1)));
    const int big = scene.add_mesh(patina::make_quad(V3f(0, 0, 5), 2.0f, V3f(0, 0, -1)));
    const int plain = scene.add_mesh(patina::make_quad(V3f(0), 10.0f));
    scene.commit();
    std::vector<std::unique_ptr<pr::Light>> lights;
    lights.push_back(
        std::make_unique<pr::AreaLight>(scene, small, shader("emitter", "intensity = 3.0")));
    lights.push_back(std::make_unique<pr::AreaLight>(
        scene, big, shader("emitter", "intensity = 1.0\ntwo_sided = true")));
    auto sun = std::make_unique<pr::DistantLight>(V3f(0, 0, 1), 0.53f, sun_colour(), 2.0f);
    sun->set_scene_radius(1.5f);
    lights.push_back(std::move(sun));
    std::vector<const pr::Light*> raw;
    for (const auto& l : lights)
        raw.push_back(l.get());
    EXPECT_NEAR(raw[1]->power() / raw[0]->power(), 8.0f / 3.0f, 1e-4f);

    const pr::LightSampler sampler(std::move(lights));
    double total_power = 0.0, total_pmf = 0.0;
    for (const pr::Light* l : raw)
        total_power += l->power();
    for (const pr::Light* l : raw) {
        EXPECT_NEAR(sampler.pmf(l), l->power() / total_power, 1e-6);
        total_pmf += sampler.pmf(l);
    }
    EXPECT_NEAR(total_pmf, 1.0, 1e-6);

    // sample() on a fine grid of u hits each light as often as its pmf says
    const int n = 100000;
    std::vector<int> count(raw.size(), 0);
    for (int k = 0; k < n; ++k) {
        const auto s = sampler.sample((k + 0.5f) / n);
        ASSERT_TRUE(s);
        const size_t i =
            static_cast<size_t>(std::find(raw.begin(), raw.end(), s->light) - raw.begin());
        ASSERT_LT(i, raw.size());
        EXPECT_EQ(s->pmf, sampler.pmf(s->light));
        ++count[i];
    }
    for (size_t i = 0; i < raw.size(); ++i)
        EXPECT_NEAR(static_cast<double>(count[i]) / n, sampler.pmf(raw[i]), 1e-4);

    ASSERT_EQ(sampler.infinite_lights().size(), 1u);
    EXPECT_EQ(sampler.infinite_lights()[0], raw[2]);
    EXPECT_EQ(sampler.area_light_for_mesh(small), raw[0]);
    EXPECT_EQ(sampler.area_light_for_mesh(big), raw[1]);
    EXPECT_EQ(sampler.area_light_for_mesh(plain), nullptr);
    EXPECT_EQ(sampler.pmf(nullptr), 0.0f);
}

// The power of a unit white (D65 of luminance 1) is about 1 per unit of π × area: the
// luminance estimate behind power() is close to Y.
TEST(LightSampler, PowerLuminanceOfUnitWhiteIsAboutOne)
{
    const float white[3] = {1.0f, 1.0f, 1.0f};
    const PatinaRgbSpectrum s = patina::default_host().uplift(white, true);
    const PatinaWavelengths wl = pr::power_wavelengths();
    const auto L = SampledSpectrum::from_function(
        wl, [&](float l) { return patina::RgbToSpectrum::eval(s, l); });
    EXPECT_NEAR(pr::power_luminance(L), 1.0f, 0.05f);
}

// With every power 0 the choice is uniform; an empty sampler gives nothing.
TEST(LightSampler, UniformWhenAllPowersAreZero)
{
    std::vector<std::unique_ptr<pr::Light>> lights;
    lights.push_back(std::make_unique<pr::DistantLight>(V3f(0, 0, 1), 0.0f, sun_colour(), 0.0f));
    lights.push_back(std::make_unique<pr::DistantLight>(V3f(0, 1, 0), 1.0f, sun_colour(), 0.0f));
    const pr::Light* first = lights[0].get();
    const pr::Light* second = lights[1].get();
    const pr::LightSampler sampler(std::move(lights));
    EXPECT_FLOAT_EQ(sampler.pmf(first), 0.5f);
    EXPECT_FLOAT_EQ(sampler.pmf(second), 0.5f);
    EXPECT_EQ(sampler.sample(0.25f)->light, first);
    EXPECT_EQ(sampler.sample(0.75f)->light, second);
    EXPECT_EQ(sampler.infinite_lights().size(), 2u);

    EXPECT_FALSE(pr::LightSampler().sample(0.5f));
    EXPECT_EQ(pr::LightSampler().pmf(first), 0.0f);
}

// Every u chooses `light`, with probability 1.
static void expect_always_chosen(const pr::LightSampler& sampler, const pr::Light* light)
{
    for (float u : {0.0f, 0.5f, 0x1.fffffep-1f}) {
        ASSERT_TRUE(sampler.sample(u));
        EXPECT_EQ(sampler.sample(u)->light, light);
        EXPECT_EQ(sampler.sample(u)->pmf, 1.0f);
    }
    EXPECT_EQ(sampler.pmf(light), 1.0f);
}

// One light is chosen with probability 1 whatever its power; a constant environment is the
// uniform sky the integrator evaluates once per path, a map or a sun is not.
TEST(LightSampler, OneLightAndTheUniformSky)
{
    for (float power : {0.0f, 1.0f}) {
        std::vector<std::unique_ptr<pr::Light>> lights;
        lights.push_back(std::make_unique<pr::DistantLight>(V3f(0, 0, 1), 0.0f, sun_colour(), power));
        const pr::Light* sun = lights[0].get();
        const pr::LightSampler sampler(std::move(lights));
        expect_always_chosen(sampler, sun);
        EXPECT_EQ(sampler.pmf(nullptr), 0.0f);
        EXPECT_EQ(sampler.uniform_sky(), nullptr);
    }
    std::vector<std::unique_ptr<pr::Light>> lights;
    lights.push_back(std::make_unique<pr::DistantLight>(V3f(0, 0, 1), 0.0f, sun_colour(), 1.0f));
    lights.push_back(std::make_unique<pr::EnvironmentLight>(patina::default_host(),
                                                            std::array<float, 3>{1, 1, 1}, 1.0f));
    const pr::Light* sky = lights[1].get();
    const pr::LightSampler sampler(std::move(lights));
    EXPECT_EQ(sampler.uniform_sky(), sky);
}

// A uniform sky is left to BSDF sampling by default (pbrt-v4 §12.5.1, UniformInfiniteLight
// under MIS): the other lights share the whole choice, the sky's pmf is 0, and a sky alone
// leaves nothing to sample. With sample_uniform_sky it is chosen by power like the rest.
TEST(LightSampler, UniformSkyLeftToBsdfSamplingUnlessAsked)
{
    auto sun_and_sky = [] {
        std::vector<std::unique_ptr<pr::Light>> lights;
        lights.push_back(
            std::make_unique<pr::DistantLight>(V3f(0, 0, 1), 0.0f, sun_colour(), 1.0f));
        lights.push_back(std::make_unique<pr::EnvironmentLight>(
            patina::default_host(), std::array<float, 3>{1, 1, 1}, 1.0f));
        return lights;
    };
    {
        auto lights = sun_and_sky();
        const pr::Light* sun = lights[0].get();
        const pr::Light* sky = lights[1].get();
        const pr::LightSampler sampler(std::move(lights));
        EXPECT_EQ(sampler.uniform_sky(), sky);
        EXPECT_TRUE(sampler.has_sampled_lights());
        expect_always_chosen(sampler, sun);
        EXPECT_EQ(sampler.pmf(sky), 0.0f);
        EXPECT_EQ(sampler.uniform_sky_pmf(), 0.0f);
        // Rays escaping to the sky still find it.
        EXPECT_EQ(sampler.infinite_lights().size(), 2u);
    }
    {
        // Both powers are positive: both lights are chosen, in proportion to them.
        const pr::LightSampler sampler(sun_and_sky(), true);
        const pr::Light* sun = sampler.lights()[0].get();
        const pr::Light* sky = sampler.lights()[1].get();
        EXPECT_GT(sampler.pmf(sun), 0.0f);
        EXPECT_GT(sampler.pmf(sky), 0.0f);
        EXPECT_FLOAT_EQ(sampler.pmf(sun) + sampler.pmf(sky), 1.0f);
        EXPECT_EQ(sampler.uniform_sky_pmf(), sampler.pmf(sky));
    }
    {
        std::vector<std::unique_ptr<pr::Light>> lights;
        lights.push_back(std::make_unique<pr::EnvironmentLight>(
            patina::default_host(), std::array<float, 3>{1, 1, 1}, 1.0f));
        const pr::LightSampler alone(std::move(lights));
        EXPECT_FALSE(alone.has_sampled_lights());
        EXPECT_FALSE(alone.sample(0.5f));
        EXPECT_EQ(alone.pmf(alone.uniform_sky()), 0.0f);
        EXPECT_EQ(alone.infinite_lights().size(), 1u);
    }
}
