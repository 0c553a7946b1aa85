#include "host/host.h"

#include "core/color_management.h"
#include "core/rgb_spectrum.h"
#include "core/texture_access.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <cstdio>
#include <cstring>
#include <atomic>
#include <map>
#include <mutex>

// The opaque texture handle of abi.h: what the host needs to answer a lookup.
struct PatinaTexture {
    patina::TextureAccess::Handle* handle = nullptr;
    std::string path;
};

namespace patina {

namespace {
    // Errors reported by plugins during create(), kept per thread so that concurrent
    // creations never see each other's messages.
    thread_local std::vector<std::string> t_errors;
    // Tags a PatinaHost made by Host, so from_c can refuse foreign tables.
    constexpr uint64_t kHostMagic = 0x50415449'4e41484fULL;
}  // namespace

struct Host::Impl {
    // `table` must stay the first member: from_c() casts the table back to the Impl.
    PatinaHost table{};
    uint64_t magic = kHostMagic;
    const Host* owner = nullptr;
    const ColorManager* colors = nullptr;
    std::string name;
    std::string working_space;
    RgbToSpectrum uplift;
    TextureAccess textures;
    mutable std::mutex texture_mutex;
    mutable std::map<std::pair<std::string, std::string>, std::unique_ptr<PatinaTexture>> opened;
    mutable std::atomic<size_t> warnings{0};

    Impl(const ColorManager& c, std::string n)
        : colors(&c), name(std::move(n)), working_space(c.working_space()),
          uplift(c.working_rgb_to_xyz()), textures(c)
    {
    }

    static const Impl& of(const PatinaHost* h) { return *reinterpret_cast<const Impl*>(h); }
};

static_assert(std::is_standard_layout_v<PatinaHost>);

namespace {

    void host_error(const PatinaHost*, const char* shader, const char* message)
    {
        t_errors.push_back(fmt::format("{}", message ? message : "(no message)"));
        (void)shader;
    }

    void host_warning(const PatinaHost* h, const char* shader, const char* message)
    {
        ++Host::Impl::of(h).warnings;
        std::fprintf(stderr, "patina: warning: shader '%s': %s\n", shader ? shader : "?",
                     message ? message : "");
    }

    void host_rgb_to_spectrum(const PatinaHost* h, const float rgb[3], int is_illuminant,
                              PatinaRgbSpectrum* out)
    {
        *out = Host::Impl::of(h).uplift.uplift({rgb[0], rgb[1], rgb[2]}, is_illuminant != 0);
    }

    void host_eval_rgb_spectrum(const PatinaHost*, const PatinaRgbSpectrum* s,
                                const PatinaWavelengths* wl, float* out)
    {
        for (int i = 0; i < wl->count; ++i)
            out[i] = RgbToSpectrum::eval(*s, wl->lambda_nm[i]);
    }

    int host_texture_lookup(const PatinaHost* h, const PatinaTexture* tex,
                            const PatinaShadingContext* ctx, float u, float v, int first_channel,
                            int nchannels, float* out)
    {
        if (!tex || !tex->handle || nchannels <= 0) {
            for (int i = 0; i < nchannels; ++i)
                out[i] = 0.0f;
            return 0;
        }
        // Mesh uv has v up; OIIO's t runs down the image: t = 1 - v, and dt = -dv.
        const float dsdx = ctx ? ctx->duvdx[0] : 0.0f, dtdx = ctx ? -ctx->duvdx[1] : 0.0f;
        const float dsdy = ctx ? ctx->duvdy[0] : 0.0f, dtdy = ctx ? -ctx->duvdy[1] : 0.0f;
        const bool ok = Host::Impl::of(h).textures.lookup(tex->handle, u, 1.0f - v, dsdx, dtdx,
                                                         dsdy, dtdy, first_channel, nchannels,
                                                         out);
        if (!ok)
            for (int i = 0; i < nchannels; ++i)
                out[i] = 0.0f;
        return ok ? 1 : 0;
    }

    int copy3(const PatinaVec3& v, int n, float* out)
    {
        if (n < 3)
            return 0;
        out[0] = v.x;
        out[1] = v.y;
        out[2] = v.z;
        return 3;
    }

    int host_attribute(const PatinaHost*, const PatinaShadingContext* ctx, const char* name,
                       int n, float* out)
    {
        if (!ctx || !name || !out)
            return 0;
        const std::string_view a(name);
        if (a == "P") return copy3(ctx->P, n, out);
        if (a == "N") return copy3(ctx->N, n, out);
        if (a == "Ng") return copy3(ctx->Ng, n, out);
        if (a == "dPdu") return copy3(ctx->dPdu, n, out);
        if (a == "dPdv") return copy3(ctx->dPdv, n, out);
        if (a == "uv" && n >= 2) {
            out[0] = ctx->uv.x;
            out[1] = ctx->uv.y;
            return 2;
        }
        if (a == "primitive_id" && n >= 1) {
            out[0] = static_cast<float>(ctx->primitive_id);
            return 1;
        }
        if (a == "mesh_id" && n >= 1) {
            out[0] = static_cast<float>(ctx->mesh_id);
            return 1;
        }
        // Slab coordinates and per-vertex attributes arrive with the renderer and the
        // stone issue; until a host provides them the lookup reports "no such attribute".
        return 0;
    }

    const PatinaTexture* host_open_texture(const PatinaHost* h, const char* path,
                                           const char* colorspace)
    {
        const Host::Impl& impl = Host::Impl::of(h);
        if (!path || !*path) {
            host_error(h, nullptr, "open_texture: no file name given");
            return nullptr;
        }
        try {
            return impl.owner->open_texture(path, colorspace && *colorspace ? colorspace : "raw");
        } catch (const std::exception& e) {
            host_error(h, nullptr, e.what());
            return nullptr;
        }
    }

    int host_read_image(const PatinaHost* h, const char* path, int subimage, int dims[3],
                        float* out, size_t capacity)
    {
        auto input = OIIO::ImageInput::open(path ? path : "");
        if (!input) {
            host_error(h, nullptr,
                       fmt::format("cannot read '{}': {}", path ? path : "", OIIO::geterror())
                           .c_str());
            return 0;
        }
        if (subimage < 0 || !input->seek_subimage(subimage, 0)) {
            // Say what is there: a volume cut short by a crash or a full disk reads as a file
            // with fewer parts than its header promises.
            std::string why = input->geterror();
            int readable = 0;
            while (input->seek_subimage(readable, 0))
                ++readable;
            input->geterror();  // (clear)
            host_error(h, nullptr,
                       fmt::format("cannot read part {} of '{}': the file has {} readable "
                                   "part{}{}{} (truncated, or not the file expected?)",
                                   subimage, path, readable, readable == 1 ? "" : "s",
                                   why.empty() ? "" : "; ", why)
                           .c_str());
            return 0;
        }
        const OIIO::ImageSpec& spec = input->spec();
        dims[0] = spec.width;
        dims[1] = spec.height;
        dims[2] = spec.nchannels;
        if (!out)
            return 1;
        const size_t need = size_t(spec.width) * spec.height * spec.nchannels;
        if (capacity < need) {
            host_error(h, nullptr,
                       fmt::format("read_image '{}': buffer of {} floats, need {}", path,
                                   capacity, need)
                           .c_str());
            return 0;
        }
        if (!input->read_image(subimage, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out)) {
            host_error(h, nullptr,
                       fmt::format("cannot read '{}': {}", path, input->geterror()).c_str());
            return 0;
        }
        return 1;
    }

}  // namespace

Host::Host(const ColorManager& colors, std::string host_name)
    : impl_(std::make_unique<Impl>(colors, std::move(host_name)))
{
    impl_->owner = this;
    PatinaHost& t = impl_->table;
    t.size = sizeof(PatinaHost);
    t.abi_version = PATINA_ABI_VERSION;
    t.host_name = impl_->name.c_str();
    t.working_space = impl_->working_space.c_str();
    t.error = host_error;
    t.warning = host_warning;
    t.rgb_to_spectrum = host_rgb_to_spectrum;
    t.eval_rgb_spectrum = host_eval_rgb_spectrum;
    t.texture_lookup = host_texture_lookup;
    t.attribute = host_attribute;
    t.open_texture = host_open_texture;
    t.read_image = host_read_image;
}

Host::~Host() = default;

const PatinaHost* Host::c_host() const { return &impl_->table; }

const Host* Host::from_c(const PatinaHost* host)
{
    if (!host || host->error != host_error)
        return nullptr;
    const Impl& impl = Impl::of(host);
    return impl.magic == kHostMagic ? impl.owner : nullptr;
}

const ColorManager& Host::colors() const { return *impl_->colors; }

PatinaRgbSpectrum Host::uplift(const float rgb[3], bool illuminant) const
{
    return impl_->uplift.uplift({rgb[0], rgb[1], rgb[2]}, illuminant);
}

const PatinaTexture* Host::open_texture(const std::string& path, const std::string& colorspace) const
{
    std::lock_guard lock(impl_->texture_mutex);
    auto key = std::make_pair(path, colorspace);
    auto it = impl_->opened.find(key);
    if (it != impl_->opened.end())
        return it->second.get();
    auto tex = std::make_unique<PatinaTexture>();
    tex->handle = impl_->textures.open(path, colorspace);
    tex->path = path;
    return impl_->opened.emplace(key, std::move(tex)).first->second.get();
}

std::vector<std::string> Host::take_errors() const
{
    std::vector<std::string> out;
    out.swap(t_errors);
    return out;
}

size_t Host::warning_count() const { return impl_->warnings.load(); }

Host& default_host()
{
    static ColorManager colors(ColorManager::default_config_path());
    static Host host(colors, fmt::format("patina {}", PATINA_VERSION_STRING));
    return host;
}

}  // namespace patina
