#include "texgen/forecast/policy_file.h"

#include "core/data_files.h"
#include "formats/toml_location.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>

namespace patina::texgen::forecast {

namespace fs = std::filesystem;

namespace {

class Reader {
public:
    explicit Reader(const fs::path& file) : file_(file), dir_(file.parent_path()) {}

    [[noreturn]] void fail(const toml::node& node, const std::string& key,
                           const std::string& what) const
    {
        formats::toml_fail(file_, &node, key + ": " + what);
    }

    void only_keys(const toml::table& t, const std::string& where,
                   std::initializer_list<const char*> allowed) const
    {
        formats::toml_check_keys(file_, t, where, allowed);
    }

    double number(const toml::table& t, const std::string& where, const char* key, double fallback,
                  double min, double max) const
    {
        const toml::node* n = t.get(key);
        if (!n)
            return fallback;
        const std::optional<double> v = n->value<double>();
        if (!v)
            fail(*n, where + key, "expected a number");
        if (!(*v >= min && *v <= max))
            fail(*n, where + key, fmt::format("must be in {}-{}, got {}", min, max, *v));
        return *v;
    }

    std::string text(const toml::node& n, const std::string& key) const
    {
        const std::optional<std::string> s = n.value<std::string>();
        if (!s)
            fail(n, key, "expected a string");
        return *s;
    }

    // A file named in the policy file is relative to it.
    std::string path_text(const std::string& text) const
    {
        const size_t colon = text.rfind(':');
        const std::string file = colon == std::string::npos ? text : text.substr(0, colon);
        const std::string rest = colon == std::string::npos ? "" : text.substr(colon);
        const fs::path p(file);
        if (p.is_absolute() || !fs::exists(dir_ / p))
            return text;
        return (dir_ / p).string() + rest;
    }
    fs::path path(const std::string& text) const
    {
        const fs::path p(text);
        return p.is_absolute() ? p : dir_ / p;
    }

    LightingPolicy policy(const toml::table& t, size_t index) const
    {
        const std::string where = fmt::format("policy[{}].", index);
        only_keys(t, where, {"name", "lamp", "lux", "hours_per_day", "days_per_year", "uv_filter",
                             "daylight", "exposure"});
        LightingPolicy p;
        const toml::node* name = t.get("name");
        if (!name)
            fail(t, where.substr(0, where.size() - 1), "missing key 'name'");
        p.name = text(*name, where + "name");
        const toml::node* daylight = t.get("daylight");
        const toml::node* exposure = t.get("exposure");
        if (daylight && exposure)
            fail(*exposure, where + "exposure", "a policy has daylight or an exposure map, not both");
        // Lamp
        try {
            if (const toml::node* lamp = t.get("lamp"))
                p.lamp = parse_lamp(path_text(text(*lamp, where + "lamp")));
            else if (!exposure)
                p.lamp = fade::illuminant_by_name("D65");
        } catch (const std::runtime_error& e) {
            fail(*t.get("lamp"), where + "lamp", e.what());
        }
        if (!daylight && !exposure) {
            if (!t.get("lamp"))
                fail(t, where.substr(0, where.size() - 1),
                     "missing key 'lamp' (or 'daylight', or 'exposure')");
            if (!t.get("lux"))
                fail(t, where.substr(0, where.size() - 1), "missing key 'lux'");
        }
        p.lux = number(t, where, "lux", 0.0, 0.0, 1e7);
        p.hours_per_day = number(t, where, "hours_per_day", 8.0, 0.0, 24.0);
        p.days_per_year = number(t, where, "days_per_year", 365.0, 0.0, 366.0);
        if (const toml::node* f = t.get("uv_filter")) {
            std::string spec;
            if (const std::optional<double> v = f->value<double>())
                spec = fmt::format("{}", *v);
            else
                spec = path_text(text(*f, where + "uv_filter"));
            try {
                p.filter = parse_uv_filter(spec, where + "uv_filter");
            } catch (const std::runtime_error& e) {
                fail(*f, where + "uv_filter", e.what());
            }
        } else if (daylight) {
            p.filter = window_glass();
        }
        if (daylight) {
            const toml::table* d = daylight->as_table();
            if (!d)
                fail(*daylight, where + "daylight", "expected a table { epw, facing, share }");
            const std::string dw = where + "daylight.";
            only_keys(*d, dw, {"epw", "facing", "share", "ground_albedo"});
            DaylightSource s;
            const toml::node* epw = d->get("epw");
            if (!epw)
                fail(*daylight, where + "daylight", "missing key 'epw'");
            s.epw = path(text(*epw, dw + "epw"));
            if (!fs::exists(s.epw))
                fail(*epw, dw + "epw", "no such file: " + s.epw.string());
            if (const toml::node* facing = d->get("facing")) {
                if (const std::optional<double> deg = facing->value<double>()) {
                    s.facing_azimuth_deg = *deg;
                } else {
                    const std::string f = text(*facing, dw + "facing");
                    const std::pair<const char*, double> compass[] = {
                        {"north", 0.0}, {"east", 90.0}, {"south", 180.0}, {"west", 270.0}};
                    auto it = std::find_if(std::begin(compass), std::end(compass),
                                           [&](const auto& c) { return f == c.first; });
                    if (it == std::end(compass))
                        fail(*facing, dw + "facing",
                             "north, east, south, west or degrees clockwise from north");
                    s.facing_azimuth_deg = it->second;
                }
            }
            s.share = number(*d, dw, "share", 1.0, 0.0, 1.0);
            s.ground_albedo = number(*d, dw, "ground_albedo", 0.2, 0.0, 1.0);
            p.daylight = s;
        }
        if (exposure) {
            const toml::table* e = exposure->as_table();
            if (!e)
                fail(*exposure, where + "exposure", "expected a table { map, scale, channel }");
            const std::string ew = where + "exposure.";
            only_keys(*e, ew, {"map", "scale", "channel"});
            ExposureMapSource s;
            const toml::node* map = e->get("map");
            if (!map)
                fail(*exposure, where + "exposure", "missing key 'map'");
            s.map = path(text(*map, ew + "map"));
            s.scale = number(*e, ew, "scale", 1.0, 0.0, 1e12);
            if (const toml::node* c = e->get("channel"))
                s.channel = text(*c, ew + "channel");
            if (!t.get("lamp")) {
                // The map's own spectrum (the exposure baker records it), else D65
                const fade::ExposureMap m = fade::read_exposure_map(s.map, s.channel);
                p.lamp = m.illuminant_nm.empty()
                             ? fade::illuminant_by_name(m.illuminant.empty() ? "D65" : m.illuminant)
                             : fade::illuminant_from_table(m.illuminant.empty() ? "exposure map"
                                                                                : m.illuminant,
                                                           m.illuminant_nm, m.illuminant_value);
            }
            p.exposure = s;
        }
        return p;
    }

private:
    fs::path file_, dir_;
};

}  // namespace

UvFilter window_glass()
{
    UvFilter f = parse_uv_filter(find_data_file("filters/window_glass.csv").string(), "glazing");
    f.label = "window glass";
    return f;
}

std::vector<LightingPolicy> read_policy_file(const fs::path& file)
{
    if (!fs::exists(file))
        throw std::runtime_error(file.string() + ": no such policy file");
    const toml::table root = formats::parse_toml_file(file);
    const Reader rd(file);
    rd.only_keys(root, "", {"policy"});
    const toml::node* list = root.get("policy");
    const toml::array* policies = list ? list->as_array() : nullptr;
    if (!policies || policies->empty())
        formats::toml_fail(file, list, "no [[policy]] tables");
    std::vector<LightingPolicy> out;
    std::set<std::string> names;
    for (size_t i = 0; i < policies->size(); ++i) {
        const toml::node& node = *policies->get(i);
        const toml::table* t = node.as_table();
        if (!t)
            rd.fail(node, fmt::format("policy[{}]", i), "expected a table");
        out.push_back(rd.policy(*t, i));
        if (!names.insert(out.back().name).second)
            rd.fail(*t->get("name"), fmt::format("policy[{}].name", i),
                    "another policy has the name '" + out.back().name + "'");
    }
    return out;
}

}  // namespace patina::texgen::forecast
