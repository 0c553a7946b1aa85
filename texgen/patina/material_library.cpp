#include "texgen/patina/material_library.h"

#include "formats/toml_location.h"

#include <patina/shading/kubelka_munk.h>
#include "core/shader_library.h"
#include "texgen/patina/stack_materials.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

    using formats::toml_fail;

    double number_of(const fs::path& file, const toml::node& node, const std::string& key)
    {
        if (const auto v = node.value<double>())
            return *v;
        toml_fail(file, &node, fmt::format("'{}' must be a number", key));
    }

    Imath::V3f triple_of(const fs::path& file, const toml::node& node, const std::string& key)
    {
        const toml::array* a = node.as_array();
        if (!a || a->size() != 3)
            toml_fail(file, &node, fmt::format("'{}' must be an array of 3 numbers", key));
        Imath::V3f v;
        for (int c = 0; c < 3; ++c)
            v[c] = static_cast<float>(number_of(file, *a->get(c), key));
        return v;
    }

    // The keys a material table may hold; anything else is a typo.
    const std::set<std::string> kMaterialKeys = {"kind", "names", "color", "color_space",
                                                 "scattering", "mixture", "roughness",
                                                 "specular", "description",
                                                 "wavelengths_nm", "n", "k", "r_inf"};

    /// A table of numbers of `size` entries (any size when 0), each finite and >= 0.
    std::vector<float> table_of(const fs::path& file, const toml::node& node,
                                const std::string& key, size_t size)
    {
        const toml::array* a = node.as_array();
        if (!a || a->empty())
            toml_fail(file, &node, fmt::format("'{}' must be an array of numbers", key));
        if (size && a->size() != size)
            toml_fail(file, &node, fmt::format("'{}' has {} values for {} wavelengths (wavelengths_nm)",
                                         key, a->size(), size));
        std::vector<float> out;
        for (const toml::node& v : *a) {
            const double x = number_of(file, v, key);
            if (!std::isfinite(x) || x < 0.0)
                toml_fail(file, &v, fmt::format("'{}' must hold finite numbers >= 0", key));
            out.push_back(static_cast<float>(x));
        }
        return out;
    }

}  // namespace

void MaterialLibrary::load(const fs::path& file, const ColorManager& colors)
{
    const toml::table root = formats::parse_toml_file(file);
    for (const auto& [key, node] : root)
        if (key.str() != "library" && key.str() != "materials")
            toml_fail(file, &node, fmt::format("unknown table '{}' (expected [library] and "
                                         "[materials.<name>])", key.str()));
    const toml::table* table = root["materials"].as_table();
    if (!table)
        throw std::runtime_error(fmt::format("{}: no [materials.<name>] tables", file.string()));

    // Plain materials first, so that mixtures may name materials defined after them.
    std::vector<std::pair<std::string, const toml::table*>> plain, mixtures;
    for (const auto& [key, node] : *table) {
        const toml::table* m = node.as_table();
        if (!m)
            toml_fail(file, &node, fmt::format("materials.{} must be a table", key.str()));
        (m->contains("mixture") ? mixtures : plain).emplace_back(std::string(key.str()), m);
    }

    auto add_name = [&](const std::string& name, size_t index, const toml::node& node) {
        if (by_name_.count(name))
            toml_fail(file, &node, fmt::format("material name '{}' is already defined (in {})", name,
                                         materials_[by_name_.at(name)].file.string()));
        by_name_[name] = index;
    };

    auto define = [&](const std::string& name, const toml::table& m, bool mixture) {
        for (const auto& [k, v] : m)
            if (!kMaterialKeys.count(std::string(k.str())))
                toml_fail(file, &v, fmt::format("material '{}': unknown key '{}' (known: kind, "
                                          "names, color, color_space, scattering, mixture, "
                                          "roughness, specular, description, wavelengths_nm, "
                                          "n, k, r_inf)",
                                          name, k.str()));
        PatinaMaterial mat;
        mat.name = name;
        mat.file = file;
        if (const toml::node* kind = m.get("kind")) {
            const auto s = kind->value<std::string>();
            if (!s || (*s != "metal" && *s != "layer"))
                toml_fail(file, kind, fmt::format("material '{}': kind must be \"metal\" or "
                                              "\"layer\"", name));
            mat.is_metal = *s == "metal";
        }
        if (const toml::node* names = m.get("names")) {
            const toml::array* a = names->as_array();
            if (!a)
                toml_fail(file, names, "'names' must be an array of strings");
            for (const toml::node& n : *a) {
                const auto s = n.value<std::string>();
                if (!s || s->empty())
                    toml_fail(file, &n, "'names' must be an array of non-empty strings");
                mat.aliases.push_back(*s);
            }
        }
        if (const toml::node* d = m.get("description"))
            mat.description = d->value<std::string>().value_or("");
        if (const toml::node* r = m.get("roughness")) {
            mat.roughness = static_cast<float>(number_of(file, *r, "roughness"));
            if (!(mat.roughness > 0.0f && mat.roughness <= 1.0f))
                toml_fail(file, r, fmt::format("material '{}': roughness must be in (0, 1]", name));
        }
        if (const toml::node* s = m.get("specular"))
            mat.specular = triple_of(file, *s, "specular");

        // Optional spectral tables: a metal's n and k, a layer's R_inf.
        std::vector<float> table_nm, n_table, k_table, r_table;
        if (const toml::node* w = m.get("wavelengths_nm")) {
            table_nm = table_of(file, *w, "wavelengths_nm", 0);
            for (size_t i = 1; i < table_nm.size(); ++i)
                if (!(table_nm[i] > table_nm[i - 1]))
                    toml_fail(file, w, "'wavelengths_nm' must increase strictly");
        }
        for (const char* key : {"n", "k", "r_inf"})
            if (const toml::node* t = m.get(key)) {
                if (table_nm.empty())
                    toml_fail(file, t, fmt::format("material '{}': '{}' needs 'wavelengths_nm'",
                                               name, key));
                if ((std::string(key) == "r_inf") == mat.is_metal || mixture)
                    toml_fail(file, t, fmt::format("material '{}': '{}' is for {}", name, key,
                                               std::string(key) == "r_inf"
                                                   ? "a layer that is not a mixture"
                                                   : "a metal"));
                std::vector<float> v = table_of(file, *t, key, table_nm.size());
                (std::string(key) == "n" ? n_table
                 : std::string(key) == "k" ? k_table : r_table) = std::move(v);
            }
        if (n_table.empty() != k_table.empty())
            toml_fail(file, &m, fmt::format("material '{}': give both 'n' and 'k' or neither", name));
        for (float r : r_table)
            if (!(r > 0.0f && r <= 1.0f))
                toml_fail(file, m.get("r_inf"), fmt::format("material '{}': r_inf must lie in "
                                                        "(0, 1]", name));

        if (mixture) {
            // Duncan's rule: K and S of a mixture are the volume-weighted sums.
            const toml::node* mix_node = m.get("mixture");
            const toml::table* mix = mix_node->as_table();
            if (!mix || mix->empty())
                toml_fail(file, mix_node, "'mixture' must be a table of material = fraction");
            if (m.contains("color") || m.contains("scattering") || mat.is_metal)
                toml_fail(file, mix_node, fmt::format("material '{}': a mixture takes its colour "
                                                  "and scattering from its components", name));
            double sum = 0.0;
            Imath::V3f K(0.0f), S(0.0f);
            mat.spectral.lambda_nm = spectral_grid();
            mat.spectral.absorption.assign(kSpectralSamples, 0.0f);
            mat.spectral.scattering.assign(kSpectralSamples, 0.0f);
            for (const auto& [component, fraction_node] : *mix) {
                const PatinaMaterial* c = find(std::string(component.str()));
                if (!c)
                    toml_fail(file, &fraction_node, fmt::format("material '{}': mixture names "
                                                          "unknown material '{}'",
                                                          name, component.str()));
                if (c->is_metal)
                    toml_fail(file, &fraction_node, fmt::format("material '{}': a mixture cannot "
                                                          "hold the metal '{}'",
                                                          name, component.str()));
                const double f = number_of(file, fraction_node, "mixture fraction");
                if (!(f > 0.0 && f <= 1.0))
                    toml_fail(file, &fraction_node, "a mixture fraction must be in (0, 1]");
                sum += f;
                K += c->absorption * static_cast<float>(f);
                S += c->scattering * static_cast<float>(f);
                for (int i = 0; i < kSpectralSamples; ++i) {
                    mat.spectral.absorption[i] += c->spectral.absorption[i] * static_cast<float>(f);
                    mat.spectral.scattering[i] += c->spectral.scattering[i] * static_cast<float>(f);
                }
            }
            for (int i = 0; i < kSpectralSamples; ++i)
                mat.spectral.r_infinity.push_back(static_cast<float>(shading::km_r_infinity(
                    mat.spectral.absorption[i] / mat.spectral.scattering[i])));
            if (std::abs(sum - 1.0) > 1e-3)
                toml_fail(file, mix_node, fmt::format("material '{}': mixture fractions sum to {} "
                                                  "(must be 1)", name, sum));
            mat.absorption = K;
            mat.scattering = S;
            for (int c = 0; c < 3; ++c)
                mat.color[c] = static_cast<float>(shading::km_r_infinity(K[c] / S[c]));
        } else {
            const toml::node* color = m.get("color");
            if (!color)
                toml_fail(file, &m, fmt::format("material '{}' has no 'color' (R_inf, or a metal's "
                                          "reflectance) and no 'mixture'", name));
            Imath::V3f c = triple_of(file, *color, "color");
            for (int i = 0; i < 3; ++i)
                if (!(c[i] > 0.0f && c[i] <= 1.0f))
                    toml_fail(file, color, fmt::format("material '{}': colour components must be in "
                                                   "(0, 1]", name));
            std::string space = "srgb_texture";
            if (const toml::node* cs = m.get("color_space"))
                space = cs->value<std::string>().value_or("");
            try {
                colors.convert(space, "lin_rec709", &c.x, 1);
            } catch (const std::exception& e) {
                toml_fail(file, m.get("color_space") ? m.get("color_space") : color, e.what());
            }
            // Keep R_inf inside (0, 1): K/S is infinite at 0 and 0 at 1.
            for (int i = 0; i < 3; ++i)
                c[i] = std::clamp(c[i], 1e-4f, 0.9999f);
            mat.color = c;
            if (!mat.is_metal) {
                const toml::node* s = m.get("scattering");
                if (!s)
                    toml_fail(file, &m, fmt::format("material '{}' has no 'scattering' (S, 1/µm)",
                                              name));
                const float S = static_cast<float>(number_of(file, *s, "scattering"));
                if (!(S > 0.0f) || !std::isfinite(S))
                    toml_fail(file, s, fmt::format("material '{}': scattering must be positive",
                                               name));
                mat.scattering = Imath::V3f(S);
                // K/S from R_inf (D&H 1996 §4.1), with the assumed S.
                for (int i = 0; i < 3; ++i)
                    mat.absorption[i] = static_cast<float>(shading::km_k_over_s(c[i])) * S;
            }
            // The spectral optics: the tables when given, else uplifted from the colour.
            if (!n_table.empty()) {
                mat.spectral.lambda_nm = spectral_grid();
                mat.spectral.n = resample_to_grid(table_nm, n_table);
                mat.spectral.k = resample_to_grid(table_nm, k_table);
                mat.spectral.absorption.assign(kSpectralSamples, 0.0f);
                mat.spectral.scattering.assign(kSpectralSamples, 0.0f);
            } else if (!r_table.empty()) {
                mat.spectral.lambda_nm = spectral_grid();
                mat.spectral.r_infinity = resample_to_grid(table_nm, r_table);
                for (float& r : mat.spectral.r_infinity) {
                    r = std::clamp(r, 1e-4f, 0.9999f);
                    mat.spectral.scattering.push_back(mat.scattering[0]);
                    mat.spectral.absorption.push_back(static_cast<float>(shading::km_k_over_s(r)) * mat.scattering[0]);
                }
            } else {
                mat.spectral = resolve_spectral(mat, colors);
            }
        }
        if (mat.spectral.specular.empty())
            mat.spectral.specular = uplift_reflectance(mat.specular, colors);
        const size_t index = materials_.size();
        add_name(name, index, m);
        for (const std::string& alias : mat.aliases)
            add_name(alias, index, m);
        materials_.push_back(std::move(mat));
    };

    for (const auto& [name, m] : plain)
        define(name, *m, false);
    for (const auto& [name, m] : mixtures)
        define(name, *m, true);
}

const PatinaMaterial* MaterialLibrary::find(const std::string& name) const
{
    const auto it = by_name_.find(name);
    return it == by_name_.end() ? nullptr : &materials_[it->second];
}

const PatinaMaterial& MaterialLibrary::at(const std::string& name) const
{
    if (const PatinaMaterial* m = find(name))
        return *m;
    throw std::runtime_error(fmt::format("unknown material '{}'", name));
}

std::set<std::string> MaterialLibrary::names() const
{
    std::set<std::string> out;
    for (const auto& [name, index] : by_name_)
        out.insert(name);
    return out;
}

std::vector<fs::path> MaterialLibrary::default_files()
{
    return shader_library_files("patina");
}

MaterialLibrary MaterialLibrary::load_default(const std::vector<fs::path>& extra,
                                              const ColorManager& colors)
{
    std::vector<fs::path> files = default_files();
    files.insert(files.end(), extra.begin(), extra.end());
    if (files.empty())
        throw std::runtime_error("no material library: none found under $PATINA_SHADER_PATH or "
                                 "<exe>/../share/patina/shaders/patina; pass --materials FILE");
    MaterialLibrary library;
    for (const fs::path& f : files)
        library.load(f, colors);
    return library;
}

}  // namespace patina::texgen
