// The renderer's batched ray queries: EmbreeScene::intersect_coherent (camera rays as one
// coherent stream) answers exactly as one intersect call per ray, and a render whose camera
// rays go in batches is bitwise the same for any region split; the [render] robust option.
#include "render_fixture.h"

#include "core/embree_scene.h"
#include "core/mesh.h"

#include <optional>
#include <vector>

using namespace render_test;

namespace {

// A sphere on a plane seen by a pinhole from the front: rays that hit either, and rays that
// miss over the horizon.
std::vector<patina::RayQuery> camera_rays(int width, int height)
{
    std::vector<patina::RayQuery> rays;
    const Imath::V3f origin(0.0f, 1.0f, 5.0f);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const Imath::V3f dir(-0.6f + 1.2f * (x + 0.5f) / width,
                                 0.4f - 0.8f * (y + 0.5f) / height, -1.0f);
            rays.push_back({origin, dir.normalized()});
        }
    return rays;
}

void expect_stream_matches_single_rays(bool robust)
{
    patina::EmbreeScene scene(robust);
    scene.add_mesh(patina::make_uv_sphere({0.0f, 0.8f, 0.0f}, 0.8f, 24, 48));
    scene.add_mesh(patina::make_plane({0.0f, 0.0f, 0.0f}, 20.0f, 4));
    scene.commit();
    // 37 x 11 = 407 rays: several 64-ray chunks and a partial one.
    const std::vector<patina::RayQuery> rays = camera_rays(37, 11);
    std::vector<std::optional<patina::Hit>> hits(rays.size());
    scene.intersect_coherent(rays, hits);
    int hit_count = 0, misses = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const auto one = scene.intersect(rays[i].origin, rays[i].dir);
        ASSERT_EQ(one.has_value(), hits[i].has_value()) << "ray " << i;
        if (!one) {
            ++misses;
            continue;
        }
        ++hit_count;
        // The same triangle at the same distance and barycentrics, to the bit.
        EXPECT_EQ(one->mesh_id, hits[i]->mesh_id) << "ray " << i;
        EXPECT_EQ(one->prim_id, hits[i]->prim_id) << "ray " << i;
        EXPECT_EQ(one->t, hits[i]->t) << "ray " << i;
        EXPECT_EQ(one->u, hits[i]->u) << "ray " << i;
        EXPECT_EQ(one->v, hits[i]->v) << "ray " << i;
    }
    EXPECT_GT(hit_count, 100);
    EXPECT_GT(misses, 10);
}

}  // namespace

TEST(RayBatch, CoherentStreamAnswersAsSingleRays)
{
    expect_stream_matches_single_rays(true);
    expect_stream_matches_single_rays(false);
}

TEST(RayBatch, CoherentStreamChecksItsArguments)
{
    patina::EmbreeScene scene;
    scene.add_mesh(patina::make_plane({0.0f, 0.0f, 0.0f}, 2.0f));
    std::vector<patina::RayQuery> rays(3, {{0, 1, 0}, {0, -1, 0}});
    std::vector<std::optional<patina::Hit>> hits(3);
    EXPECT_THROW(scene.intersect_coherent(rays, hits), std::runtime_error);  // before commit
    scene.commit();
    std::vector<std::optional<patina::Hit>> too_few(2);
    EXPECT_THROW(scene.intersect_coherent(rays, too_few), std::invalid_argument);
    scene.intersect_coherent(rays, hits);
    for (const auto& h : hits) {
        ASSERT_TRUE(h.has_value());
        EXPECT_FLOAT_EQ(h->t, 1.0f);
    }
}

// Camera rays go to Embree in batches of a tile row; a band of rows (a farm tile) and the
// whole frame must still give the same bits for the band's pixels (tiles merge bitwise),
// here with an odd width and height so that tiles and batches are partial.
TEST(RayBatch, BandOfRowsIsBitwiseTheWholeFrame)
{
    auto l = load(write_scene("bands", kWhiteFurnace));
    l->scene.film.width = 37;
    l->scene.film.height = 23;
    l->scene.film.spp = 6;  // one batch of 4 samples and one of 2
    l->scene.camera.set_aspect(37.0f / 23.0f);
    const pr::Region full{0, 0, 37, 23};
    const pr::FilmResult whole = pr::render_region(l->scene, full, {1, true, std::nullopt});
    for (int index = 0; index < 3; ++index) {
        const pr::Region band = pr::tile_region(index, 3, 37, 23);
        const pr::FilmResult part = pr::render_region(l->scene, band, {2, true, std::nullopt});
        const size_t offset = static_cast<size_t>(band.y0) * 37 * 3;
        ASSERT_EQ(part.xyz.size(), static_cast<size_t>(band.height()) * 37 * 3);
        EXPECT_EQ(0, std::memcmp(part.xyz.data(), whole.xyz.data() + offset,
                                 part.xyz.size() * sizeof(float)))
            << "band " << index;
    }
}

// [render] robust = false: Embree's faster traversal; the furnace still matches the sky
// (unit white has Y = 1, as in WhiteFurnaceSphereMatchesTheSky).
TEST(RayBatch, RobustOptionIsReadAndRendersTheFurnace)
{
    auto robust = load(write_scene("robust_default", kWhiteFurnace));
    EXPECT_TRUE(robust->scene.robust_traversal);
    auto fast = load(write_scene("robust_off", std::string("[render]\nrobust = false\n") + kWhiteFurnace));
    EXPECT_FALSE(fast->scene.robust_traversal);
    EXPECT_NEAR(mean_y(pr::render_xyz(fast->scene, 0, true)), 1.0, 0.01);

    const std::string bad_type = error_of("robust_bad", "[render]\nrobust = 'no'\n");
    EXPECT_NE(bad_type.find("robust_bad.toml:2:"), std::string::npos) << bad_type;
    EXPECT_NE(bad_type.find("[render] robust must be true or false"), std::string::npos) << bad_type;
    const std::string bad_key = error_of("robust_key", "[render]\nrobustness = false\n");
    EXPECT_NE(bad_key.find("unknown key 'robustness' in [render]"), std::string::npos) << bad_key;
}
