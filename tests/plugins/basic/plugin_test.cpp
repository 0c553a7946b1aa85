// The basic plugin as a host sees it: symbols, version, descriptor table, parameter metadata
// and defaults that create instances (docs/shaders.md, generated from the metadata, is
// checked by cli.shader_reference).
#include "basic_plugin.h"

#include <cmath>
#include <cstdio>
#include <regex>
#include <set>

namespace patina::test {
namespace {

    TEST(BasicPlugin, LoadsWithTheHostsAbiVersion)
    {
        const LoadedPlugin& p = basic_plugin();
        ASSERT_TRUE(p.info) << p.error;
        ASSERT_TRUE(p.abi_version);
        EXPECT_EQ(*p.abi_version, PATINA_ABI_VERSION);
        EXPECT_STREQ(p.info->plugin_name, "basic");
        ASSERT_TRUE(p.info->plugin_version);
        // RTLD_LOCAL and hidden visibility: the shaders' C++ symbols are not exported
        EXPECT_EQ(dlsym(p.handle, "_ZN6patina5basic14lambert_shaderEv"), nullptr);
    }

    TEST(BasicPlugin, DeclaresItsShadersWithTheirFunctionTables)
    {
        const LoadedPlugin& p = basic_plugin();
        ASSERT_TRUE(p.info) << p.error;
        ASSERT_EQ(p.info->shader_count, 5);
        const std::pair<const char*, PatinaShaderKind> expected[] = {
            {"lambert", PATINA_SHADER_BSDF},
            {"conductor", PATINA_SHADER_BSDF},
            {"dielectric", PATINA_SHADER_BSDF},
            {"emitter", PATINA_SHADER_EMITTER},
            {"homogeneous", PATINA_SHADER_MEDIUM}};
        for (const auto& [name, kind] : expected) {
            const PatinaShaderDesc& s = shader(name);
            EXPECT_EQ(s.kind, kind) << name;
            EXPECT_TRUE(s.help && *s.help) << name;
            EXPECT_TRUE(s.create && s.destroy) << name;
            EXPECT_EQ(s.texture, nullptr) << name;
            // Exactly the table of its kind is set.
            EXPECT_EQ(s.bsdf != nullptr, kind == PATINA_SHADER_BSDF) << name;
            EXPECT_EQ(s.emitter != nullptr, kind == PATINA_SHADER_EMITTER) << name;
            EXPECT_EQ(s.medium != nullptr, kind == PATINA_SHADER_MEDIUM) << name;
            if (s.bsdf) {
                EXPECT_TRUE(s.bsdf->eval && s.bsdf->pdf && s.bsdf->sample) << name;
            }
            if (s.emitter) {
                EXPECT_TRUE(s.emitter->emit) << name;
            }
            if (s.medium) {
                EXPECT_TRUE(s.medium->sample_distance && s.medium->transmittance &&
                            s.medium->phase_eval && s.medium->phase_sample)
                    << name;
            }
        }
    }

    TEST(BasicPlugin, EveryParameterHasCompleteMetadata)
    {
        const LoadedPlugin& p = basic_plugin();
        ASSERT_TRUE(p.info) << p.error;
        const std::regex identifier("[a-z_][a-z0-9_]*");
        for (int si = 0; si < p.info->shader_count; ++si) {
            const PatinaShaderDesc& s = p.info->shaders[si];
            EXPECT_TRUE(std::regex_match(s.name, identifier)) << s.name;
            std::set<std::string> names;
            for (int i = 0; i < s.param_count; ++i) {
                const PatinaParamDecl& d = s.params[i];
                SCOPED_TRACE(std::string(s.name) + "." + d.name);
                EXPECT_TRUE(std::regex_match(d.name, identifier));
                EXPECT_TRUE(names.insert(d.name).second) << "duplicate parameter";
                ASSERT_TRUE(d.help && *d.help);
                ASSERT_TRUE(d.colorspace);
                EXPECT_LE(d.min_value, d.max_value);
                if (d.type == PATINA_PARAM_COLOR) {
                    EXPECT_STRNE(d.colorspace, "");
                    for (float v : d.default_value) {
                        EXPECT_GE(v, d.min_value);
                        EXPECT_LE(v, d.max_value);
                    }
                }
                if (d.type == PATINA_PARAM_FLOAT) {
                    EXPECT_GE(d.default_value[0], d.min_value);
                    EXPECT_LE(d.default_value[0], d.max_value);
                }
                if (d.type == PATINA_PARAM_SPECTRUM && d.default_spectrum) {
                    const PatinaTabulatedSpectrum& t = *d.default_spectrum;
                    ASSERT_GE(t.count, 2);
                    // The default table spans the host's wavelength range
                    EXPECT_LE(t.lambda_nm[0], PATINA_LAMBDA_MIN_NM);
                    EXPECT_GE(t.lambda_nm[t.count - 1], PATINA_LAMBDA_MAX_NM);
                    for (int k = 0; k < t.count; ++k) {
                        EXPECT_GE(t.value[k], d.min_value);
                        EXPECT_LE(t.value[k], d.max_value);
                        if (k > 0) {
                            EXPECT_GT(t.lambda_nm[k], t.lambda_nm[k - 1]);
                        }
                    }
                }
            }
        }
    }

    TEST(BasicPlugin, DefaultsCreateWithoutErrors)
    {
        const LoadedPlugin& p = basic_plugin();
        ASSERT_TRUE(p.info) << p.error;
        for (int si = 0; si < p.info->shader_count; ++si) {
            const PatinaShaderDesc& s = p.info->shaders[si];
            ParamSet params(s);
            Instance instance(s, params);
            EXPECT_TRUE(instance) << s.name;
            EXPECT_TRUE(test_host().errors.empty()) << s.name << ": " << test_host().errors.front();
        }
    }

} // namespace
} // namespace patina::test
