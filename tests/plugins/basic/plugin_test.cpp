// The basic plugin as a host sees it: symbols, version, descriptor table, parameter metadata,
// defaults that create instances, and a README that says what the metadata says.
#include "basic_plugin.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace patina::test {
namespace {

    const char* type_name(PatinaParamType type)
    {
        switch (type) {
        case PATINA_PARAM_FLOAT:
            return "float";
        case PATINA_PARAM_INT:
            return "int";
        case PATINA_PARAM_BOOL:
            return "bool";
        case PATINA_PARAM_COLOR:
            return "color";
        case PATINA_PARAM_SPECTRUM:
            return "spectrum";
        case PATINA_PARAM_STRING:
            return "string";
        case PATINA_PARAM_TEXTURE:
            return "texture";
        case PATINA_PARAM_FILE:
            return "file";
        }
        return "?";
    }

    const char* kind_name(PatinaShaderKind kind)
    {
        switch (kind) {
        case PATINA_SHADER_BSDF:
            return "bsdf";
        case PATINA_SHADER_MEDIUM:
            return "medium";
        case PATINA_SHADER_EMITTER:
            return "emitter";
        case PATINA_SHADER_TEXTURE:
            return "texture";
        }
        return "?";
    }

    /// One README table row, built from the metadata alone.
    std::string readme_row(const PatinaParamDecl& d)
    {
        char def[128] = "", range[64] = "";
        switch (d.type) {
        case PATINA_PARAM_FLOAT:
            std::snprintf(def, sizeof def, "%g", d.default_value[0]);
            break;
        case PATINA_PARAM_INT:
            std::snprintf(def, sizeof def, "%d", int(d.default_value[0]));
            break;
        case PATINA_PARAM_BOOL:
            std::snprintf(def, sizeof def, "%s", d.default_value[0] != 0.0f ? "true" : "false");
            break;
        case PATINA_PARAM_COLOR:
            std::snprintf(def, sizeof def, "%g %g %g", d.default_value[0], d.default_value[1],
                          d.default_value[2]);
            break;
        case PATINA_PARAM_SPECTRUM:
            if (d.default_spectrum)
                std::snprintf(def, sizeof def, "table of %d values, %g-%g nm",
                              d.default_spectrum->count, d.default_spectrum->lambda_nm[0],
                              d.default_spectrum->lambda_nm[d.default_spectrum->count - 1]);
            else
                std::snprintf(def, sizeof def, "%g", d.default_value[0]);
            break;
        case PATINA_PARAM_STRING:
        case PATINA_PARAM_TEXTURE:
        case PATINA_PARAM_FILE:
            std::snprintf(def, sizeof def, "%s", d.default_string ? d.default_string : "");
            break;
        }
        if (d.type == PATINA_PARAM_FLOAT || d.type == PATINA_PARAM_INT ||
            d.type == PATINA_PARAM_COLOR || d.type == PATINA_PARAM_SPECTRUM)
            std::snprintf(range, sizeof range, "[%g, %g]", d.min_value, d.max_value);
        std::ostringstream row;
        row << "| `" << d.name << "` | " << type_name(d.type) << " | " << def << " | " << range
            << " | " << (d.colorspace ? d.colorspace : "") << " | " << d.help << " |";
        return row.str();
    }

    std::string readme_section(const PatinaShaderDesc& s)
    {
        std::ostringstream out;
        out << "## " << s.name << " (" << kind_name(s.kind) << ")\n\n"
            << s.help << "\n\n"
            << "| parameter | type | default | range | colour space / units | description |\n"
            << "|---|---|---|---|---|---|\n";
        for (int i = 0; i < s.param_count; ++i)
            out << readme_row(s.params[i]) << "\n";
        return out.str();
    }

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

    TEST(BasicPlugin, ReadmeListsTheMetadata)
    {
        // README.md states each parameter with the same text as the metadata (--list-shaders)
        std::ifstream in(std::string(PATINA_SOURCE_DIR) + "/plugins/basic/README.md");
        ASSERT_TRUE(in) << "plugins/basic/README.md is missing";
        std::stringstream buffer;
        buffer << in.rdbuf();
        const std::string readme = buffer.str();
        const LoadedPlugin& p = basic_plugin();
        ASSERT_TRUE(p.info) << p.error;
        for (int si = 0; si < p.info->shader_count; ++si) {
            const std::string section = readme_section(p.info->shaders[si]);
            EXPECT_NE(readme.find(section), std::string::npos)
                << "README.md lacks or differs from:\n"
                << section;
        }
    }

    // Run with --gtest_also_run_disabled_tests to print the README's shader sections.
    TEST(BasicPlugin, DISABLED_PrintReadmeSections)
    {
        const LoadedPlugin& p = basic_plugin();
        ASSERT_TRUE(p.info) << p.error;
        for (int si = 0; si < p.info->shader_count; ++si)
            std::printf("%s\n", readme_section(p.info->shaders[si]).c_str());
    }

} // namespace
} // namespace patina::test
