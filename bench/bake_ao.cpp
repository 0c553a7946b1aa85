// bench_bake_ao: the AO baker against raw Embree on exactly the same rays.
//
// A procedural statue (make_statue, ~92k triangles) on a ground plane, its uvs rasterised
// at 1024 x 1024 (2 x 2 sub-samples per texel), AO with 64 rays per texel on 2 threads.
// Prints the bake's rays/s, then replays the same rays (recorded from AoBaker::for_each_ray
// with the bake driver's per-sample generators) through rtcOccluded1 on a bare RTCScene of
// the same triangles and build flags, tbb::parallel_for on the same 2 threads, and the
// ratio of the two throughputs (target >= 0.6). Replay runs in chunks of ~4M rays so the
// recorded rays never need more than ~130 MB; only the rtcOccluded1 loops are timed.
//
//   bench_bake_ao [--resolution N] [--rays R] [--threads T] [--rings K]
#include "core/embree_scene.h"
#include "core/mesh.h"
#include "texgen/meshes/statue_mesh.h"
#include "texgen/ao/ao_baker.h"
#include "texgen/bake/bake_driver.h"
#include "texgen/texels/texel_grid.h"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
using namespace patina;
using namespace patina::texgen;

double seconds_since(Clock::time_point start)
{
    return std::chrono::duration<double>(Clock::now() - start).count();
}

struct RecordedRay {
    float org[3];
    float dir[3];
};

/// A bare Embree scene of `meshes`, with EmbreeScene's flags (robust, high build quality).
struct RawScene {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;

    RawScene(const std::vector<const TriangleMesh*>& meshes, bool same_flags)
    {
        device = rtcNewDevice(nullptr);
        scene = rtcNewScene(device);
        if (same_flags) {
            rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
            rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
        }
        for (const TriangleMesh* m : meshes) {
            RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
            auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
                g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, m->positions.size()));
            auto* i = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
                g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, m->triangle_count()));
            for (size_t k = 0; k < m->positions.size(); ++k)
                std::memcpy(v + 3 * k, &m->positions[k].x, 12);
            std::memcpy(i, m->indices.data(), m->indices.size() * 4);
            rtcCommitGeometry(g);
            rtcAttachGeometry(scene, g);
            rtcReleaseGeometry(g);
        }
        rtcCommitScene(scene);
    }
    ~RawScene()
    {
        rtcReleaseScene(scene);
        rtcReleaseDevice(device);
    }

    /// Time rtcOccluded1 over `rays` on the current TBB arena; adds the unoccluded count.
    double trace(const std::vector<RecordedRay>& rays, std::atomic<size_t>& unoccluded) const
    {
        const auto start = Clock::now();
        tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 1024),
                          [&](const tbb::blocked_range<size_t>& r) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            size_t open = 0;
            for (size_t k = r.begin(); k != r.end(); ++k) {
                RTCRay ray;
                ray.org_x = rays[k].org[0];
                ray.org_y = rays[k].org[1];
                ray.org_z = rays[k].org[2];
                ray.dir_x = rays[k].dir[0];
                ray.dir_y = rays[k].dir[1];
                ray.dir_z = rays[k].dir[2];
                ray.tnear = 0.0f;
                ray.tfar = INFINITY;
                ray.time = 0.0f;
                ray.mask = 0xFFFFFFFFu;
                ray.id = 0;
                ray.flags = 0;
                rtcOccluded1(scene, &context, &ray);
                open += ray.tfar != -INFINITY;
            }
            unoccluded += open;
        });
        return seconds_since(start);
    }
};

}  // namespace

int main(int argc, char** argv)
{
    int resolution = 1024, rays_per_texel = 64, threads = 2, rings = 240;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string a = argv[i];
        const int v = std::atoi(argv[i + 1]);
        if (a == "--resolution") resolution = v;
        else if (a == "--rays") rays_per_texel = v;
        else if (a == "--threads") threads = v;
        else if (a == "--rings") rings = v;
        else {
            std::fprintf(stderr, "bench_bake_ao: unknown option %s\n", a.c_str());
            return 2;
        }
    }
    tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism,
                                    static_cast<size_t>(threads));

    // The scene: a statue on a ground plane (the plane only occludes).
    StatueOptions statue_options;
    statue_options.rings = rings;
    statue_options.segments = rings * 4 / 5;
    const TriangleMesh statue = make_statue(Imath::V3f(0.0f), statue_options);
    const TriangleMesh ground = make_plane(Imath::V3f(0.0f), 8.0f, 1);
    EmbreeScene scene;
    scene.add_mesh(statue);
    scene.add_mesh(ground);
    scene.commit();
    std::printf("scene: statue %zu triangles + ground %zu triangles\n", statue.triangle_count(),
                ground.triangle_count());

    RasterOptions raster;
    raster.width = raster.height = resolution;
    raster.supersampling = 2;
    auto start = Clock::now();
    const std::vector<TexelGrid> tiles = rasterize_uv(statue, raster);
    const SampleGroups& groups = tiles.at(0).groups;
    std::printf("texels: %zu covered of %dx%d (%zu samples), rasterised in %.2f s\n",
                groups.group_count(), resolution, resolution, groups.samples.size(),
                seconds_since(start));

    // The bake, as patina-texgen ao runs it.
    const AoBaker baker(scene, {rays_per_texel});
    const BakeRun run{0, static_cast<uint64_t>(tiles[0].udim), nullptr};
    size_t bake_rays = 0;
    for (size_t g = 0; g < groups.group_count(); ++g)
        bake_rays += baker.rays_per_sample(groups.group_size(g)) * groups.group_size(g);
    start = Clock::now();
    const std::vector<float> values = bake_groups(groups, baker, run);
    const double bake_seconds = seconds_since(start);
    double mean_ao = 0.0;
    for (float v : values)
        mean_ao += v;
    mean_ao /= static_cast<double>(values.size());
    std::printf("bake: %zu rays in %.3f s = %.2f M rays/s (%d threads), mean ao %.4f\n",
                bake_rays, bake_seconds, bake_rays * 1e-6 / bake_seconds, threads, mean_ao);

    // The same rays through raw Embree: record them in chunks with the driver's generators
    // (bake_driver.cpp: Pcg32(hash_values(seed, stream, group, sample index in group))).
    std::vector<const TriangleMesh*> meshes = {&statue, &ground};
    for (bool same_flags : {true, false}) {
        const RawScene raw(meshes, same_flags);
        std::vector<RecordedRay> chunk;
        chunk.reserve(size_t(4) << 20);
        std::atomic<size_t> unoccluded{0};
        size_t traced = 0;
        size_t below_facet = 0;
        double raw_seconds = 0.0;
        auto flush = [&] {
            raw_seconds += raw.trace(chunk, unoccluded);
            traced += chunk.size();
            chunk.clear();
        };
        for (size_t g = 0; g < groups.group_count(); ++g) {
            const uint32_t first = groups.offsets[g], last = groups.offsets[g + 1];
            for (uint32_t s = first; s != last; ++s) {
                Pcg32 rng(hash_values(run.seed, run.stream, g, s - first));
                size_t emitted = 0;
                const uint32_t n = baker.for_each_ray(
                    groups.samples[s], last - first, rng,
                    [&](const Imath::V3f& o, const Imath::V3f& d) {
                        chunk.push_back({{o.x, o.y, o.z}, {d.x, d.y, d.z}});
                        ++emitted;
                    });
                below_facet += n - emitted;
            }
            if (chunk.size() >= (size_t(4) << 20) - 4096)
                flush();
        }
        flush();
        const double raw_rate = (traced + below_facet) * 1e-6 / raw_seconds;
        const double bake_rate = bake_rays * 1e-6 / bake_seconds;
        std::printf("raw embree (%s): %zu rays traced (+%zu below the facet, counted as the "
                    "bake counts them) in %.3f s = %.2f M rays/s; unoccluded fraction %.4f\n",
                    same_flags ? "robust, high-quality BVH as EmbreeScene" : "default flags",
                    traced, below_facet, raw_seconds, raw_rate,
                    double(unoccluded) / double(traced + below_facet));
        std::printf("ratio bake / raw (%s) = %.3f%s\n", same_flags ? "same flags" : "default flags",
                    bake_rate / raw_rate, same_flags ? "  (target >= 0.6)" : "");
    }
    return 0;
}
