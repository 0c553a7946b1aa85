// CIE tables, colorimetric integration, wavelength sampling and SampledSpectrum.
#include "core/spectrum.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <cstring>

namespace patina {
namespace {

    // clang-format off
// CIE 1931 2° standard colorimetric observer x̄, ȳ, z̄, 360-830 nm every 5 nm
// (ISO 11664-1 / CIE S 014-1; numbers as distributed in Debian colord-data).
constexpr float kCieX[kCieSamples] = {
    0.0001299f, 0.0002321f, 0.0004149f, 0.0007416f, 0.001368f, 0.002236f, 0.004243f, 0.00765f,
    0.01431f, 0.02319f, 0.04351f, 0.07763f, 0.13438f, 0.21477f, 0.2839f, 0.3285f, 0.34828f,
    0.34806f, 0.3362f, 0.3187f, 0.2908f, 0.2511f, 0.19536f, 0.1421f, 0.09564f, 0.05795001f,
    0.03201f, 0.0147f, 0.0049f, 0.0024f, 0.0093f, 0.0291f, 0.06327f, 0.1096f, 0.1655f, 0.2257499f,
    0.2904f, 0.3597f, 0.4334499f, 0.5120501f, 0.5945f, 0.6784f, 0.7621f, 0.8425f, 0.9163f, 0.9786f,
    1.0263f, 1.0567f, 1.0622f, 1.0456f, 1.0026f, 0.9384f, 0.8544499f, 0.7514f, 0.6424f, 0.5419f,
    0.4479f, 0.3608f, 0.2835f, 0.2187f, 0.1649f, 0.1212f, 0.0874f, 0.0636f, 0.04677f, 0.0329f,
    0.0227f, 0.01584f, 0.01135916f, 0.008110916f, 0.005790346f, 0.004109457f, 0.002899327f,
    0.00204919f, 0.001439971f, 0.0009999493f, 0.0006900786f, 0.0004760213f, 0.0003323011f,
    0.0002348261f, 0.0001661505f, 0.000117413f, 0.00008307527f, 0.00005870652f, 0.00004150994f,
    0.00002935326f, 0.00002067383f, 0.00001455977f, 0.00001025398f, 0.000007221456f,
    0.000005085868f, 0.000003581652f, 0.000002522525f, 0.000001776509f, 0.000001251141f,
};
constexpr float kCieY[kCieSamples] = {
    0.000003917f, 0.000006965f, 0.00001239f, 0.00002202f, 0.000039f, 0.000064f, 0.00012f, 0.000217f,
    0.000396f, 0.00064f, 0.00121f, 0.00218f, 0.004f, 0.0073f, 0.0116f, 0.01684f, 0.023f, 0.0298f,
    0.038f, 0.048f, 0.06f, 0.0739f, 0.09098f, 0.1126f, 0.13902f, 0.1693f, 0.20802f, 0.2586f, 0.323f,
    0.4073f, 0.503f, 0.6082f, 0.71f, 0.7932f, 0.862f, 0.9148501f, 0.954f, 0.9803f, 0.9949501f, 1.0f,
    0.995f, 0.9786f, 0.952f, 0.9154f, 0.87f, 0.8163f, 0.757f, 0.6949f, 0.631f, 0.5668f, 0.503f,
    0.4412f, 0.381f, 0.321f, 0.265f, 0.217f, 0.175f, 0.1382f, 0.107f, 0.0816f, 0.061f, 0.04458f,
    0.032f, 0.0232f, 0.017f, 0.01192f, 0.00821f, 0.005723f, 0.004102f, 0.002929f, 0.002091f,
    0.001484f, 0.001047f, 0.00074f, 0.00052f, 0.0003611f, 0.0002492f, 0.0001719f, 0.00012f,
    0.0000848f, 0.00006f, 0.0000424f, 0.00003f, 0.0000212f, 0.00001499f, 0.0000106f, 0.0000074657f,
    0.0000052578f, 0.0000037029f, 0.0000026078f, 0.0000018366f, 0.0000012934f, 0.00000091093f,
    0.00000064153f, 0.00000045181f,
};
constexpr float kCieZ[kCieSamples] = {
    0.0006061f, 0.001086f, 0.001946f, 0.003486f, 0.006450001f, 0.01054999f, 0.02005001f, 0.03621f,
    0.06785001f, 0.1102f, 0.2074f, 0.3713f, 0.6456f, 1.0390501f, 1.3856f, 1.62296f, 1.74706f,
    1.7826f, 1.77211f, 1.7441f, 1.6692f, 1.5281f, 1.28764f, 1.0419f, 0.8129501f, 0.6162f, 0.46518f,
    0.3533f, 0.272f, 0.2123f, 0.1582f, 0.1117f, 0.07824999f, 0.05725001f, 0.04216f, 0.02984f,
    0.0203f, 0.0134f, 0.008749999f, 0.005749999f, 0.0039f, 0.002749999f, 0.0021f, 0.0018f,
    0.001650001f, 0.0014f, 0.0011f, 0.001f, 0.0008f, 0.0006f, 0.00034f, 0.00024f, 0.00019f, 0.0001f,
    0.00004999999f, 0.00003f, 0.00002f, 0.00001f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f,
    0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f,
    0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f,
};
// CIE standard illuminant D65, relative SPD, 360-830 nm every 5 nm, 100 at 560 nm
// (ISO 11664-2 / CIE S 014-2; colord-data stores it divided by 100).
constexpr float kD65[kCieSamples] = {
    46.6383f, 49.3637f, 52.0891f, 51.0323f, 49.9755f, 52.3118f, 54.6482f, 68.7015f, 82.7549f,
    87.1204f, 91.486f, 92.4589f, 93.4318f, 90.057f, 86.6823f, 95.7736f, 104.865f, 110.936f,
    117.008f, 117.41f, 117.812f, 116.336f, 114.861f, 115.392f, 115.923f, 112.367f, 108.811f,
    109.082f, 109.354f, 108.578f, 107.802f, 106.296f, 104.79f, 106.239f, 107.689f, 106.047f,
    104.405f, 104.225f, 104.046f, 102.023f, 100.0f, 98.1671f, 96.3342f, 96.0611f, 95.788f, 92.2368f,
    88.6856f, 89.3459f, 90.0062f, 89.8026f, 89.5991f, 88.6489f, 87.6987f, 85.4936f, 83.2886f,
    83.4939f, 83.6992f, 81.863f, 80.0268f, 80.1207f, 80.2146f, 81.2462f, 82.2778f, 80.281f,
    78.2842f, 74.0027f, 69.7213f, 70.6652f, 71.6091f, 72.979f, 74.349f, 67.9765f, 61.604f, 65.7448f,
    69.8856f, 72.4863f, 75.087f, 69.3398f, 63.5927f, 55.0054f, 46.4182f, 56.6118f, 66.8054f,
    65.0941f, 63.3828f, 63.8434f, 64.304f, 61.8779f, 59.4519f, 55.7054f, 51.959f, 54.6998f,
    57.4406f, 58.8765f, 60.3125f,
};
    // clang-format on

    // x̄, ȳ, z̄ and D65 side by side: one 16-byte load per table node for all four.
    struct CieXyzNode {
        float x, y, z, d65;
    };
    constexpr std::array<CieXyzNode, kCieSamples> kCieXyzNodes = [] {
        std::array<CieXyzNode, kCieSamples> nodes{};
        for (int i = 0; i < kCieSamples; ++i)
            nodes[static_cast<size_t>(i)] = {kCieX[i], kCieY[i], kCieZ[i], kD65[i]};
        return nodes;
    }();

    // Linear interpolation in a 5 nm table; 0 outside 360-830 nm.
    float lerp_table(const float* table, float lambda_nm)
    {
        if (!(lambda_nm >= kLambdaMinNm && lambda_nm <= kLambdaMaxNm))
            return 0.0f;
        float x = (lambda_nm - kLambdaMinNm) / kCieStepNm;
        int i = std::min(static_cast<int>(x), kCieSamples - 2);
        float t = x - static_cast<float>(i);
        return table[i] + t * (table[i + 1] - table[i]);
    }

    // Visible-wavelength importance sampling, pbrt-v4 (Pharr, Jakob, Humphreys 2023,
    // SampleVisibleWavelengths):
    // p(λ) = A / cosh²(k (λ − 538)) on [360, 830]; CDF(λ) = (tanh(k (λ − 538)) − T0) / (T1 − T0)
    // with T0 = tanh(k (360 − 538)), T1 = tanh(k (830 − 538)), so A = k / (T1 − T0).
    constexpr double kVisK = 0.0072;
    constexpr double kVisT0 = -0.856910625469828;
    constexpr double kVisT1MinusT0 = 1.8275019724100978;
    constexpr double kVisA = 0.003939804229324407;

    // Four floats in one SIMD register (GCC/Clang vector extension: SSE on x86-64, NEON on
    // ARM; no -m flags needed), for the four wavelengths a path usually carries.
    using Float4 = float __attribute__((vector_size(16)));
    using Int4 = int32_t __attribute__((vector_size(16)));

    // ln(x) for finite normal x > 0, four at a time: x = m 2^e with m in [sqrt(1/2),
    // sqrt(2)), then Cephes' logf polynomial for ln(m) (Moshier, Cephes Math Library,
    // logf.c; relative error below 2e-7 over that range).
    Float4 log_positive(Float4 x)
    {
        const Int4 bits = std::bit_cast<Int4>(x);
        const Int4 mantissa = (bits & 0x007fffff) | 0x3f000000;  // m in [0.5, 1)
        Float4 m = std::bit_cast<Float4>(mantissa);
        Float4 e = __builtin_convertvector((bits >> 23) - 126, Float4);
        const Int4 low = m < 0.707106781186547524f;
        e = low ? e - 1.0f : e;
        m = (low ? m + m : m) - 1.0f;
        const Float4 z = m * m;
        Float4 y = m * 7.0376836292e-2f - 1.1514610310e-1f;
        y = y * m + 1.1676998740e-1f;
        y = y * m - 1.2420140846e-1f;
        y = y * m + 1.4249322787e-1f;
        y = y * m - 1.6668057665e-1f;
        y = y * m + 2.0000714765e-1f;
        y = y * m - 2.4999993993e-1f;
        y = y * m + 3.3333331174e-1f;
        y = y * m * z;
        // ln 2 in two parts (0.693359375 is exact in float) for the exponent's share.
        y += e * -2.12194440e-4f;
        y += z * -0.5f;
        return m + y + e * 0.693359375f;
    }

    // frac(u + i/count): hero-wavelength rotation of one uniform number.
    float rotate_u(float u, int i, int count)
    {
        float ui = u + static_cast<float>(i) / static_cast<float>(count);
        if (ui >= 1.0f)
            ui -= 1.0f;
        return std::clamp(ui, 0.0f, 0x1.fffffep-1f);
    }

} // namespace

float cie_x(float lambda_nm)
{
    return lerp_table(kCieX, lambda_nm);
}
float cie_y(float lambda_nm)
{
    return lerp_table(kCieY, lambda_nm);
}
float cie_z(float lambda_nm)
{
    return lerp_table(kCieZ, lambda_nm);
}
float d65(float lambda_nm)
{
    return lerp_table(kD65, lambda_nm);
}

float illuminant_a(float lambda_nm)
{
    // CIE 15:2004, definition of illuminant A: S_A(λ) = 100 (560/λ)^5 (exp(c2/(2848·560)) − 1) /
    // (exp(c2/(2848 λ)) − 1) with c2 = 1.435e7 nm·K (the value fixed in the definition, not today's
    // CODATA c2).
    if (!(lambda_nm > 0.0f))
        return 0.0f;
    const double l = lambda_nm;
    const double c2 = 1.435e7;
    const double num = std::expm1(c2 / (2848.0 * 560.0));
    const double den = std::expm1(c2 / (2848.0 * l));
    return static_cast<float>(100.0 * std::pow(560.0 / l, 5.0) * num / den);
}

Xyz spectrum_to_xyz(const SpectrumFn& reflectance, const SpectrumFn& illuminant)
{
    // Trapezoid rule on a 1 nm grid (the tables are linear between their 5 nm samples).
    Xyz xyz = {0.0, 0.0, 0.0};
    double white_y = 0.0;
    for (int i = 0; i <= 470; ++i) {
        const float l = kLambdaMinNm + static_cast<float>(i);
        const double w = (i == 0 || i == 470) ? 0.5 : 1.0;
        const double e = w * illuminant(l);
        const double r = reflectance(l);
        xyz[0] += e * r * cie_x(l);
        xyz[1] += e * r * cie_y(l);
        xyz[2] += e * r * cie_z(l);
        white_y += e * cie_y(l);
    }
    if (white_y <= 0.0)
        return {0.0, 0.0, 0.0};
    for (double& c : xyz)
        c /= white_y;
    return xyz;
}

Xyz emission_to_xyz(const SpectrumFn& radiance)
{
    Xyz xyz = {0.0, 0.0, 0.0};
    for (int i = 0; i <= 470; ++i) {
        const float l = kLambdaMinNm + static_cast<float>(i);
        const double e = ((i == 0 || i == 470) ? 0.5 : 1.0) * radiance(l);
        xyz[0] += e * cie_x(l);
        xyz[1] += e * cie_y(l);
        xyz[2] += e * cie_z(l);
    }
    for (double& c : xyz)
        c /= kCieYIntegral;
    return xyz;
}

float visible_wavelength_pdf(float lambda_nm)
{
    if (!(lambda_nm >= kLambdaMinNm && lambda_nm <= kLambdaMaxNm))
        return 0.0f;
    // 1/cosh² = 1 − tanh², in float: this runs for every wavelength of every sample.
    const float t = std::tanh(static_cast<float>(kVisK) * (lambda_nm - 538.0f));
    return static_cast<float>(kVisA) * (1.0f - t * t);
}

float sample_visible_wavelength(float u)
{
    // Invert the CDF above: λ = 538 + atanh(T0 + u (T1 − T0)) / k.
    const float t = static_cast<float>(kVisT0) + u * static_cast<float>(kVisT1MinusT0);
    const float l = 538.0f + std::atanh(t) / static_cast<float>(kVisK);
    return std::clamp(l, kLambdaMinNm, kLambdaMaxNm);
}

PatinaWavelengths sample_wavelengths_visible(float u, int count)
{
    assert(count >= 1 && count <= PATINA_MAX_WAVELENGTHS);
    PatinaWavelengths wl{};
    wl.count = count;
    for (int i = 0; i < count; ++i)
        wl.lambda_nm[i] = sample_visible_wavelength(rotate_u(u, i, count));
    return wl;
}

PatinaWavelengths sample_wavelengths_visible(float u, int count, SampledSpectrum& pdf)
{
    assert(count >= 1 && count <= PATINA_MAX_WAVELENGTHS);
    PatinaWavelengths wl{};
    wl.count = count;
    pdf = SampledSpectrum(count, 0.0f);
    const float step = 1.0f / static_cast<float>(count);
    // Four wavelengths at a time, in SIMD registers.
    for (int first = 0; first < count; first += 4) {
        const Float4 lane = {0.0f, 1.0f, 2.0f, 3.0f};
        // frac(u + i/count), as rotate_u.
        Float4 ui = u + (lane + static_cast<float>(first)) * step;
        ui = ui >= 1.0f ? ui - 1.0f : ui;
        ui = ui < 0.0f ? 0.0f : ui;
        ui = ui > 0x1.fffffep-1f ? 0x1.fffffep-1f : ui;
        // λ = 538 + atanh(t)/k with atanh(t) = ln((1 + t)/(1 − t)) / 2; and since
        // tanh(k(λ − 538)) = t, the pdf A/cosh² is A(1 − t²): no tanh needed.
        const Float4 t = static_cast<float>(kVisT0) + ui * static_cast<float>(kVisT1MinusT0);
        Float4 l = 538.0f + log_positive((1.0f + t) / (1.0f - t)) * static_cast<float>(0.5 / kVisK);
        l = l < kLambdaMinNm ? kLambdaMinNm : l;
        l = l > kLambdaMaxNm ? kLambdaMaxNm : l;
        const Float4 density = static_cast<float>(kVisA) * (1.0f - t * t);
        for (int i = 0; i < 4 && first + i < count; ++i) {
            wl.lambda_nm[first + i] = l[i];
            pdf.v[first + i] = density[i];
        }
    }
    return wl;
}

namespace {

    // One step j of the tabulated inverse CDF: λ from lambda to lambda + width as u goes
    // over [j/N, (j+1)/N), with density pdf = 1 / (N width) there. 16 bytes: one load.
    struct WavelengthStep {
        float lambda, width, pdf, unused;
    };

    // Nodes at u = j/N of the analytic inverse CDF (pbrt-v4's, above), in double.
    std::array<WavelengthStep, kWavelengthTableSize> make_wavelength_table()
    {
        constexpr int n = kWavelengthTableSize;
        std::array<double, n + 1> node{};
        for (int j = 0; j <= n; ++j) {
            const double t = kVisT0 + (static_cast<double>(j) / n) * kVisT1MinusT0;
            node[static_cast<size_t>(j)] = 538.0 + std::atanh(t) / kVisK;
        }
        node[0] = kLambdaMinNm;  // atanh rounding at the ends
        node[n] = kLambdaMaxNm;
        std::array<WavelengthStep, n> table{};
        for (int j = 0; j < n; ++j) {
            WavelengthStep& step = table[static_cast<size_t>(j)];
            step.lambda = static_cast<float>(node[static_cast<size_t>(j)]);
            const float end = static_cast<float>(node[static_cast<size_t>(j) + 1]);
            step.width = end - step.lambda;
            step.pdf = static_cast<float>(1.0 / (n * static_cast<double>(step.width)));
        }
        return table;
    }
    // Built at load time (no guard per call).
    const std::array<WavelengthStep, kWavelengthTableSize> kWavelengthTable =
        make_wavelength_table();

} // namespace

namespace {

    // Four lanes of sample_wavelengths_tabulated: s = N frac(u + i/count) for lanes
    // i = first .. first + 3, the step is the integer part of s, the place in it the rest.
    [[gnu::always_inline]] inline void tabulated_block(float u, int first, float stride,
                                                       Float4& lambda, Float4& density)
    {
        constexpr float n = static_cast<float>(kWavelengthTableSize);
        const Float4 lane = {0.0f, 1.0f, 2.0f, 3.0f};
        Float4 s = u * n + (lane + static_cast<float>(first)) * stride;
        s = s >= n ? s - n : s;
        s = s < 0.0f ? 0.0f : s;
        Int4 j = __builtin_convertvector(s, Int4);
        j = j < kWavelengthTableSize - 1 ? j : kWavelengthTableSize - 1;
        const Float4 f = s - __builtin_convertvector(j, Float4);
        Float4 rows[4];
        for (int i = 0; i < 4; ++i)
            std::memcpy(&rows[i], &kWavelengthTable[static_cast<size_t>(j[i])], sizeof rows[i]);
        // Transpose the four steps into lambda, width and pdf lanes.
        const Float4 t0 = __builtin_shufflevector(rows[0], rows[1], 0, 4, 1, 5);  // l0 l1 w0 w1
        const Float4 t1 = __builtin_shufflevector(rows[2], rows[3], 0, 4, 1, 5);  // l2 l3 w2 w3
        const Float4 t2 = __builtin_shufflevector(rows[0], rows[1], 2, 6, 2, 6);  // p0 p1
        const Float4 t3 = __builtin_shufflevector(rows[2], rows[3], 2, 6, 2, 6);  // p2 p3
        const Float4 start = __builtin_shufflevector(t0, t1, 0, 1, 4, 5);
        const Float4 width = __builtin_shufflevector(t0, t1, 2, 3, 6, 7);
        density = __builtin_shufflevector(t2, t3, 0, 1, 4, 5);
        lambda = start + f * width;
        lambda = lambda > kLambdaMaxNm ? kLambdaMaxNm : lambda;
    }

} // namespace

PatinaWavelengths sample_wavelengths_tabulated(float u, int count, SampledSpectrum& pdf)
{
    assert(count >= 1 && count <= PATINA_MAX_WAVELENGTHS);
    PatinaWavelengths wl{};
    wl.count = count;
    pdf = SampledSpectrum(count, 0.0f);
    const float stride = static_cast<float>(kWavelengthTableSize) / static_cast<float>(count);
    for (int first = 0; first < count; first += 4) {
        Float4 l, density;
        tabulated_block(u, first, stride, l, density);
        if (first + 4 <= count) {
            std::memcpy(wl.lambda_nm + first, &l, sizeof l);
            std::memcpy(pdf.v + first, &density, sizeof density);
        } else {
            for (int i = 0; first + i < count; ++i) {
                wl.lambda_nm[first + i] = l[i];
                pdf.v[first + i] = density[i];
            }
        }
    }
    return wl;
}

float tabulated_wavelength_pdf(float lambda_nm)
{
    if (!(lambda_nm >= kLambdaMinNm && lambda_nm <= kLambdaMaxNm))
        return 0.0f;
    // The last step starting at or below λ.
    const auto after = std::upper_bound(
        kWavelengthTable.begin() + 1, kWavelengthTable.end(), lambda_nm,
        [](float l, const WavelengthStep& step) { return l < step.lambda; });
    return (after - 1)->pdf;
}

float uniform_wavelength_pdf(float lambda_nm)
{
    if (!(lambda_nm >= kLambdaMinNm && lambda_nm <= kLambdaMaxNm))
        return 0.0f;
    return 1.0f / (kLambdaMaxNm - kLambdaMinNm);
}

PatinaWavelengths sample_wavelengths_uniform(float u, int count)
{
    assert(count >= 1 && count <= PATINA_MAX_WAVELENGTHS);
    PatinaWavelengths wl{};
    wl.count = count;
    for (int i = 0; i < count; ++i) {
        const float ui = rotate_u(u, i, count);
        wl.lambda_nm[i] = kLambdaMinNm + ui * (kLambdaMaxNm - kLambdaMinNm);
    }
    return wl;
}

float SampledSpectrum::average() const
{
    if (count == 0)
        return 0.0f;
    float sum = 0.0f;
    for (int i = 0; i < count; ++i)
        sum += v[i];
    return sum / static_cast<float>(count);
}

float SampledSpectrum::min_value() const
{
    if (count == 0)
        return 0.0f;
    return *std::min_element(v, v + count);
}

SampledSpectrum exp(const SampledSpectrum& s)
{
    SampledSpectrum r = s;
    for (int i = 0; i < r.count; ++i)
        r.v[i] = std::exp(s.v[i]);
    return r;
}

SampledSpectrum sqrt(const SampledSpectrum& s)
{
    SampledSpectrum r = s;
    for (int i = 0; i < r.count; ++i)
        r.v[i] = std::sqrt(std::max(s.v[i], 0.0f));
    return r;
}

SampledSpectrum visible_wavelength_pdf(const PatinaWavelengths& wl)
{
    return SampledSpectrum::from_function(wl, [](float l) { return visible_wavelength_pdf(l); });
}

Xyz xyz_from_samples(const SampledSpectrum& L, const PatinaWavelengths& wl,
                     const SampledSpectrum& pdf)
{
    // Monte Carlo estimate of ∫ L x̄ dλ / ∫ ȳ dλ: one sample per wavelength, averaged (in
    // float: a handful of terms per sample; the film sums the samples in double).
    if (L.count == 0)
        return {0.0, 0.0, 0.0};
    float x = 0.0f, y = 0.0f, z = 0.0f;
    for (int i = 0; i < L.count; ++i) {
        // Terminated secondary wavelengths and wavelengths outside the tables count as 0.
        const float lambda = wl.lambda_nm[i];
        if (pdf.v[i] == 0.0f || !(lambda >= kLambdaMinNm && lambda <= kLambdaMaxNm))
            continue;
        // One table position for the three matching functions.
        const float p = (lambda - kLambdaMinNm) / kCieStepNm;
        const int k = std::min(static_cast<int>(p), kCieSamples - 2);
        const float f = p - static_cast<float>(k);
        const CieXyzNode& a = kCieXyzNodes[k];
        const CieXyzNode& b = kCieXyzNodes[k + 1];
        const float w = L.v[i] / pdf.v[i];
        x += w * (a.x + f * (b.x - a.x));
        y += w * (a.y + f * (b.y - a.y));
        z += w * (a.z + f * (b.z - a.z));
    }
    const double norm = 1.0 / (static_cast<double>(L.count) * kCieYIntegral);
    return {x * norm, y * norm, z * norm};
}

namespace {

    // x̄, ȳ, z̄ and D65 at four wavelengths: lerp_table's position of each (the same float
    // operations, in SIMD lanes), one SIMD lerp of the two (x̄, ȳ, z̄, D65) nodes per
    // wavelength, then a 4x4 transpose. Lanes not `valid` come out 0.
    [[gnu::always_inline]] inline void cie_block(Float4 lambda, Int4 valid, Float4& x, Float4& y,
                                                 Float4& z, Float4& d)
    {
        const Float4 p = (lambda - kLambdaMinNm) / kCieStepNm;
        Int4 k = __builtin_convertvector(p, Int4);
        k = k < kCieSamples - 2 ? k : kCieSamples - 2;
        k = valid ? k : 0;  // any node: the lane is masked below
        const Float4 f = p - __builtin_convertvector(k, Float4);
        Float4 rows[4];
        for (int i = 0; i < 4; ++i) {
            Float4 a, b;
            std::memcpy(&a, &kCieXyzNodes[static_cast<size_t>(k[i])], sizeof a);
            std::memcpy(&b, &kCieXyzNodes[static_cast<size_t>(k[i]) + 1], sizeof b);
            rows[i] = a + f[i] * (b - a);
        }
        const Float4 t0 = __builtin_shufflevector(rows[0], rows[1], 0, 4, 1, 5);  // x0 x1 y0 y1
        const Float4 t1 = __builtin_shufflevector(rows[2], rows[3], 0, 4, 1, 5);  // x2 x3 y2 y3
        const Float4 t2 = __builtin_shufflevector(rows[0], rows[1], 2, 6, 3, 7);  // z0 z1 d0 d1
        const Float4 t3 = __builtin_shufflevector(rows[2], rows[3], 2, 6, 3, 7);  // z2 z3 d2 d3
        const Float4 zero = {};
        x = valid ? __builtin_shufflevector(t0, t1, 0, 1, 4, 5) : zero;
        y = valid ? __builtin_shufflevector(t0, t1, 2, 3, 6, 7) : zero;
        z = valid ? __builtin_shufflevector(t2, t3, 0, 1, 4, 5) : zero;
        d = valid ? __builtin_shufflevector(t2, t3, 2, 3, 6, 7) : zero;
    }

    // Store four lanes of a spectrum of `count` lanes whose other lanes are 0.
    void store_first_block(SampledSpectrum& s, int count, Float4 block)
    {
        const Float4 zero = {};
        s.count = count;
        std::memcpy(s.v, &block, sizeof block);
        for (int b = 4; b < SampledSpectrum::kLanes; b += 4)
            std::memcpy(s.v + b, &zero, sizeof zero);
    }

} // namespace

CieAtWavelengths cie_at_wavelengths(const PatinaWavelengths& wl)
{
    static_assert(PATINA_MAX_WAVELENGTHS % 4 == 0, "whole blocks of four lanes");
    CieAtWavelengths cie;  // all entries 0
    cie.x.count = cie.y.count = cie.z.count = cie.d65.count = wl.count;
    // Four wavelengths at a time; lanes past the count or outside the tables stay 0.
    for (int first = 0; first < wl.count; first += 4) {
        const Float4 lane = {0.0f, 1.0f, 2.0f, 3.0f};
        Float4 lambda;
        std::memcpy(&lambda, wl.lambda_nm + first, sizeof lambda);
        const Int4 valid = (lambda >= kLambdaMinNm) & (lambda <= kLambdaMaxNm) &
                           (lane + static_cast<float>(first) < static_cast<float>(wl.count));
        Float4 x, y, z, d;
        cie_block(lambda, valid, x, y, z, d);
        std::memcpy(cie.x.v + first, &x, sizeof x);
        std::memcpy(cie.y.v + first, &y, sizeof y);
        std::memcpy(cie.z.v + first, &z, sizeof z);
        std::memcpy(cie.d65.v + first, &d, sizeof d);
    }
    return cie;
}

// AVX2 and baseline clones, chosen at load time (VEX encoding: fewer register copies). No
// FMA in either, so both round alike: the same bits.
namespace {

    // Four wavelengths, the renderer's usual count: one block, straight through, every
    // lane inside the tables (the table's λ stay in 360-830 nm).
    [[gnu::always_inline]] inline void set_up_four(float u, PatinaWavelengths& wl,
                                                   SampledSpectrum& pdf, CieAtWavelengths& cie)
    {
        Float4 l, density;
        tabulated_block(u, 0, static_cast<float>(kWavelengthTableSize) / 4.0f, l, density);
        wl.count = 4;
        const Float4 zero = {};
        std::memcpy(wl.lambda_nm, &l, sizeof l);
        for (int b = 4; b < PATINA_MAX_WAVELENGTHS; b += 4)
            std::memcpy(wl.lambda_nm + b, &zero, sizeof zero);
        store_first_block(pdf, 4, density);
        Float4 x, y, z, d;
        cie_block(l, l >= kLambdaMinNm, x, y, z, d);
        store_first_block(cie.x, 4, x);
        store_first_block(cie.y, 4, y);
        store_first_block(cie.z, 4, z);
        store_first_block(cie.d65, 4, d);
    }

} // namespace

[[gnu::target_clones("avx2", "default")]]
void sample_wavelengths_tabulated(float u, int count, PatinaWavelengths& wl,
                                  SampledSpectrum& pdf, CieAtWavelengths& cie)
{
    if (count != 4) {
        wl = sample_wavelengths_tabulated(u, count, pdf);
        cie = cie_at_wavelengths(wl);
        return;
    }
    set_up_four(u, wl, pdf, cie);
}

[[gnu::target_clones("avx2", "default")]]  // as sample_wavelengths_tabulated
void sample_wavelengths_tabulated4(std::span<const float> u, std::span<const SpectralSetUp> out)
{
    assert(u.size() == out.size());
    // Two samples per turn, written one after the other in one block: each is a chain of
    // dependent look-ups (table step, then the CIE nodes at its λ), and two independent
    // chains side by side keep the core busy while either waits.
    size_t i = 0;
    for (; i + 2 <= u.size(); i += 2) {
        set_up_four(u[i], *out[i].wl, *out[i].pdf, *out[i].cie);
        set_up_four(u[i + 1], *out[i + 1].wl, *out[i + 1].pdf, *out[i + 1].cie);
    }
    if (i < u.size())
        set_up_four(u[i], *out[i].wl, *out[i].pdf, *out[i].cie);
}

[[gnu::target_clones("avx2", "default")]]  // as sample_wavelengths_tabulated
Xyz xyz_from_samples(const SampledSpectrum& L, const CieAtWavelengths& cie,
                     const SampledSpectrum& pdf)
{
    // As above: terminated wavelengths (pdf 0) count as 0, the average is over L.count.
    if (L.count == 0)
        return {0.0, 0.0, 0.0};
    // In whole blocks of four lanes up to the count: the lanes past it hold 0 in L, pdf and
    // the tables, so they add 0 (L / pdf gives 0 for a zero pdf).
    Float4 x = {}, y = {}, z = {};
    for (int b = 0; b < L.count; b += 4) {
        Float4 l, p, cx, cy, cz;
        std::memcpy(&l, L.v + b, sizeof l);
        std::memcpy(&p, pdf.v + b, sizeof p);
        std::memcpy(&cx, cie.x.v + b, sizeof cx);
        std::memcpy(&cy, cie.y.v + b, sizeof cy);
        std::memcpy(&cz, cie.z.v + b, sizeof cz);
        const Float4 w = p != 0.0f ? l / p : Float4{};
        x += w * cx;
        y += w * cy;
        z += w * cz;
    }
    const double norm = 1.0 / (static_cast<double>(L.count) * kCieYIntegral);
    return {((x[0] + x[1]) + (x[2] + x[3])) * norm, ((y[0] + y[1]) + (y[2] + y[3])) * norm,
            ((z[0] + z[1]) + (z[2] + z[3])) * norm};
}

Xyz xyz_from_samples(const SampledSpectrum& L, const PatinaWavelengths& wl)
{
    return xyz_from_samples(L, wl, visible_wavelength_pdf(wl));
}

} // namespace patina
