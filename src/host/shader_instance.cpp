#include "host/shader_instance.h"

#include <patina/plugin_support.h>

#include "formats/toml_location.h"

#include "core/color_management.h"
#include "host/host.h"
#include "core/spectrum_csv.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <optional>
#include <span>

namespace patina {

ShaderInstance::~ShaderInstance()
{
    if (instance_)
        shader_->desc->destroy(instance_);
}

namespace {

    using plugin::type_name;

    size_t edit_distance(std::string_view a, std::string_view b)
    {
        std::vector<size_t> row(b.size() + 1);
        for (size_t j = 0; j <= b.size(); ++j)
            row[j] = j;
        for (size_t i = 1; i <= a.size(); ++i) {
            size_t diag = row[0];
            row[0] = i;
            for (size_t j = 1; j <= b.size(); ++j) {
                const size_t up = row[j];
                row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
                diag = up;
            }
        }
        return row[b.size()];
    }

    // Builds messages that name the file, the line, the shader and the parameter.
    struct Context {
        const ParamSource& source;
        std::string_view label;
        std::string_view shader;

        [[noreturn]] void fail(const toml::node* node, std::string_view param,
                               std::string_view problem) const
        {
            const std::string where =
                formats::toml_where(source.file.empty() ? std::string("<params>") : source.file,
                                    node);
            std::string what = param.empty() ? std::string()
                                             : fmt::format("parameter '{}': ", param);
            throw ParamError(fmt::format("{}: shader '{}' ({}): {}{}", where, label, shader,
                                         what, problem));
        }
    };

    bool is_working_space(const ColorManager& colors, std::string_view space)
    {
        return space.empty() || space == "scene_linear" || space == colors.working_space();
    }

    std::optional<double> as_number(const toml::node& n)
    {
        if (auto v = n.value<double>(); v && (n.is_integer() || n.is_floating_point()))
            return v;
        return std::nullopt;
    }

    const char* node_type(const toml::node& n)
    {
        switch (n.type()) {
        case toml::node_type::string: return "a string";
        case toml::node_type::integer: return "an integer";
        case toml::node_type::floating_point: return "a number";
        case toml::node_type::boolean: return "a boolean";
        case toml::node_type::array: return "an array";
        case toml::node_type::table: return "a table";
        default: return "a date or time";
        }
    }

    // Storage that must outlive the create() call (strings and spectrum tables).
    struct Scratch {
        std::deque<std::string> strings;
        std::deque<std::vector<float>> floats;
    };

    void check_range(const Context& ctx, const toml::node* node, const PatinaParamDecl& d,
                     double v)
    {
        if (!std::isfinite(v))
            ctx.fail(node, d.name, "value is not a finite number");
        if (v < d.min_value || v > d.max_value)
            ctx.fail(node, d.name, fmt::format("value {} is outside the range [{}, {}]", v,
                                               d.min_value, d.max_value));
    }

    void bind_color(const Context& ctx, const Host& host, const toml::node& node,
                    const PatinaParamDecl& d, PatinaParamValue& out)
    {
        // A colour is [r, g, b], a grey number, or { rgb = [...], colorspace = "name" }.
        const toml::node* rgb_node = &node;
        std::string space = d.colorspace ? d.colorspace : "";
        if (const toml::table* t = node.as_table()) {
            for (auto&& [k, v] : *t)
                if (k.str() != "rgb" && k.str() != "colorspace")
                    ctx.fail(&v, d.name, fmt::format("unknown key '{}' in a colour (expected "
                                                     "'rgb' and 'colorspace')", k.str()));
            rgb_node = t->get("rgb");
            if (!rgb_node)
                ctx.fail(&node, d.name, "a colour table needs 'rgb = [r, g, b]'");
            if (const toml::node* cs = t->get("colorspace")) {
                if (!cs->is_string())
                    ctx.fail(cs, d.name, "'colorspace' must be a string");
                space = **cs->as_string();
                if (!host.colors().has_colorspace(space))
                    ctx.fail(cs, d.name, fmt::format("unknown colour space '{}' in OCIO config '{}'",
                                                     space, host.colors().config_path().string()));
            }
        }
        float rgb[3];
        if (auto g = as_number(*rgb_node)) {
            rgb[0] = rgb[1] = rgb[2] = static_cast<float>(*g);
        } else if (const toml::array* a = rgb_node->as_array()) {
            if (a->size() != 3)
                ctx.fail(rgb_node, d.name, fmt::format("a colour needs 3 components, got {}",
                                                       a->size()));
            for (size_t i = 0; i < 3; ++i) {
                auto c = as_number(*a->get(i));
                if (!c)
                    ctx.fail(a->get(i), d.name, "colour components must be numbers");
                rgb[i] = static_cast<float>(*c);
            }
        } else {
            ctx.fail(rgb_node, d.name,
                     fmt::format("expected a colour [r, g, b] or a number, got {}",
                                 node_type(*rgb_node)));
        }
        for (float c : rgb)
            check_range(ctx, rgb_node, d, c);
        if (!is_working_space(host.colors(), space) && space != "raw")
            host.colors().convert(space, host.colors().working_space(), rgb, 1);
        std::copy(rgb, rgb + 3, out.rgb);
    }

    void bind_spectrum(const Context& ctx, const toml::node& node, const PatinaParamDecl& d,
                       Scratch& scratch, PatinaParamValue& out)
    {
        // A spectrum is a constant number, [[lambda_nm, value], ...],
        // { lambda_nm = [...], value = [...] } or { file = "x.csv", column = "name" }.
        std::vector<float> lambda, value;
        const toml::table* table = node.as_table();
        if (table && table->contains("file")) {
            for (auto&& [k, v] : *table)
                if (k.str() != "file" && k.str() != "column")
                    ctx.fail(&v, d.name, fmt::format("unknown key '{}' in a spectrum from a file "
                                                     "(expected 'file' and 'column')", k.str()));
            const auto file = table->get_as<std::string>("file");
            const auto column = table->get_as<std::string>("column");
            if (!file || !column)
                ctx.fail(&node, d.name, "a spectrum from a file needs 'file = \"x.csv\"' and "
                                        "'column = \"name\"'");
            std::filesystem::path path(**file);
            if (path.is_relative() && !ctx.source.base_dir.empty())
                path = ctx.source.base_dir / path;
            try {
                const SpectrumCsv csv = read_spectrum_csv(path);
                const std::vector<double>& v = csv.values[csv.column(**column)];
                for (size_t i = 0; i < v.size(); ++i) {
                    check_range(ctx, &node, d, v[i]);
                    lambda.push_back(static_cast<float>(csv.lambda_nm[i]));
                    value.push_back(static_cast<float>(v[i]));
                }
            } catch (const ParamError&) {
                throw;
            } catch (const std::exception& e) {
                ctx.fail(&node, d.name, e.what());
            }
        } else if (auto c = as_number(node)) {
            check_range(ctx, &node, d, *c);
            lambda = {560.0f};
            value = {static_cast<float>(*c)};
        } else if (const toml::array* a = node.as_array()) {
            for (const toml::node& pair : *a) {
                const toml::array* p = pair.as_array();
                std::optional<double> l, v;
                if (p && p->size() == 2) {
                    l = as_number(*p->get(0));
                    v = as_number(*p->get(1));
                }
                if (!l || !v)
                    ctx.fail(&pair, d.name, "expected [lambda_nm, value] pairs");
                check_range(ctx, &pair, d, *v);
                lambda.push_back(static_cast<float>(*l));
                value.push_back(static_cast<float>(*v));
            }
        } else if (const toml::table* t = table) {
            const toml::array* la = t->get_as<toml::array>("lambda_nm");
            const toml::array* va = t->get_as<toml::array>("value");
            if (!la || !va || la->size() != va->size())
                ctx.fail(&node, d.name, "a spectrum table needs arrays 'lambda_nm' and 'value' "
                                        "of equal length");
            for (auto&& [k, v] : *t)
                if (k.str() != "lambda_nm" && k.str() != "value")
                    ctx.fail(&v, d.name, fmt::format("unknown key '{}' in a spectrum", k.str()));
            for (size_t i = 0; i < la->size(); ++i) {
                auto l = as_number(*la->get(i));
                auto v = as_number(*va->get(i));
                if (!l || !v)
                    ctx.fail(la->get(i), d.name, "spectrum entries must be numbers");
                check_range(ctx, va->get(i), d, *v);
                lambda.push_back(static_cast<float>(*l));
                value.push_back(static_cast<float>(*v));
            }
        } else {
            ctx.fail(&node, d.name, fmt::format("expected a number or a spectrum, got {}",
                                                node_type(node)));
        }
        if (lambda.empty())
            ctx.fail(&node, d.name, "a spectrum needs at least one entry");
        for (size_t i = 1; i < lambda.size(); ++i)
            if (!(lambda[i] > lambda[i - 1]))
                ctx.fail(&node, d.name, "wavelengths must increase strictly");
        scratch.floats.push_back(std::move(lambda));
        const float* l = scratch.floats.back().data();
        scratch.floats.push_back(std::move(value));
        out.spectrum = {static_cast<int>(scratch.floats.back().size()), l,
                        scratch.floats.back().data()};
    }

    const float kDefaultLambda = 560.0f;

    void bind_default(const Host& host, const PatinaParamDecl& d, PatinaParamValue& v)
    {
        v.f = d.default_value[0];
        v.i = static_cast<int>(d.default_value[0]);
        switch (d.type) {
        case PATINA_PARAM_COLOR: {
            float rgb[3] = {d.default_value[0], d.default_value[1], d.default_value[2]};
            const std::string space = d.colorspace ? d.colorspace : "";
            if (!is_working_space(host.colors(), space) && space != "raw")
                host.colors().convert(space, host.colors().working_space(), rgb, 1);
            std::copy(rgb, rgb + 3, v.rgb);
            break;
        }
        case PATINA_PARAM_SPECTRUM:
            if (d.default_spectrum)
                v.spectrum = *d.default_spectrum;
            else
                v.spectrum = {1, &kDefaultLambda, &d.default_value[0]};
            break;
        case PATINA_PARAM_STRING:
        case PATINA_PARAM_TEXTURE:
        case PATINA_PARAM_FILE:
            v.s = d.default_string ? d.default_string : "";
            break;
        default:
            break;
        }
    }

}  // namespace

std::shared_ptr<ShaderInstance> create_shader_instance(const PluginRegistry& registry,
                                                       std::string_view shader_name,
                                                       const toml::table& params,
                                                       std::string_view label,
                                                       const ParamSource& source)
{
    const Host* host = Host::from_c(registry.host());
    if (!host)
        throw std::logic_error("create_shader_instance: the registry's host is not a patina::Host");
    const Context ctx{source, label, shader_name};
    const LoadedShader* shader = registry.find(shader_name);
    if (!shader) {
        try {
            registry.get(shader_name);
        } catch (const PluginError& e) {
            ctx.fail(nullptr, "", e.what());
        }
    }
    const PatinaShaderDesc& desc = *shader->desc;
    const std::span<const PatinaParamDecl> decls(desc.params, static_cast<size_t>(desc.param_count));

    // Unknown keys first: a typo must never be silently replaced by a default.
    for (auto&& [key, node] : params) {
        const std::string_view k = key.str();
        if (std::find(source.ignore_keys.begin(), source.ignore_keys.end(), k) !=
            source.ignore_keys.end())
            continue;
        const bool known = std::any_of(decls.begin(), decls.end(),
                                       [&](const PatinaParamDecl& d) { return k == d.name; });
        if (known)
            continue;
        std::string hint;
        size_t best = 3;
        for (const PatinaParamDecl& d : decls)
            if (size_t e = edit_distance(k, d.name); e < best) {
                best = e;
                hint = fmt::format(" (did you mean '{}'?)", d.name);
            }
        std::string names;
        for (const PatinaParamDecl& d : decls)
            names += (names.empty() ? "" : ", ") + std::string(d.name);
        ctx.fail(&node, k, fmt::format("unknown parameter{}; '{}' takes: {}", hint, shader_name,
                                       names.empty() ? "no parameters" : names));
    }

    Scratch scratch;
    std::vector<PatinaParamValue> values(decls.size());
    for (size_t i = 0; i < decls.size(); ++i) {
        const PatinaParamDecl& d = decls[i];
        PatinaParamValue& v = values[i];
        v = PatinaParamValue{};
        v.type = d.type;
        const toml::node* node = params.get(d.name);
        if (!node) {
            bind_default(*host, d, v);
        } else {
            switch (d.type) {
            case PATINA_PARAM_FLOAT: {
                auto x = as_number(*node);
                if (!x)
                    ctx.fail(node, d.name, fmt::format("expected a number, got {}", node_type(*node)));
                check_range(ctx, node, d, *x);
                v.f = static_cast<float>(*x);
                break;
            }
            case PATINA_PARAM_INT: {
                if (!node->is_integer())
                    ctx.fail(node, d.name, fmt::format("expected an integer, got {}", node_type(*node)));
                const double x = static_cast<double>(**node->as_integer());
                check_range(ctx, node, d, x);
                v.i = static_cast<int>(x);
                v.f = static_cast<float>(x);
                break;
            }
            case PATINA_PARAM_BOOL:
                if (!node->is_boolean())
                    ctx.fail(node, d.name, fmt::format("expected true or false, got {}", node_type(*node)));
                v.i = **node->as_boolean() ? 1 : 0;
                v.f = static_cast<float>(v.i);
                break;
            case PATINA_PARAM_COLOR:
                bind_color(ctx, *host, *node, d, v);
                break;
            case PATINA_PARAM_SPECTRUM:
                bind_spectrum(ctx, *node, d, scratch, v);
                break;
            case PATINA_PARAM_STRING:
                if (!node->is_string())
                    ctx.fail(node, d.name, fmt::format("expected a string, got {}", node_type(*node)));
                scratch.strings.push_back(**node->as_string());
                v.s = scratch.strings.back().c_str();
                break;
            case PATINA_PARAM_FILE: {
                if (!node->is_string())
                    ctx.fail(node, d.name, fmt::format("expected a file name, got {}", node_type(*node)));
                std::filesystem::path path(**node->as_string());
                if (path.is_relative() && !source.base_dir.empty())
                    path = source.base_dir / path;
                std::error_code ec;
                if (!std::filesystem::is_regular_file(path, ec))
                    ctx.fail(node, d.name, fmt::format("no such file '{}'", path.string()));
                scratch.strings.push_back(std::filesystem::absolute(path).string());
                v.s = scratch.strings.back().c_str();
                break;
            }
            case PATINA_PARAM_TEXTURE: {
                // A texture is "file" (in the declared colour space) or
                // { file = "...", colorspace = "..." }.
                std::string file, space = d.colorspace ? d.colorspace : "raw";
                if (node->is_string()) {
                    file = **node->as_string();
                } else if (const toml::table* t = node->as_table()) {
                    for (auto&& [k, sub] : *t)
                        if (k.str() != "file" && k.str() != "colorspace")
                            ctx.fail(&sub, d.name, fmt::format("unknown key '{}' in a texture", k.str()));
                    auto f = t->get_as<std::string>("file");
                    if (!f)
                        ctx.fail(node, d.name, "a texture table needs 'file = \"...\"'");
                    file = **f;
                    if (auto cs = t->get_as<std::string>("colorspace"))
                        space = **cs;
                } else {
                    ctx.fail(node, d.name, fmt::format("expected a file name, got {}", node_type(*node)));
                }
                std::filesystem::path path(file);
                if (path.is_relative() && !source.base_dir.empty())
                    path = source.base_dir / path;
                scratch.strings.push_back(path.string());
                v.s = scratch.strings.back().c_str();
                try {
                    v.texture = host->open_texture(path.string(), space);
                } catch (const std::exception& e) {
                    ctx.fail(node, d.name, e.what());
                }
                break;
            }
            }
        }
        if (d.type == PATINA_PARAM_COLOR)
            v.color = host->uplift(v.rgb, d.max_value > 1.0f);
    }

    host->take_errors();
    void* instance = desc.create(host->c_host(), values.data());
    if (!instance) {
        std::string why;
        for (const std::string& e : host->take_errors())
            why += (why.empty() ? "" : "; ") + e;
        ctx.fail(nullptr, "", why.empty() ? "the plugin refused the parameters" : why);
    }
    return std::make_shared<ShaderInstance>(*shader, instance, std::string(label));
}

namespace {

    /// A parameter's default and range as the listings print them.
    struct ParamText {
        std::string def, range;
    };

    /// `long_tables`: a tabulated default with its wavelength range, as the reference prints it.
    ParamText param_text(const PatinaParamDecl& d, bool long_tables = false)
    {
        ParamText t;
        switch (d.type) {
        case PATINA_PARAM_COLOR:
            t.def = fmt::format("[{}, {}, {}]", d.default_value[0], d.default_value[1],
                                d.default_value[2]);
            break;
        case PATINA_PARAM_SPECTRUM:
            if (d.default_spectrum && long_tables && d.default_spectrum->count > 0)
                t.def = fmt::format("table of {} values, {}-{} nm", d.default_spectrum->count,
                                    d.default_spectrum->lambda_nm[0],
                                    d.default_spectrum->lambda_nm[d.default_spectrum->count - 1]);
            else if (d.default_spectrum)
                t.def = fmt::format("table of {}", d.default_spectrum->count);
            else
                t.def = fmt::format("{}", d.default_value[0]);
            break;
        case PATINA_PARAM_STRING:
        case PATINA_PARAM_TEXTURE:
        case PATINA_PARAM_FILE:
            t.def = fmt::format("\"{}\"", d.default_string ? d.default_string : "");
            break;
        case PATINA_PARAM_BOOL:
            t.def = d.default_value[0] != 0.0f ? "true" : "false";
            break;
        default:
            t.def = fmt::format("{}", d.default_value[0]);
        }
        if (d.type == PATINA_PARAM_FLOAT || d.type == PATINA_PARAM_INT ||
            d.type == PATINA_PARAM_COLOR || d.type == PATINA_PARAM_SPECTRUM)
            t.range = fmt::format("[{}, {}]", d.min_value, d.max_value);
        return t;
    }

    /// Text for a Markdown table cell: no line breaks, '|' escaped.
    std::string cell(const char* text)
    {
        std::string out;
        for (const char* c = text ? text : ""; *c; ++c) {
            if (*c == '|')
                out += "\\|";
            else if (*c == '\n' || *c == '\r')
                out += ' ';
            else
                out += *c;
        }
        return out;
    }

}  // namespace

std::string describe_shader(const PatinaShaderDesc& desc)
{
    std::string out;
    for (int i = 0; i < desc.param_count; ++i) {
        const PatinaParamDecl& d = desc.params[i];
        const ParamText t = param_text(d);
        out += fmt::format("    {:<20} {:<9} default {:<16} {:<16} {:<12} {}\n", d.name,
                           type_name(d.type), t.def, t.range, d.colorspace ? d.colorspace : "",
                           d.help ? d.help : "");
    }
    return out;
}

std::string describe_shader_markdown(const PatinaShaderDesc& desc)
{
    if (desc.param_count == 0)
        return "No parameters.\n";
    std::string out = "| parameter | type | default | range | colour space or units | meaning |\n"
                      "|---|---|---|---|---|---|\n";
    for (int i = 0; i < desc.param_count; ++i) {
        const PatinaParamDecl& d = desc.params[i];
        const ParamText t = param_text(d, true);
        out += fmt::format("| `{}` | {} | `{}` | {} | {} | {} |\n", d.name, type_name(d.type),
                           cell(t.def.c_str()), t.range, cell(d.colorspace), cell(d.help));
    }
    return out;
}

}  // namespace patina
