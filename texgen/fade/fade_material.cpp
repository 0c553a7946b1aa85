#include "texgen/fade/fade_material.h"

#include "formats/toml_location.h"

#include "core/shader_library.h"
#include "core/spectrum_csv.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cstdlib>
#include <set>
#include <stdexcept>

namespace fs = std::filesystem;

namespace patina::texgen::fade {

size_t FadeMaterial::colorant_index(const std::string& colorant) const
{
    for (size_t j = 0; j < colorants.size(); ++j)
        if (colorants[j].name == colorant)
            return j;
    throw std::runtime_error(
        fmt::format("fade material '{}' holds no colorant '{}'", name, colorant));
}

void FadeMaterial::validate() const
{
    auto fail = [&](const std::string& what) {
        throw std::runtime_error(fmt::format("fade material '{}': {}", name, what));
    };
    if (!(thickness_m > 0.0))
        fail("thickness must be > 0");
    if (colorants.empty())
        fail("no colorants");
    if (initial_fractions.size() != colorants.size())
        fail("one initial fraction per colorant needed");
    auto check_spectrum = [&](const TabulatedSpectrum& s, const std::string& what) {
        if (s.nm.size() != s.value.size() || s.nm.empty())
            fail(what + ": nm and value must have the same, non-zero length");
        for (size_t i = 0; i < s.nm.size(); ++i) {
            if (!(s.value[i] >= 0.0))
                fail(fmt::format("{}: negative value {} at {} nm", what, s.value[i], s.nm[i]));
            if (i > 0 && !(s.nm[i] > s.nm[i - 1]))
                fail(what + ": wavelengths must increase");
        }
    };
    for (size_t j = 0; j < colorants.size(); ++j) {
        const Colorant& c = colorants[j];
        if (!(initial_fractions[j] >= 0.0 && initial_fractions[j] <= 1.0))
            fail(fmt::format("fraction of '{}' must be in [0, 1]", c.name));
        check_spectrum(c.absorption_per_m, c.name + " absorption");
        check_spectrum(c.scattering_per_m, c.name + " scattering");
        if (!(c.fading.rate_m3_per_j >= 0.0) || !(c.fading.reference_nm > 0.0))
            fail(fmt::format("fading rate of '{}' must be >= 0 with reference > 0", c.name));
        if (c.breakdown) {
            if (!(c.breakdown->rate.rate_m3_per_j >= 0.0) ||
                !(c.breakdown->rate.reference_nm > 0.0))
                fail(fmt::format("breakdown rate of '{}' must be >= 0", c.name));
            if (c.breakdown->product == c.name)
                fail(fmt::format("'{}' cannot break down into itself", c.name));
            colorant_index(c.breakdown->product);
        }
    }
    // Eqs. (12)-(14) mix the colorants by volume: together they cannot fill more than the
    // layer (the rest is a clear binder or air).
    double total = 0.0;
    for (double f : initial_fractions)
        total += f;
    if (total > 1.0 + 1e-9)
        fail(fmt::format("the colorants' volume fractions sum to {:.6g}, more than the layer "
                         "holds (1)", total));
    check_spectrum(substrate_reflectance, "substrate");
    for (double v : substrate_reflectance.value)
        if (v > 1.0)
            fail("substrate reflectance must be <= 1");
}

FadeMaterial with_rates(FadeMaterial material, const RateSet& rates)
{
    for (const auto& [colorant, rate] : rates) {
        if (!(rate >= 0.0))
            throw std::runtime_error(fmt::format("rate of '{}' must be >= 0", colorant));
        material.colorants[material.colorant_index(colorant)].fading.rate_m3_per_j = rate;
    }
    return material;
}

namespace {

// "file:line:column: key: problem", the location of the offending node.
class Reader {
public:
    explicit Reader(const fs::path& file) : file_(file) {}

    [[noreturn]] void fail(const toml::node& node, const std::string& key,
                           const std::string& what) const
    {
        formats::toml_fail(file_, &node, key + ": " + what);
    }

    void only_keys(const toml::table& t, const std::string& where,
                   std::initializer_list<const char*> allowed) const
    {
        formats::toml_check_keys(file_, t, where + ".", allowed);
    }

    double number(const toml::node& node, const std::string& key, double min) const
    {
        std::optional<double> v = node.value<double>();
        if (!v)
            fail(node, key, "expected a number");
        if (!(*v >= min))
            fail(node, key, fmt::format("must be >= {}", min));
        return *v;
    }

    const toml::node& required(const toml::table& t, const std::string& where,
                               const char* key) const
    {
        const toml::node* n = t.get(key);
        if (!n)
            fail(t, where, fmt::format("missing key '{}'", key));
        return *n;
    }

    // A number (a constant), { nm = [...], value = [...] } (piecewise linear), or
    // { file = "measured.csv", column = "K" } (a spectral CSV, relative to this file).
    TabulatedSpectrum spectrum(const toml::node& node, const std::string& key) const
    {
        if (node.is_number())
            return TabulatedSpectrum::constant(number(node, key, 0.0));
        const toml::table* t = node.as_table();
        if (!t)
            fail(node, key, "expected a number, a table { nm = [...], value = [...] } or "
                            "{ file = \"...csv\", column = \"...\" }");
        if (t->contains("file"))
            return spectrum_file(*t, key);
        only_keys(*t, key, {"nm", "value"});
        TabulatedSpectrum s;
        const toml::array* nm = required(*t, key, "nm").as_array();
        const toml::array* value = required(*t, key, "value").as_array();
        if (!nm || !value)
            fail(*t, key, "nm and value must be arrays of numbers");
        if (nm->size() != value->size() || nm->empty())
            fail(*t, key, fmt::format("nm has {} entries, value {}: need the same, > 0",
                                      nm->size(), value->size()));
        for (size_t i = 0; i < nm->size(); ++i) {
            s.nm.push_back(number((*nm)[i], key + ".nm", 0.0));
            s.value.push_back(number((*value)[i], key + ".value", 0.0));
            if (i > 0 && !(s.nm[i] > s.nm[i - 1]))
                fail((*nm)[i], key + ".nm", "wavelengths must increase");
        }
        return s;
    }

    // A measured spectrum from a CSV file (core/spectrum_csv.h): its column, values >= 0.
    TabulatedSpectrum spectrum_file(const toml::table& t, const std::string& key) const
    {
        only_keys(t, key, {"file", "column"});
        const std::optional<std::string> file = t["file"].value<std::string>();
        if (!file)
            fail(t, key + ".file", "expected a file name");
        const fs::path path = fs::path(*file).is_absolute() ? fs::path(*file)
                                                            : file_.parent_path() / *file;
        try {
            const SpectrumCsv csv = read_spectrum_csv(path);
            std::string name;
            if (const toml::node* column = t.get("column")) {
                const std::optional<std::string> given = column->value<std::string>();
                if (!given)
                    fail(*column, key + ".column", "expected a column name");
                name = *given;
            }
            const size_t c = csv.column(name);
            TabulatedSpectrum s{csv.lambda_nm, csv.values[c]};
            for (size_t i = 0; i < s.value.size(); ++i)
                if (!(s.value[i] >= 0.0))
                    fail(t, key, fmt::format("{}: {} at {} nm must be >= 0", path.string(),
                                             s.value[i], s.nm[i]));
            return s;
        } catch (const std::runtime_error& e) {
            if (std::string(e.what()).rfind(file_.string(), 0) == 0)
                throw;
            fail(t, key, e.what());
        }
    }

    WavelengthRate rate(const toml::table& t, const std::string& key) const
    {
        WavelengthRate r;
        r.rate_m3_per_j = number(required(t, key, "rate"), key + ".rate", 0.0);
        if (const toml::node* n = t.get("reference_nm"))
            r.reference_nm = number(*n, key + ".reference_nm", 1.0);
        if (const toml::node* n = t.get("cutoff_nm"))
            r.cutoff_nm = number(*n, key + ".cutoff_nm", 0.0);
        return r;
    }

    const toml::table& table(const toml::node& node, const std::string& key) const
    {
        const toml::table* t = node.as_table();
        if (!t)
            fail(node, key, "expected a table");
        return *t;
    }

private:
    fs::path file_;
};

}  // namespace

void FadeLibrary::load(const fs::path& file)
{
    const toml::table root = formats::parse_toml_file(file);
    const Reader rd(file);
    rd.only_keys(root, "(top level)", {"library", "colorants", "materials", "rate_sets"});
    if (const toml::node* lib = root.get("library"))
        rd.only_keys(rd.table(*lib, "library"), "library", {"format", "description"});

    // Colorants first: materials of this file may name them.
    if (const toml::node* cs = root.get("colorants")) {
        for (const auto& [k, node] : rd.table(*cs, "colorants")) {
            const std::string name(k.str());
            const std::string key = "colorants." + name;
            const toml::table& t = rd.table(node, key);
            rd.only_keys(t, key,
                         {"description", "absorption_per_m", "scattering_per_m", "fading",
                          "breakdown"});
            if (colorants_.count(name))
                rd.fail(node, key, "colorant defined twice");
            Colorant c;
            c.name = name;
            c.absorption_per_m =
                rd.spectrum(rd.required(t, key, "absorption_per_m"), key + ".absorption_per_m");
            c.scattering_per_m = TabulatedSpectrum::constant(0.0);
            if (const toml::node* s = t.get("scattering_per_m"))
                c.scattering_per_m = rd.spectrum(*s, key + ".scattering_per_m");
            if (const toml::node* d = t.get("description"))
                c.description = d->value_or(std::string());
            if (const toml::node* f = t.get("fading")) {
                const toml::table& ft = rd.table(*f, key + ".fading");
                rd.only_keys(ft, key + ".fading", {"rate", "reference_nm", "cutoff_nm"});
                c.fading = rd.rate(ft, key + ".fading");
            }
            if (const toml::node* b = t.get("breakdown")) {
                const toml::table& bt = rd.table(*b, key + ".breakdown");
                rd.only_keys(bt, key + ".breakdown",
                             {"product", "rate", "reference_nm", "cutoff_nm"});
                Breakdown br;
                const toml::node& product = rd.required(bt, key + ".breakdown", "product");
                br.product = product.value_or(std::string());
                if (br.product.empty())
                    rd.fail(product, key + ".breakdown.product", "expected a colorant name");
                br.rate = rd.rate(bt, key + ".breakdown");
                c.breakdown = br;
            }
            colorants_[name] = std::move(c);
        }
        // Breakdown products must exist (in this or an earlier file).
        for (const auto& [k, node] : rd.table(*cs, "colorants")) {
            const Colorant& c = colorants_.at(std::string(k.str()));
            if (c.breakdown && !colorants_.count(c.breakdown->product))
                rd.fail(*rd.table(node, "").get("breakdown"),
                        "colorants." + c.name + ".breakdown.product",
                        fmt::format("unknown colorant '{}'", c.breakdown->product));
        }
    }

    if (const toml::node* ms = root.get("materials")) {
        for (const auto& [k, node] : rd.table(*ms, "materials")) {
            const std::string name(k.str());
            const std::string key = "materials." + name;
            const toml::table& t = rd.table(node, key);
            rd.only_keys(t, key, {"description", "thickness_um", "substrate", "colorants"});
            if (materials_.count(name))
                rd.fail(node, key, "material defined twice");
            FadeMaterial m;
            m.name = name;
            m.file = file;
            if (const toml::node* d = t.get("description"))
                m.description = d->value_or(std::string());
            const toml::node& th = rd.required(t, key, "thickness_um");
            m.thickness_m = rd.number(th, key + ".thickness_um", 0.0) * 1e-6;
            if (!(m.thickness_m > 0.0))
                rd.fail(th, key + ".thickness_um", "must be > 0");
            if (const toml::node* s = t.get("substrate")) {
                m.substrate_reflectance = rd.spectrum(*s, key + ".substrate");
                for (double v : m.substrate_reflectance.value)
                    if (v > 1.0)
                        rd.fail(*s, key + ".substrate", "reflectance must be <= 1");
            }
            const toml::table& ct =
                rd.table(rd.required(t, key, "colorants"), key + ".colorants");
            for (const auto& [ck, cv] : ct) {
                const std::string cname(ck.str());
                auto it = colorants_.find(cname);
                if (it == colorants_.end())
                    rd.fail(cv, key + ".colorants." + cname, "unknown colorant");
                const double f = rd.number(cv, key + ".colorants." + cname, 0.0);
                if (f > 1.0)
                    rd.fail(cv, key + ".colorants." + cname, "volume fraction must be <= 1");
                m.colorants.push_back(it->second);
                m.initial_fractions.push_back(f);
            }
            // Breakdown products the material does not list start at fraction 0.
            for (size_t j = 0; j < m.colorants.size(); ++j) {
                if (!m.colorants[j].breakdown)
                    continue;
                const std::string& p = m.colorants[j].breakdown->product;
                const bool listed = std::any_of(m.colorants.begin(), m.colorants.end(),
                                                [&](const Colorant& c) { return c.name == p; });
                if (!listed) {
                    m.colorants.push_back(colorants_.at(p));
                    m.initial_fractions.push_back(0.0);
                }
            }
            try {
                m.validate();
            } catch (const std::runtime_error& e) {
                rd.fail(node, key, e.what());
            }
            materials_[name] = std::move(m);
        }
    }

    if (const toml::node* rs = root.get("rate_sets")) {
        for (const auto& [k, node] : rd.table(*rs, "rate_sets")) {
            const std::string name(k.str());
            const std::string key = "rate_sets." + name;
            RateSet set;
            for (const auto& [ck, cv] : rd.table(node, key)) {
                const std::string cname(ck.str());
                if (!colorants_.count(cname))
                    rd.fail(cv, key + "." + cname, "unknown colorant");
                set[cname] = rd.number(cv, key + "." + cname, 0.0);
            }
            rate_sets_[name] = std::move(set);
        }
    }
}

const FadeMaterial* FadeLibrary::find(const std::string& name) const
{
    auto it = materials_.find(name);
    return it == materials_.end() ? nullptr : &it->second;
}

const FadeMaterial& FadeLibrary::material(const std::string& name) const
{
    if (const FadeMaterial* m = find(name))
        return *m;
    std::string known;
    for (const auto& [n, m] : materials_)
        known += fmt::format("{}{}", known.empty() ? "" : ", ", n);
    throw std::runtime_error(fmt::format("unknown fade material '{}' (known: {})", name,
                                         known.empty() ? "none loaded" : known));
}

const Colorant& FadeLibrary::colorant(const std::string& name) const
{
    auto it = colorants_.find(name);
    if (it == colorants_.end())
        throw std::runtime_error(fmt::format("unknown colorant '{}'", name));
    return it->second;
}

const RateSet& FadeLibrary::rate_set(const std::string& name) const
{
    auto it = rate_sets_.find(name);
    if (it == rate_sets_.end())
        throw std::runtime_error(fmt::format("unknown rate set '{}'", name));
    return it->second;
}

std::vector<std::string> FadeLibrary::material_names() const
{
    std::vector<std::string> names;
    for (const auto& [n, m] : materials_)
        names.push_back(n);
    return names;
}

FadeMaterial FadeLibrary::material_with_rates(const std::string& name,
                                              const std::string& rates) const
{
    FadeMaterial m = material(name);
    if (rates.empty())
        return m;
    // The rates of the colorants this material holds (a set may name all of a family)
    RateSet held;
    for (const auto& [colorant, beta] : rate_set(rates))
        for (const Colorant& c : m.colorants)
            if (c.name == colorant)
                held[colorant] = beta;
    if (held.empty())
        throw std::runtime_error("rate set " + rates + " names none of " + m.name +
                                 "'s colorants");
    return with_rates(std::move(m), held);
}

std::vector<fs::path> FadeLibrary::default_files()
{
    return patina::shader_library_files("fade");
}

FadeLibrary FadeLibrary::load_files(const std::vector<fs::path>& files)
{
    FadeLibrary lib;
    for (const fs::path& f : files.empty() ? default_files() : files)
        lib.load(f);
    return lib;
}

}  // namespace patina::texgen::fade
