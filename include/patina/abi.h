/*
 * patina/abi.h — the Patina shading-plugin ABI, version 1.
 *
 * This header is the whole contract between a Patina host (patina-render, the texgen tools,
 * a studio's own renderer) and a shading plugin. It is plain C (C99) so that a
 * plugin built with another compiler or C++ standard library still loads. Nothing else is
 * needed to write a plugin; the optional C++ helpers in <patina/shading/...> are header-only.
 *
 * ---------------------------------------------------------------------------------------
 * 1. What a plugin is
 * ---------------------------------------------------------------------------------------
 * A plugin is a shared library (.so) exporting exactly two symbols with C linkage:
 *
 *     PATINA_PLUGIN_DEFINE_VERSION;   (defines const int patina_plugin_abi_version)
 *     PATINA_PLUGIN_ENTRY_DECL const PatinaPluginInfo* patina_plugin_entry(const PatinaHost* host)
 *     { ... return &table; }
 *
 * The macros give both symbols C linkage and default visibility from C and from C++ (in
 * C++ a plain `const int` at namespace scope would have internal linkage and not be
 * exported).
 *
 * The host dlopen()s the library with RTLD_NOW | RTLD_LOCAL (a plugin's symbols never leak
 * into the host or into other plugins), reads `patina_plugin_abi_version`, and refuses the
 * plugin, saying why, when
 *   - the major version (version / 100) differs from the host's, or
 *   - the plugin's minor version (version % 100) is newer than the host's (it may rely on
 *     host services this host does not have), or
 *   - either symbol is missing, or
 *   - a shader name it declares is already declared by another plugin or twice by itself.
 * Then it calls `patina_plugin_entry` once, with a host services table that stays valid
 * until the plugin is unloaded, and copies nothing out of the returned table: the table,
 * its descriptors and their strings must live as long as the library is loaded (use
 * static storage).
 *
 * Discovery: the host searches only directories it knows or was given — patina-render's own
 * bundled folder (<prefix>/lib/patina/plugins), PATINA_PLUGIN_PATH (colon-separated absolute
 * directories), the --plugin-path option and the scene file — never the current directory
 * or LD_LIBRARY_PATH implicitly.
 *
 * ---------------------------------------------------------------------------------------
 * 2. Shaders, parameters and instances
 * ---------------------------------------------------------------------------------------
 * A plugin declares one or more shaders (PatinaShaderDesc): a name unique across all loaded
 * plugins, a kind (bsdf, medium, emitter, texture), parameter declarations with full
 * metadata, and function pointers. The host binds parameters from a scene or shader file
 * (TOML), checks their names, types and ranges against the declarations — an unknown or
 * misspelt parameter is an error — fills every missing parameter with its default, and
 * calls `create` with one PatinaParamValue per declaration, in declaration order.
 * `create` returns an opaque instance that is immutable afterwards; the host calls
 * `destroy` exactly once for every instance it created.
 *
 * ---------------------------------------------------------------------------------------
 * 3. Rules for evaluation functions
 * ---------------------------------------------------------------------------------------
 *  - Reentrant and thread-safe: many threads call them on one instance at once.
 *  - Allocation-free and never open files; textures are read through the host services.
 *  - Spectral: every radiometric value is an array of `wavelengths->count` samples
 *    (1 <= count <= PATINA_MAX_WAVELENGTHS), one per wavelength in `wavelengths->lambda_nm`
 *    (360-830 nm, hero-wavelength sampling). Output arrays hold PATINA_MAX_WAVELENGTHS floats;
 *    entries at or past `count` are ignored.
 *  - BSDFs work in the local shading frame: +z is the shading normal, x and y follow dPdu
 *    (orthonormalised). Directions are unit vectors pointing away from the surface, `wo`
 *    towards the viewer (or the previous vertex), `wi` towards the light (the next vertex).
 *    A direction with z < 0 lies below the surface.
 *  - `eval` returns the BSDF value f(wo, wi) *without* the cosine factor. `pdf` is the
 *    solid-angle density with which `sample` generates wi given wo; it must match `sample`
 *    exactly (checked by a chi-square test). Delta lobes are never returned by eval/pdf.
 *  - Never NaN or Inf; return 0 (and a zero pdf) instead.
 *  - `ctx` is never NULL when a host calls; both sides of a surface are shaded (wo.z < 0
 *    means the viewer is below the shading normal): a one-sided shader returns 0 there.
 *
 * ---------------------------------------------------------------------------------------
 * 4. Version history (bump PATINA_ABI_VERSION_MINOR when adding at the end of a struct or a
 *    service; bump MAJOR whenever an existing plugin or host would break)
 * ---------------------------------------------------------------------------------------
 *   100  Patina 0.1: first version.
 *   101  PATINA_PARAM_FILE (a data file resolved by the host); host services open_texture
 *        and read_image, for shaders whose textures are named inside a data file (a patina
 *        stack.toml, a slab volume). A 101 plugin that uses them checks host->size.
 */
#ifndef PATINA_ABI_H
#define PATINA_ABI_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PATINA_ABI_VERSION_MAJOR 1
#define PATINA_ABI_VERSION_MINOR 1
/** major*100 + minor, the value of the exported `patina_plugin_abi_version`. */
#define PATINA_ABI_VERSION (PATINA_ABI_VERSION_MAJOR * 100 + PATINA_ABI_VERSION_MINOR)

/** Mark the two exported symbols; everything else in a plugin may stay hidden. */
#if defined(__GNUC__) || defined(__clang__)
#define PATINA_PLUGIN_EXPORT __attribute__((visibility("default")))
#else
#define PATINA_PLUGIN_EXPORT
#endif

#ifdef __cplusplus
#define PATINA_EXTERN_C extern "C"
#else
#define PATINA_EXTERN_C
#endif

/** Define the exported version symbol: put `PATINA_PLUGIN_DEFINE_VERSION;` in one source. */
#define PATINA_PLUGIN_DEFINE_VERSION                                                          \
    PATINA_EXTERN_C PATINA_PLUGIN_EXPORT const int patina_plugin_abi_version = PATINA_ABI_VERSION

/** Prefix of the entry point's definition (C linkage, exported). */
#define PATINA_PLUGIN_ENTRY_DECL PATINA_EXTERN_C PATINA_PLUGIN_EXPORT

/** Names of the two symbols the host looks up with dlsym. */
#define PATINA_PLUGIN_VERSION_SYMBOL "patina_plugin_abi_version"
#define PATINA_PLUGIN_ENTRY_SYMBOL "patina_plugin_entry"

/** The most wavelength samples a path carries (hero wavelength + rotations). */
#define PATINA_MAX_WAVELENGTHS 8
/** Range of wavelengths a host samples, in nanometres. */
#define PATINA_LAMBDA_MIN_NM 360.0f
#define PATINA_LAMBDA_MAX_NM 830.0f

/* ------------------------------------------------------------------------------------- */
/* Small value types                                                                       */
/* ------------------------------------------------------------------------------------- */

typedef struct PatinaVec2 {
    float x, y;
} PatinaVec2;

typedef struct PatinaVec3 {
    float x, y, z;
} PatinaVec3;

/** The wavelengths a path carries: `count` samples, lambda_nm[0] is the hero wavelength. */
typedef struct PatinaWavelengths {
    int count;
    float lambda_nm[PATINA_MAX_WAVELENGTHS];
} PatinaWavelengths;

/**
 * An RGB colour uplifted to a smooth spectrum by the host (Jakob & Hanika 2019 model):
 *     value(lambda) = scale * S(c0*lambda^2 + c1*lambda + c2),  S(x) = 1/2 + x / (2 sqrt(1+x^2))
 * with lambda in nanometres. For a reflectance (PATINA_PARAM_COLOR) the value lies in [0, 1];
 * a grey g is stored exactly as c = 0, scale = 2g (a constant spectrum). When `illuminant`
 * is non-zero (emission colours), the value is further multiplied by the working space's
 * white illuminant (D65) normalised to luminance Y = 1, so that an emission colour
 * (1, 1, 1) renders as (1, 1, 1) in the working space: evaluate it with PatinaHost::
 * eval_rgb_spectrum. For reflectances `patina_rgb_spectrum_eval` below is exact.
 */
typedef struct PatinaRgbSpectrum {
    float c0, c1, c2;
    float scale;
    int illuminant;
} PatinaRgbSpectrum;

/**
 * A tabulated spectrum: `count` (wavelength nm, value) pairs sorted by wavelength, linearly
 * interpolated and clamped to the end values outside the table. The arrays are owned by the
 * host and valid only during `create`: an instance copies what it needs.
 */
typedef struct PatinaTabulatedSpectrum {
    int count;
    const float* lambda_nm;
    const float* value;
} PatinaTabulatedSpectrum;

/** Opaque handle to a texture the host opened (OIIO TextureSystem) on a plugin's behalf. */
typedef struct PatinaTexture PatinaTexture;

/* ------------------------------------------------------------------------------------- */
/* Parameter declarations and values                                                       */
/* ------------------------------------------------------------------------------------- */

typedef enum PatinaParamType {
    PATINA_PARAM_FLOAT = 1,    /**< one float; range [min_value, max_value] checked */
    PATINA_PARAM_INT = 2,      /**< one integer; range checked */
    PATINA_PARAM_BOOL = 3,     /**< true / false */
    PATINA_PARAM_COLOR = 4,    /**< RGB in the declared colour space, each in [min,max]; uplifted as a
                                    reflectance when max_value <= 1, else as an emission colour */
    PATINA_PARAM_SPECTRUM = 5, /**< tabulated spectrum, or a single number for a constant one */
    PATINA_PARAM_STRING = 6,   /**< free text, e.g. a file name or an enumerated choice */
    PATINA_PARAM_TEXTURE = 7,  /**< a texture file; the host opens it and passes a handle */
    PATINA_PARAM_FILE = 8      /**< (1.1) a data file the plugin reads in create: the host resolves a
                                    relative name against the file the value came from, checks
                                    that it exists and passes the absolute path in `s` */
} PatinaParamType;

/**
 * Declaration of one parameter: the metadata that `patina-render --list-shaders` prints and
 * that the host checks values against.
 */
typedef struct PatinaParamDecl {
    const char* name;           /**< [a-z_][a-z0-9_]*, unique within the shader */
    PatinaParamType type;
    float default_value[3];     /**< FLOAT/INT/BOOL: [0]; COLOR: rgb; SPECTRUM: [0] if no table */
    const char* default_string; /**< STRING/TEXTURE default (may be NULL = "" / no texture) */
    const PatinaTabulatedSpectrum* default_spectrum; /**< SPECTRUM default table or NULL */
    float min_value, max_value; /**< inclusive range for FLOAT/INT/COLOR components/SPECTRUM values */
    const char* colorspace;     /**< COLOR/TEXTURE: declared colour space of the value ("raw" for data);
                                     FLOAT/SPECTRUM: units ("nm", "1/m", "" for none) */
    const char* help;           /**< one sentence for users */
} PatinaParamDecl;

/** The value of one parameter as passed to `create`; which member is set follows the type. */
typedef struct PatinaParamValue {
    PatinaParamType type;
    float f;                        /**< FLOAT (also INT and BOOL as 0/1 for convenience) */
    int i;                          /**< INT, BOOL */
    float rgb[3];                   /**< COLOR: in the host's working space (scene-linear) */
    PatinaRgbSpectrum color;        /**< COLOR: `rgb` uplifted by the host */
    PatinaTabulatedSpectrum spectrum; /**< SPECTRUM (a constant arrives as a 1-entry table) */
    const char* s;                  /**< STRING, TEXTURE file name; valid during create only */
    const PatinaTexture* texture;   /**< TEXTURE: handle valid until the host shuts down, or NULL */
} PatinaParamValue;

/* ------------------------------------------------------------------------------------- */
/* The shading context                                                                      */
/* ------------------------------------------------------------------------------------- */

/** Transport mode, for BSDFs whose value is not symmetric (refraction, shading normals). */
typedef enum PatinaTransportMode {
    PATINA_TRANSPORT_RADIANCE = 0,  /**< paths traced from the camera */
    PATINA_TRANSPORT_IMPORTANCE = 1 /**< paths traced from lights */
} PatinaTransportMode;

/**
 * What the host knows about the point being shaded, in world space unless said otherwise.
 * Fields a host cannot provide are zero; ask for others by name with `attribute`.
 */
typedef struct PatinaShadingContext {
    PatinaVec3 P;       /**< position */
    PatinaVec3 N;       /**< shading normal (the local frame's +z) */
    PatinaVec3 Ng;      /**< geometric normal, on the same side as N */
    PatinaVec3 dPdu, dPdv;
    PatinaVec2 uv;      /**< texture coordinates */
    float duvdx[2], duvdy[2]; /**< screen-space uv derivatives for filtered lookups (0 = point sample) */
    int primitive_id;
    int mesh_id;
    PatinaTransportMode mode;
    const void* host_data; /**< the host's own per-point data, opaque to plugins */
} PatinaShadingContext;

/* ------------------------------------------------------------------------------------- */
/* Host services                                                                           */
/* ------------------------------------------------------------------------------------- */

typedef struct PatinaHost PatinaHost;

/**
 * Services the host offers to plugins. Every function is thread-safe. `size` is
 * sizeof(PatinaHost) of the host, so a plugin of a newer minor version can tell which
 * trailing members exist.
 */
struct PatinaHost {
    size_t size;
    int abi_version;           /**< the host's PATINA_ABI_VERSION */
    const char* host_name;     /**< e.g. "patina-render 0.1.0" */
    const char* working_space; /**< OCIO name of the scene-linear working space, e.g. "ACEScg" */

    /** Report an error during `create` (then return NULL) or a warning; `shader` names the
        instance's shader. The host shows it with the file and parameter it came from. */
    void (*error)(const PatinaHost* host, const char* shader, const char* message);
    void (*warning)(const PatinaHost* host, const char* shader, const char* message);

    /** Uplift an RGB triple in the working space to a spectrum. `is_illuminant` = 0 for a
        reflectance (components clamped to [0,1]), 1 for an unbounded emission colour. */
    void (*rgb_to_spectrum)(const PatinaHost* host, const float rgb[3], int is_illuminant,
                            PatinaRgbSpectrum* out);
    /** Evaluate an uplifted spectrum at `wl->count` wavelengths into out[]. */
    void (*eval_rgb_spectrum)(const PatinaHost* host, const PatinaRgbSpectrum* spectrum,
                              const PatinaWavelengths* wl, float* out);

    /** Filtered texture lookup at texture coordinates (u, v) — the mesh convention, v = 0
        at the bottom row of the image — with the uv derivatives of `ctx` (OIIO
        TextureSystem, periodic wrap, mip-mapped; ctx may be NULL for a point sample).
        Writes `nchannels` floats starting at `first_channel`, already converted from the
        texture's declared colour space to the working space. Returns 1 on success, 0 on
        failure (out filled with zeros). */
    int (*texture_lookup)(const PatinaHost* host, const PatinaTexture* texture,
                          const PatinaShadingContext* ctx, float u, float v, int first_channel,
                          int nchannels, float* out);

    /** Look up a named attribute of the shading point: "P", "N", "Ng", "dPdu", "dPdv" (3
        floats), "uv" (2), "primitive_id", "mesh_id" (1 int), "slab_uvw" (3) and any
        per-vertex attribute of the mesh. `nfloats` is the capacity of `out`; returns the
        number of floats written, 0 when the attribute does not exist. */
    int (*attribute)(const PatinaHost* host, const PatinaShadingContext* ctx, const char* name,
                     int nfloats, float* out);

    /* ---- 1.1: present when host->size >= offsetof(PatinaHost, read_image) + sizeof(void*) */

    /** Open a texture named by the plugin (e.g. inside a PATINA_PARAM_FILE), in the declared
        OCIO colour space ("raw" for data). Call during create only. The handle stays valid
        until the host shuts down. Returns NULL after reporting why through host->error. */
    const PatinaTexture* (*open_texture)(const PatinaHost* host, const char* path,
                                         const char* colorspace);

    /** Read every channel of one subimage (EXR part) of an image file as raw floats, rows
        top to bottom, channels interleaved, without colour conversion. Call during create
        only. dims receives {width, height, channels}; pass out = NULL to ask for the size
        first. Returns 1 on success, 0 after reporting why through host->error (a missing
        file or subimage, or `capacity` floats too few). */
    int (*read_image)(const PatinaHost* host, const char* path, int subimage, int dims[3],
                      float* out, size_t capacity);
};

/** True when `host` offers the 1.1 services (open_texture, read_image). */
#define PATINA_HOST_HAS_READ_IMAGE(host)                                                      \
    ((host)->size >= offsetof(PatinaHost, read_image) + sizeof(void*))

/* ------------------------------------------------------------------------------------- */
/* Function tables per kind                                                                */
/* ------------------------------------------------------------------------------------- */

/** Flags of a sampled BSDF lobe. */
enum {
    PATINA_LOBE_REFLECTION = 1,
    PATINA_LOBE_TRANSMISSION = 2,
    PATINA_LOBE_DIFFUSE = 4,
    PATINA_LOBE_GLOSSY = 8,
    PATINA_LOBE_SPECULAR = 16, /**< a delta lobe: pdf is not a density, eval returns 0 */
    /** The sampled direction depends on the wavelength (dispersion): the host keeps only
        the hero wavelength for the rest of the path. */
    PATINA_LOBE_WAVELENGTH_DEPENDENT = 32
};

/** Result of PatinaBsdfFuncs::sample. */
typedef struct PatinaBsdfSample {
    PatinaVec3 wi;                      /**< sampled direction, local frame */
    float f[PATINA_MAX_WAVELENGTHS];    /**< BSDF value f(wo, wi) without cosine. For a specular
                                             (delta) lobe, the value for which
                                             f * |wi.z| / pdf is the path weight (pbrt's convention) */
    float pdf;                          /**< solid-angle pdf; for a specular lobe the discrete
                                             probability of having chosen it */
    int lobe;                           /**< PATINA_LOBE_* flags of the sampled lobe */
    float eta;                          /**< for transmission: index of refraction on wi's side over
                                             the index on wo's side; else 1 */
} PatinaBsdfSample;

typedef struct PatinaBsdfFuncs {
    /** f(wo, wi) without the cosine factor, for all non-delta lobes. */
    void (*eval)(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo,
                 PatinaVec3 wi, const PatinaWavelengths* wl, float* f);
    /** Solid-angle pdf of `sample` choosing wi given wo (non-delta lobes). */
    float (*pdf)(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo,
                 PatinaVec3 wi, const PatinaWavelengths* wl);
    /** Sample wi given wo and uniform numbers u_lobe in [0,1) and u in [0,1)^2.
        Returns 1 and fills `out`, or 0 when no direction could be sampled. */
    int (*sample)(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo,
                  float u_lobe, PatinaVec2 u, const PatinaWavelengths* wl,
                  PatinaBsdfSample* out);
    /** Directional albedo estimate per wavelength (for lobe selection and denoiser AOVs);
        may be NULL. */
    void (*albedo)(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo,
                   const PatinaWavelengths* wl, float* albedo);
} PatinaBsdfFuncs;

/** A scattering, absorbing medium. Positions and directions are in world space. */
typedef struct PatinaMediumFuncs {
    /** Sample a free-flight distance along the ray (origin, dir) up to t_max with uniform
        u; returns 1 and sets *t (< t_max) for a scattering event, 0 when the ray passes.
        `weight` receives the path throughput factor for the hero-wavelength estimator
        (transmittance * sigma_s / pdf for a scatter, transmittance / pdf otherwise). */
    int (*sample_distance)(const void* instance, const PatinaShadingContext* ctx,
                           PatinaVec3 origin, PatinaVec3 dir, float t_max, float u,
                           const PatinaWavelengths* wl, float* t, float* weight);
    /** Transmittance between origin and origin + t*dir (ratio tracking for heterogeneous
        media uses `u` as its random stream seed in [0,1)). */
    void (*transmittance)(const void* instance, const PatinaShadingContext* ctx,
                          PatinaVec3 origin, PatinaVec3 dir, float t, float u,
                          const PatinaWavelengths* wl, float* tr);
    /** Phase function value p(wo, wi) per wavelength and its sampling pdf. */
    float (*phase_eval)(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo,
                        PatinaVec3 wi, const PatinaWavelengths* wl, float* p);
    /** Sample wi; returns its pdf (0 on failure) and writes p(wo, wi) to p. */
    float (*phase_sample)(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo,
                          PatinaVec2 u, const PatinaWavelengths* wl, PatinaVec3* wi, float* p);
} PatinaMediumFuncs;

/** An area emitter bound to a surface. */
typedef struct PatinaEmitterFuncs {
    /** Radiance leaving the surface towards wo (local frame, +z = normal), in W/(m^2 sr nm),
        per wavelength. */
    void (*emit)(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo,
                 const PatinaWavelengths* wl, float* radiance);
} PatinaEmitterFuncs;

/** A pattern: writes `nchannels` values at the shading point (e.g. a procedural map). */
typedef struct PatinaTextureFuncs {
    void (*eval)(const void* instance, const PatinaShadingContext* ctx,
                 const PatinaWavelengths* wl, int nchannels, float* out);
} PatinaTextureFuncs;

/* ------------------------------------------------------------------------------------- */
/* Shader descriptors and the plugin table                                                 */
/* ------------------------------------------------------------------------------------- */

typedef enum PatinaShaderKind {
    PATINA_SHADER_BSDF = 1,
    PATINA_SHADER_MEDIUM = 2,
    PATINA_SHADER_EMITTER = 3,
    PATINA_SHADER_TEXTURE = 4
} PatinaShaderKind;

typedef struct PatinaShaderDesc {
    const char* name;  /**< unique across all loaded plugins, [a-z_][a-z0-9_]* */
    PatinaShaderKind kind;
    const char* help;  /**< what the shader models, one or two sentences */
    int param_count;
    const PatinaParamDecl* params;

    /** Build an immutable instance from one value per declared parameter (declaration
        order, defaults filled in, ranges already checked). Return NULL after calling
        host->error to refuse the values. */
    void* (*create)(const PatinaHost* host, const PatinaParamValue* values);
    void (*destroy)(void* instance);

    /** The table matching `kind`; the others are NULL. */
    const PatinaBsdfFuncs* bsdf;
    const PatinaMediumFuncs* medium;
    const PatinaEmitterFuncs* emitter;
    const PatinaTextureFuncs* texture;
} PatinaShaderDesc;

/** What patina_plugin_entry returns. */
typedef struct PatinaPluginInfo {
    const char* plugin_name;    /**< e.g. "basic" */
    const char* plugin_version; /**< the plugin's own version string */
    int shader_count;
    const PatinaShaderDesc* shaders;
} PatinaPluginInfo;

/** Signature of the entry point. */
typedef const PatinaPluginInfo* (*PatinaPluginEntryFn)(const PatinaHost* host);

/** Evaluate a reflectance PatinaRgbSpectrum (illuminant == 0) at one wavelength. */
static inline float patina_rgb_spectrum_eval(const PatinaRgbSpectrum* s, float lambda_nm)
{
    float x = (s->c0 * lambda_nm + s->c1) * lambda_nm + s->c2;
    /* S(x) = 1/2 + x / (2 sqrt(1 + x^2)); for huge |x| the limit 0 or 1. */
    float y;
    if (x > 1e18f || x < -1e18f)
        y = x > 0 ? 1.0f : 0.0f;
    else
        y = 0.5f + x / (2.0f * sqrtf(1.0f + x * x));
    return s->scale * y;
}

/** Evaluate a tabulated spectrum at one wavelength (linear interpolation, clamped ends). */
static inline float patina_tabulated_eval(const PatinaTabulatedSpectrum* s, float lambda_nm)
{
    int lo, hi;
    if (s->count <= 0) return 0.0f;
    if (s->count == 1 || lambda_nm <= s->lambda_nm[0]) return s->value[0];
    if (lambda_nm >= s->lambda_nm[s->count - 1]) return s->value[s->count - 1];
    lo = 0;
    hi = s->count - 1;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (s->lambda_nm[mid] <= lambda_nm) lo = mid; else hi = mid;
    }
    {
        float t = (lambda_nm - s->lambda_nm[lo]) / (s->lambda_nm[hi] - s->lambda_nm[lo]);
        return s->value[lo] + t * (s->value[hi] - s->value[lo]);
    }
}

#ifdef __cplusplus
}
#endif

#endif /* PATINA_ABI_H */
