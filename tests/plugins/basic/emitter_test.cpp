// emitter: radiance = intensity × the host's illuminant uplift of the colour (white: D65
// normalised at 560 nm), black on the back side unless two-sided, bad values refused.
#include "basic_plugin.h"

namespace patina::test {
namespace {

    class Emitter {
    public:
        explicit Emitter(const ParamSet& params)
            : instance_(shader("emitter"), params), color_(params.data()[0].color)
        {
            ctx_.mode = PATINA_TRANSPORT_RADIANCE;
        }
        explicit operator bool() const { return static_cast<bool>(instance_); }
        std::array<float, PATINA_MAX_WAVELENGTHS> radiance(Vec3 wo,
                                                           const PatinaWavelengths& wl) const
        {
            std::array<float, PATINA_MAX_WAVELENGTHS> out;
            out.fill(-1.0f);
            shader("emitter").emitter->emit(instance_.get(), &ctx_, wo, &wl, out.data());
            return out;
        }
        const PatinaRgbSpectrum& color() const { return color_; }

    private:
        Instance instance_;
        PatinaRgbSpectrum color_;
        PatinaShadingContext ctx_{};
    };

    TEST(Emitter, WhiteEmitsIntensityTimesD65)
    {
        ParamSet params(shader("emitter"));
        params.set_float("intensity", 3.0f);
        const Emitter e(params);
        ASSERT_TRUE(e);
        // The colour was uplifted as an illuminant (declared max > 1)
        EXPECT_EQ(e.color().illuminant, 1);
        const PatinaWavelengths wl =
            wavelengths({360.0f, 400.0f, 450.0f, 560.0f, 600.0f, 700.0f, 780.0f, 830.0f});
        for (const Vec3 wo : {Vec3(0, 0, 1), direction(1.2f, 0.4f), direction(1.55f, 3.0f)}) {
            const auto l = e.radiance(wo, wl);
            for (int i = 0; i < wl.count; ++i) {
                // CIE D65 relative SPD / 100 (CIE 15:2004 Table T.1; 100 at 560 nm)
                EXPECT_NEAR(l[i], 3.0f * d65_normalised(wl.lambda_nm[i]), 1e-5f)
                    << wl.lambda_nm[i] << " nm";
            }
            EXPECT_FLOAT_EQ(l[3], 3.0f);                // 560 nm: exactly the intensity
            EXPECT_NEAR(l[1], 3.0f * 0.827549f, 1e-5f); // D65(400 nm) = 82.7549
        }
        // Only `count` entries are written
        const auto l = e.radiance(Vec3(0, 0, 1), wavelengths({500.0f, 600.0f}));
        EXPECT_EQ(l[2], -1.0f);
    }

    TEST(Emitter, ColourComesFromTheHostsUplift)
    {
        ParamSet params(shader("emitter"));
        params.set_color("color", 4.0f, 1.0f, 0.25f).set_float("intensity", 0.5f);
        const Emitter e(params);
        ASSERT_TRUE(e);
        const PatinaWavelengths wl = wavelengths();
        const auto l = e.radiance(direction(0.3f, 0.0f), wl);
        for (int i = 0; i < wl.count; ++i)
            EXPECT_NEAR(l[i], 0.5f * TestHost::eval(e.color(), wl.lambda_nm[i]), 1e-5f)
                << wl.lambda_nm[i];
        // Red emitter: more at 650 nm than at 450 nm
        const auto rb = e.radiance(Vec3(0, 0, 1), wavelengths({650.0f, 450.0f}));
        EXPECT_GT(rb[0], 4.0f * rb[1]);
    }

    TEST(Emitter, BackSideIsBlackUnlessTwoSided)
    {
        const PatinaWavelengths wl = wavelengths();
        const Vec3 back = direction(2.0f, 1.0f), front = direction(1.0f, 1.0f);
        ParamSet one(shader("emitter"));
        const Emitter one_sided(one);
        const auto lb = one_sided.radiance(back, wl);
        for (int i = 0; i < wl.count; ++i)
            EXPECT_EQ(lb[i], 0.0f);
        EXPECT_GT(one_sided.radiance(front, wl)[0], 0.0f);

        ParamSet two(shader("emitter"));
        two.set_bool("two_sided", true);
        const Emitter two_sided(two);
        const auto lf = two_sided.radiance(front, wl), lb2 = two_sided.radiance(back, wl);
        for (int i = 0; i < wl.count; ++i) {
            EXPECT_GT(lb2[i], 0.0f);
            EXPECT_EQ(lb2[i], lf[i]);
        }
    }

    TEST(Emitter, ZeroIntensityIsBlack)
    {
        ParamSet params(shader("emitter"));
        params.set_float("intensity", 0.0f);
        const Emitter e(params);
        ASSERT_TRUE(e);
        const auto l = e.radiance(Vec3(0, 0, 1), wavelengths());
        for (int i = 0; i < 8; ++i)
            EXPECT_EQ(l[i], 0.0f);
    }

    TEST(Emitter, RejectsWhatItCannotHonour)
    {
        const PatinaShaderDesc& desc = shader("emitter");
        auto expect_rejected = [&](ParamSet& params, const char* mentions) {
            Instance instance(desc, params);
            EXPECT_FALSE(instance) << mentions;
            ASSERT_FALSE(test_host().errors.empty()) << mentions << ": no error message";
            EXPECT_NE(test_host().errors.front().find(mentions), std::string::npos)
                << test_host().errors.front();
        };
        {
            ParamSet p(desc);
            p.set_float("intensity", -1.0f);
            expect_rejected(p, "intensity");
        }
        {
            ParamSet p(desc);
            p.set_float("intensity", std::nanf(""));
            expect_rejected(p, "intensity");
        }
        {
            ParamSet p(desc);
            p.set_float("intensity", INFINITY);
            expect_rejected(p, "intensity");
        }
        {
            ParamSet p(desc);
            p.set_color("color", -0.5f, 1.0f, 1.0f);
            expect_rejected(p, "color");
        }
        {
            ParamSet p(desc);
            p.set_color_spectrum("color", PatinaRgbSpectrum{0.0f, 0.0f, 0.0f, -2.0f, 1});
            expect_rejected(p, "color");
        }
        {
            // A host without eval_rgb_spectrum cannot serve this shader
            TestHost bare;
            bare.eval_rgb_spectrum = nullptr;
            ParamSet p(desc);
            void* instance = desc.create(&bare, p.data());
            EXPECT_EQ(instance, nullptr);
            ASSERT_EQ(bare.errors.size(), 1u);
            EXPECT_NE(bare.errors[0].find("eval_rgb_spectrum"), std::string::npos);
            if (instance)
                desc.destroy(instance);
        }
    }

} // namespace
} // namespace patina::test
