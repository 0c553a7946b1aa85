#include "texgen/patina/interpreter.h"

#include "core/cancel.h"
#include "core/embree_scene.h"
#include "core/progress.h"
#include "core/sampling.h"
#include "texgen/accessibility/offset_surface_baker.h"
#include "texgen/accessibility/tangent_sphere_baker.h"
#include "texgen/bake/bake_driver.h"
#include "texgen/growth/growth_model.h"
#include "texgen/patina/heightfield_offset.h"
#include "texgen/patina/operators.h"
#include "texgen/stack/surface_map.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

    constexpr double kMicrometresPerMetre = 1e6;

    /// A value per domain node, or one value for all (numbers, t, curves).
    struct Field {
        bool uniform = true;
        float value = 0.0f;
        std::vector<float> values;

        float at(size_t i) const { return uniform ? value : values[i]; }
    };

    Field uniform_field(double v) { return Field{true, static_cast<float>(v), {}}; }

    template <class F>
    Field map_fields(const std::vector<const Field*>& in, size_t n, F&& f)
    {
        bool all_uniform = true;
        for (const Field* x : in)
            all_uniform = all_uniform && x->uniform;
        float args[3] = {0, 0, 0};
        if (all_uniform) {
            for (size_t k = 0; k < in.size(); ++k)
                args[k] = in[k]->value;
            return Field{true, f(args), {}};
        }
        Field out{false, 0.0f, std::vector<float>(n)};
        for (size_t i = 0; i < n; ++i) {
            for (size_t k = 0; k < in.size(); ++k)
                args[k] = in[k]->at(i);
            out.values[i] = f(args);
        }
        return out;
    }

    /// The texture parameters a script may set (texture(DPD linear 5 40 patch_size=0.002)),
    /// each a field of GrowthParameters; `seed` offsets the statement's random stream.
    const std::map<std::string, double GrowthParameters::*>& texture_double_parameters()
    {
        static const std::map<std::string, double GrowthParameters::*> m = {
            {"layers", &GrowthParameters::layers},
            {"relaxation_radius", &GrowthParameters::relaxation_radius},
            {"patch_size", &GrowthParameters::patch_size},
            {"blocked_fraction", &GrowthParameters::blocked_fraction},
            {"seed_density", &GrowthParameters::seed_density},
            {"new_seed_ratio", &GrowthParameters::new_seed_ratio},
            {"spread_distance", &GrowthParameters::spread_distance},
            {"advance_unblocked", &GrowthParameters::advance_unblocked},
            {"advance_blocked", &GrowthParameters::advance_blocked},
            {"st_spacing", &GrowthParameters::st_spacing},
            {"noise_amplitude", &GrowthParameters::noise_amplitude},
            {"feature_size", &GrowthParameters::feature_size},
        };
        return m;
    }
    const std::map<std::string, int GrowthParameters::*>& texture_int_parameters()
    {
        static const std::map<std::string, int GrowthParameters::*> m = {
            {"levels", &GrowthParameters::levels},
            {"octaves", &GrowthParameters::octaves},
        };
        return m;
    }

    std::vector<std::string> texture_parameter_names()
    {
        std::vector<std::string> names{"seed"};
        for (const auto& [k, v] : texture_double_parameters())
            names.push_back(k);
        for (const auto& [k, v] : texture_int_parameters())
            names.push_back(k);
        return names;
    }

    void collect_textures(const Expr& e, std::vector<const Expr*>& out)
    {
        if (e.kind == ExprKind::Texture)
            out.push_back(&e);
        for (const Expr& o : e.operands)
            collect_textures(o, out);
    }

    const std::optional<Expr>* map_of(const Statement& s)
    {
        if (const auto* c = std::get_if<CoatStatement>(&s))
            return &c->map;
        if (const auto* e = std::get_if<ErodeStatement>(&s))
            return &e->map;
        if (const auto* f = std::get_if<FillStatement>(&s))
            return &f->map;
        if (const auto* p = std::get_if<PolishStatement>(&s))
            return &p->map;
        return nullptr;
    }

    /// Every texture(...) of the script, in the order written (lets included once).
    std::vector<const Expr*> textures_of(const Script& script)
    {
        std::vector<const Expr*> out;
        for (const Statement& s : script.statements) {
            if (const auto* m = map_of(s); m && m->has_value())
                collect_textures(**m, out);
            if (const auto* l = std::get_if<LetStatement>(&s))
                collect_textures(l->value, out);
        }
        return out;
    }

    double end_time_of(const InterpreterOptions& o)
    {
        if (o.end_time_years > 0.0)
            return o.end_time_years;
        return o.times_years.empty() ? 0.0 : o.times_years.back();
    }

    class Interpreter {
    public:
        Interpreter(const Script& script, const MaterialLibrary& library,
                    const PatinaDomain& domain, const InterpreterOptions& options)
            : script_(script), library_(library), domain_(domain), options_(options)
        {
        }

        std::vector<PatinaStep> run()
        {
            check_times();
            grow_textures();
            std::vector<PatinaStep> steps;
            for (size_t k = 0; k < options_.times_years.size(); ++k) {
                throw_if_cancelled();
                steps.push_back(run_step(k));
                if (options_.progress)
                    options_.progress->step();
            }
            return steps;
        }

    private:
        [[noreturn]] void fail(SourceLocation where, const std::string& message) const
        {
            throw ScriptError(script_.file_name, where, message);
        }

        void check_times() const
        {
            const auto& t = options_.times_years;
            if (t.empty())
                throw std::runtime_error("--times: no time steps");
            for (size_t i = 0; i < t.size(); ++i) {
                if (!std::isfinite(t[i]) || t[i] < 0.0)
                    throw std::runtime_error(fmt::format("--times: {} is not a time >= 0", t[i]));
                if (i > 0 && !(t[i] > t[i - 1]))
                    throw std::runtime_error("--times must ascend");
            }
            if (end_time_of(options_) < t.back())
                throw std::runtime_error(fmt::format("--end-time {} is before the last time {}",
                                                     end_time_of(options_), t.back()));
        }

        GrowthSpec spec_of(const Expr& e, uint64_t& seed) const
        {
            const TextureCall& call = e.texture;
            GrowthSpec spec;
            // The parser checked the names; a mismatch here is a bug.
            spec.model = growth_model_from_name(call.model).value();
            spec.rate = growth_rate_from_name(call.rate).value();
            spec.step = call.step;
            spec.total = call.total;
            for (const TextureParameter& p : call.parameters) {
                if (p.name == "seed") {
                    seed = hash_values(seed, static_cast<uint64_t>(std::llround(p.value)), 0x5eed);
                } else if (auto d = texture_double_parameters().find(p.name);
                           d != texture_double_parameters().end()) {
                    spec.parameters.*(d->second) = p.value;
                } else if (auto i = texture_int_parameters().find(p.name);
                           i != texture_int_parameters().end()) {
                    // (Checked before the conversion: a double outside int's range does not
                    // convert to any int.)
                    if (p.value != std::floor(p.value) || p.value < -1e9 || p.value > 1e9)
                        fail(p.location, fmt::format("texture parameter '{}' must be a whole "
                                                     "number (got {})", p.name, p.value));
                    spec.parameters.*(i->second) = static_cast<int>(p.value);
                } else {
                    const std::vector<std::string> names = texture_parameter_names();
                    fail(p.location, fmt::format("unknown texture parameter '{}'{} (known: {})",
                                                 p.name, did_you_mean(p.name, names),
                                                 fmt::join(names, ", ")));
                }
            }
            return spec;
        }

        /// Grow every texture of the script once, for every time step (D&H 1996 §3.3).
        void grow_textures()
        {
            const double T = end_time_of(options_);
            const std::vector<const Expr*> textures = textures_of(script_);
            for (size_t k = 0; k < textures.size(); ++k) {
                const Expr& e = *textures[k];
                uint64_t seed = hash_values(options_.seed, k, 0x7e47);
                GrowthSpec spec = spec_of(e, seed);
                std::vector<double> fractions;
                for (double t : options_.times_years)
                    fractions.push_back(std::clamp(
                        growth_fraction(spec) * (T > 0.0 ? t / T : 1.0), 0.0, 1.0));
                // The coat's thickness is the layer's maximum (§3.2: "a specified maximum
                // thickness that is modulated by the thickness map") at the time the script
                // describes: the maps are normalised by their maximum at STEP / TOTAL.
                fractions.push_back(growth_fraction(spec));
                std::vector<std::vector<float>> maps;
                try {
                    maps = grow(domain_.lattice, spec, seed, fractions);
                } catch (const std::invalid_argument& err) {
                    fail(e.location, fmt::format("{}: {}", to_string(e), err.what()));
                }
                const std::vector<float>& at_script_time = maps.back();
                const float peak = at_script_time.empty()
                                       ? 0.0f
                                       : *std::max_element(at_script_time.begin(),
                                                           at_script_time.end());
                maps.pop_back();
                for (std::vector<float>& m : maps)
                    for (float& v : m)
                        v = peak > 0.0f ? std::min(v / peak, 1.0f) : 0.0f;
                grown_[&e] = std::move(maps);
                if (options_.progress)
                    options_.progress->step();
            }
        }

        const std::vector<float>& map_values(const MapStatement& m)
        {
            auto it = maps_.find(&m);
            if (it != maps_.end())
                return it->second;
            if (!m.material.empty()) {
                try {
                    return maps_.emplace(&m, material_fraction(domain_, m.material)).first->second;
                } catch (const std::exception& err) {
                    fail(m.location, fmt::format("map '{}': {}", m.name, err.what()));
                }
            }
            fs::path path = m.path;
            if (path.is_relative())
                path = options_.script_dir / path;
            std::vector<std::string> channels;
            if (!m.channel.empty()) {
                channels.push_back(m.channel);
            } else {
                // The file's first channel.
                auto in = OIIO::ImageInput::open(path.string());
                if (!in)
                    fail(m.location, fmt::format("map '{}': cannot read '{}'", m.name,
                                                 path.string()));
                channels.push_back(in->spec().channelnames.at(0));
            }
            std::vector<float> values(domain_.size());
            try {
                SurfaceMap map(path, channels, fmt::format("map '{}'", m.name),
                               options_.ocio_config);
                for (size_t i = 0; i < values.size(); ++i)
                    values[i] = map.at(domain_.uv[i]);
            } catch (const ScriptError&) {
                throw;
            } catch (const std::exception& err) {
                fail(m.location, err.what());
            }
            return maps_.emplace(&m, std::move(values)).first->second;
        }

        Field eval(const Expr& e, size_t step)
        {
            const size_t n = domain_.size();
            switch (e.kind) {
            case ExprKind::Number:
                return uniform_field(e.number);
            case ExprKind::Negate: {
                Field a = eval(e.operands[0], step);
                return map_fields({&a}, n, [](const float* v) { return -v[0]; });
            }
            case ExprKind::Add:
            case ExprKind::Subtract:
            case ExprKind::Multiply:
            case ExprKind::Divide: {
                Field a = eval(e.operands[0], step);
                Field b = eval(e.operands[1], step);
                switch (e.kind) {
                case ExprKind::Add:
                    return map_fields({&a, &b}, n, [](const float* v) { return v[0] + v[1]; });
                case ExprKind::Subtract:
                    return map_fields({&a, &b}, n, [](const float* v) { return v[0] - v[1]; });
                case ExprKind::Multiply:
                    return map_fields({&a, &b}, n, [](const float* v) { return v[0] * v[1]; });
                default:
                    return map_fields({&a, &b}, n, [](const float* v) { return v[0] / v[1]; });
                }
            }
            case ExprKind::Texture: {
                Field f;
                f.uniform = false;
                f.values = grown_.at(&e)[step];
                return f;
            }
            case ExprKind::Name:
                return eval_name(e, step);
            case ExprKind::Call:
                return eval_call(e, step);
            }
            fail(e.location, "unknown expression");
        }

        Field eval_name(const Expr& e, size_t step)
        {
            const size_t n = domain_.size();
            switch (e.name_kind) {
            case NameKind::Let:
                return eval(*lets_.at(e.name), step);
            case NameKind::Curve:
                return uniform_field(curve_at(*curves_.at(e.name), options_.times_years[step]));
            case NameKind::Map: {
                Field f;
                f.uniform = false;
                f.values = map_values(*maps_by_name_.at(e.name));
                return f;
            }
            case NameKind::Field:
                break;
            }
            if (e.name == "t")
                return uniform_field(options_.times_years[step]);
            Field f{false, 0.0f, std::vector<float>(n)};
            if (e.name == "inclination") {
                for (size_t i = 0; i < n; ++i)
                    f.values[i] = domain_.normal[i].y;
            } else if (e.name == "facing_south") {
                for (size_t i = 0; i < n; ++i)
                    f.values[i] = domain_.normal[i].z;
            } else if (e.name == "height") {
                const float lo = domain_.bounds.min.y;
                const float extent = domain_.bounds.max.y - lo;
                for (size_t i = 0; i < n; ++i)
                    f.values[i] = extent > 0.0f ? (domain_.position[i].y - lo) / extent : 0.0f;
            } else {
                fail(e.location, fmt::format("built-in field '{}' has no value here", e.name));
            }
            return f;
        }

        static double curve_at(const CurveStatement& c, double t)
        {
            const auto& p = c.points;
            if (t <= p.front().time_years)
                return p.front().value;
            if (t >= p.back().time_years)
                return p.back().value;
            for (size_t i = 1; i < p.size(); ++i) {
                if (t <= p[i].time_years) {
                    const double s = (t - p[i - 1].time_years) /
                                     (p[i].time_years - p[i - 1].time_years);
                    return p[i - 1].value + s * (p[i].value - p[i - 1].value);
                }
            }
            return p.back().value;
        }

        Field eval_call(const Expr& e, size_t step)
        {
            const size_t n = domain_.size();
            std::vector<Field> args;
            for (const Expr& o : e.operands)
                args.push_back(eval(o, step));
            std::vector<const Field*> in;
            for (const Field& a : args)
                in.push_back(&a);
            const std::string& f = e.name;
            if (f == "clamp")
                return map_fields(in, n, [](const float* v) {
                    return std::min(std::max(v[0], v[1]), v[2]);
                });
            if (f == "min")
                return map_fields(in, n, [](const float* v) { return std::min(v[0], v[1]); });
            if (f == "max")
                return map_fields(in, n, [](const float* v) { return std::max(v[0], v[1]); });
            if (f == "smoothstep")
                return map_fields(in, n, [](const float* v) {
                    if (v[1] == v[0])
                        return v[2] < v[0] ? 0.0f : 1.0f;
                    const float s = std::clamp((v[2] - v[0]) / (v[1] - v[0]), 0.0f, 1.0f);
                    return s * s * (3.0f - 2.0f * s);
                });
            if (f == "mix")
                return map_fields(in, n,
                                  [](const float* v) { return v[0] + (v[1] - v[0]) * v[2]; });
            if (f == "pow")
                return map_fields(in, n, [](const float* v) { return std::pow(v[0], v[1]); });
            if (f == "abs")
                return map_fields(in, n, [](const float* v) { return std::abs(v[0]); });
            if (f == "step")
                return map_fields(in, n, [](const float* v) { return v[1] < v[0] ? 0.0f : 1.0f; });
            fail(e.location, fmt::format("function '{}' is known to the parser but not to the "
                                         "interpreter", f));
        }

        /// amount * map per node, checked: a NaN or infinity names the texel; negative
        /// values (a map may dip below 0) count as 0.
        std::vector<float> amounts(double amount, const std::optional<Expr>& map, size_t step)
        {
            const size_t n = domain_.size();
            std::vector<float> out(n, static_cast<float>(amount));
            if (!map)
                return out;
            const Field f = eval(*map, step);
            for (size_t i = 0; i < n; ++i) {
                const float v = static_cast<float>(amount) * f.at(i);
                if (!std::isfinite(v))
                    fail(map->location, fmt::format("the map {} is {} at node {} (uv {}, {})",
                                                    to_string(*map),
                                                    std::isnan(v) ? "NaN" : "infinite", i,
                                                    domain_.uv[i].x, domain_.uv[i].y));
                out[i] = std::max(v, 0.0f);
            }
            return out;
        }

        int material_id(const std::string& name, SourceLocation where)
        {
            const PatinaMaterial* m = library_.find(name);
            if (!m)
                fail(where, fmt::format("unknown material '{}'", name));
            const auto it = std::find(materials_.begin(), materials_.end(), m);
            if (it != materials_.end())
                return static_cast<int>(it - materials_.begin());
            materials_.push_back(m);
            return static_cast<int>(materials_.size() - 1);
        }

        std::string made_by(const Statement& s) const
        {
            return fmt::format("{} at {}:{}", keyword_of(s), script_.file_name,
                               to_string(location_of(s)));
        }

        /// Fill thickness of `offset` (µm per node): Miller's accessibility at radius r.
        std::vector<float> offset_fill(const OffsetStatement& o, const LayerStack& stack)
        {
            const double r = o.radius_m;
            if (domain_.is_strip) {
                // The strip's surface is the height field of the stack itself.
                const std::vector<float> heights = stack.total_heights();
                const auto cell_um = static_cast<float>(domain_.cell_size_m * kMicrometresPerMetre);
                const auto r_um = static_cast<float>(r * kMicrometresPerMetre);
                return o.variant == OffsetStatement::Variant::Closing
                           ? closing_fill(heights, domain_.width, domain_.height, cell_um, r_um,
                                          domain_.boundary)
                           : tangent_sphere_fill(heights, domain_.width, domain_.height,
                                                 cell_um, r_um, domain_.boundary);
            }
            // On a mesh the layers are thin against the mesh (§3.1): the accessibility of
            // the base surface decides, baked once per radius and variant.
            const auto key = std::make_pair(r, o.variant);
            if (auto it = offset_cache_.find(key); it != offset_cache_.end())
                return it->second;
            if (!scene_) {
                scene_ = std::make_unique<EmbreeScene>();
                scene_->add_mesh(*domain_.mesh);
                scene_->commit();
            }
            std::unique_ptr<SampleBaker> baker;
            if (o.variant == OffsetStatement::Variant::Closing) {
                OffsetSurfaceOptions opt;
                opt.radius = static_cast<float>(r);
                opt.voxels = options_.offset_voxels;
                baker = std::make_unique<OffsetSurfaceBaker>(*scene_, domain_.bounds, opt);
            } else {
                TangentSphereOptions opt;
                opt.max_radius = static_cast<float>(r);
                baker = std::make_unique<TangentSphereBaker>(*scene_, opt);
            }
            std::vector<float> fill;
            for (const TexelGrid& grid : domain_.grids) {
                BakeRun run;
                run.seed = options_.seed;
                run.stream = static_cast<uint64_t>(grid.udim);
                const std::vector<float> v = bake_groups(grid.groups, *baker, run);
                for (size_t g = 0; g < grid.groups.group_count(); ++g) {
                    // Channel 1: offset_height (m) or accessibility_radius (m).
                    const float value = v[2 * g + 1];
                    fill.push_back(o.variant == OffsetStatement::Variant::Closing
                                       ? static_cast<float>(value * kMicrometresPerMetre)
                                       : static_cast<float>(fill_from_tangent_radius(value, static_cast<float>(r)) *
                                                            kMicrometresPerMetre));
                }
            }
            return offset_cache_.emplace(key, std::move(fill)).first->second;
        }

        PatinaStep run_step(size_t step)
        {
            const size_t n = domain_.size();
            std::optional<LayerStack> stack;
            std::vector<std::string> origins;
            lets_.clear();
            curves_.clear();
            maps_by_name_.clear();
            auto need_stack = [&](const Statement& s) -> LayerStack& {
                if (!stack)
                    fail(location_of(s), fmt::format("'{}' before 'new': a script starts its "
                                                     "stack with new MATERIAL", keyword_of(s)));
                return *stack;
            };
            bool rendered = false;
            for (const Statement& s : script_.statements) {
                if (rendered)
                    break;
                try {
                    if (const auto* st = std::get_if<NewStatement>(&s)) {
                        if (stack)
                            fail(st->location, "a second 'new': a script describes one stack");
                        stack = new_stack(material_id(st->material, st->location), n);
                    } else if (const auto* c = std::get_if<CoatStatement>(&s)) {
                        LayerStack& k = need_stack(s);
                        coat(k, material_id(c->material, c->material_location), 1.0f,
                             amounts(c->thickness_um, c->map, step));
                        origins.push_back(made_by(s));
                    } else if (const auto* er = std::get_if<ErodeStatement>(&s)) {
                        erode(need_stack(s), 1.0f,
                              amounts(er->thickness_um, er->map, step));
                    } else if (const auto* fi = std::get_if<FillStatement>(&s)) {
                        LayerStack& k = need_stack(s);
                        fill(k, material_id(fi->material, fi->material_location), 1.0f,
                             amounts(fi->height_um, fi->map, step));
                        origins.push_back(made_by(s));
                    } else if (const auto* p = std::get_if<PolishStatement>(&s)) {
                        LayerStack& k = need_stack(s);
                        if (p->mode == PolishStatement::Mode::ToHeight)
                            polish(k, 1.0f, amounts(p->height_um, p->map, step));
                        else
                            polish_until_exposed(k, static_cast<float>(p->exposed_fraction),
                                                 domain_.area_weight);
                    } else if (const auto* o = std::get_if<OffsetStatement>(&s)) {
                        LayerStack& k = need_stack(s);
                        const int id = material_id(o->material, o->material_location);
                        const std::vector<float> f = offset_fill(*o, k);
                        offset(k, id, f);
                        origins.push_back(made_by(s));
                    } else if (std::holds_alternative<RenderStatement>(s)) {
                        need_stack(s);
                        rendered = true;
                    } else if (const auto* m = std::get_if<MapStatement>(&s)) {
                        maps_by_name_[m->name] = m;
                    } else if (const auto* cu = std::get_if<CurveStatement>(&s)) {
                        curves_[cu->name] = cu;
                    } else if (const auto* l = std::get_if<LetStatement>(&s)) {
                        lets_[l->name] = &l->value;
                    }
                } catch (const ScriptError&) {
                    throw;
                } catch (const Cancelled&) {
                    throw;
                } catch (const std::exception& err) {
                    fail(location_of(s), fmt::format("{}: {}", keyword_of(s), err.what()));
                }
            }
            if (!stack)
                throw ScriptError(script_.file_name, SourceLocation{},
                                  "the script has no 'new MATERIAL': nothing to write");

            PatinaStep out;
            out.time_years = options_.times_years[step];
            out.base = materials_.at(stack->base_material);
            out.total_um = stack->total_heights();
            for (size_t l = 0; l < stack->layers.size(); ++l) {
                ResultLayer layer;
                layer.material = materials_.at(stack->layers[l].material);
                layer.made_by = l < origins.size() ? origins[l] : std::string();
                layer.thickness_um = std::move(stack->layers[l].thickness_um);
                out.layers.push_back(std::move(layer));
            }
            return out;
        }

        const Script& script_;
        const MaterialLibrary& library_;
        const PatinaDomain& domain_;
        const InterpreterOptions& options_;
        std::map<const Expr*, std::vector<std::vector<float>>> grown_;
        std::map<const MapStatement*, std::vector<float>> maps_;
        std::map<std::string, const Expr*> lets_;
        std::map<std::string, const CurveStatement*> curves_;
        std::map<std::string, const MapStatement*> maps_by_name_;
        std::vector<const PatinaMaterial*> materials_;
        std::unique_ptr<EmbreeScene> scene_;
        std::map<std::pair<double, OffsetStatement::Variant>, std::vector<float>> offset_cache_;
    };

}  // namespace

size_t patina_work_units(const Script& script, const InterpreterOptions& options)
{
    return textures_of(script).size() + options.times_years.size();
}

std::vector<PatinaStep> run_patina_script(const Script& script, const MaterialLibrary& library,
                                          const PatinaDomain& domain,
                                          const InterpreterOptions& options)
{
    return Interpreter(script, library, domain, options).run();
}

}  // namespace patina::texgen
