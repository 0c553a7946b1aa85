#include "texgen/patina/operators.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace patina::texgen {
namespace {

    constexpr size_t kGrain = 4096;
    constexpr float kInfinity = std::numeric_limits<float>::infinity();

    [[noreturn]] void fail(const char* op, const std::string& what)
    {
        throw std::invalid_argument(std::string(op) + ": " + what);
    }

    std::string number(double v)
    {
        std::ostringstream s;
        s << v;
        return s.str();
    }

    /// A thickness or height argument: finite and >= 0 (-0 counts as 0).
    void check_amount(const char* op, const char* what, float value)
    {
        if (!std::isfinite(value)) {
            fail(op, std::string(what) + " is not a finite number (" + number(value) + ")");
        }
        if (value < 0.0f) {
            fail(op, "negative " + std::string(what) + " " + number(value) + " um");
        }
    }

    /// Room for one more layer, before its texels are allocated.
    void check_room(const char* op, const LayerStack& stack)
    {
        if (stack.layers.size() >= kMaxStackLayers)
            fail(op, "the stack has " + std::to_string(stack.layers.size()) +
                         " layers already, the most a stack may hold");
    }

    void check_material(const char* op, int material)
    {
        if (material < 0) {
            fail(op, "material id " + std::to_string(material) + " is negative");
        }
    }

    /// A map is empty (1 everywhere) or one finite value per texel.
    void check_map(const char* op, std::span<const float> map, size_t texel_count)
    {
        if (map.empty()) {
            return;
        }
        if (map.size() != texel_count) {
            fail(op, "the map has " + std::to_string(map.size()) + " texels, the stack " +
                         std::to_string(texel_count));
        }
        for (size_t i = 0; i < map.size(); ++i) {
            if (!std::isfinite(map[i])) {
                fail(op, "map value " + number(map[i]) + " at texel " + std::to_string(i) +
                             " is not a finite number");
            }
        }
    }

    /// value * map[i], the map clamped at 0 below; the one product every operator uses, so
    /// that an erode undoes a coat of the same arguments exactly.
    float amount_at(float value, std::span<const float> map, size_t i)
    {
        return map.empty() ? value : value * std::max(map[i], 0.0f);
    }

    std::vector<float*> layer_pointers(LayerStack& stack)
    {
        std::vector<float*> p;
        p.reserve(stack.layers.size());
        for (Layer& layer : stack.layers) {
            p.push_back(layer.thickness_um.data());
        }
        return p;
    }

    template <class F> void for_each_texel(size_t texel_count, F&& f)
    {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, texel_count, kGrain),
                          [&](const tbb::blocked_range<size_t>& r) {
                              for (size_t i = r.begin(); i != r.end(); ++i) {
                                  f(i);
                              }
                          });
    }

    /// x0 = target - below, moved by an ulp at a time until below + x lands on the side of
    /// the target that `at_least` asks (>= when true, <= when false), within [lo, hi]. The
    /// float sum rounds, so the exact difference may miss by an ulp; when it does not, x0
    /// is kept as it is.
    float adjust_to_target(float below, float x0, float target, bool at_least, float lo, float hi)
    {
        float x = std::clamp(x0, lo, hi);
        if (at_least) {
            while (below + x < target && x < hi) {
                x = std::nextafter(x, kInfinity);
            }
        } else {
            while (below + x > target && x > lo) {
                x = std::nextafter(x, -kInfinity);
            }
        }
        return x;
    }

}  // namespace

LayerStack new_stack(int material, size_t texel_count)
{
    check_material("new", material);
    LayerStack stack;
    stack.base_material = material;
    stack.texel_count = texel_count;
    return stack;
}

void coat(LayerStack& stack, int material, float thickness_um, std::span<const float> map)
{
    check_material("coat", material);
    check_room("coat", stack);
    check_amount("coat", "thickness", thickness_um);
    check_map("coat", map, stack.texel_count);
    Layer layer;
    layer.material = material;
    layer.thickness_um.resize(stack.texel_count);
    float* t = layer.thickness_um.data();
    for_each_texel(stack.texel_count, [&](size_t i) { t[i] = amount_at(thickness_um, map, i); });
    stack.layers.push_back(std::move(layer));
}

void erode(LayerStack& stack, float thickness_um, std::span<const float> map)
{
    check_amount("erode", "thickness", thickness_um);
    check_map("erode", map, stack.texel_count);
    const std::vector<float*> layers = layer_pointers(stack);
    for_each_texel(stack.texel_count, [&](size_t i) {
        // From the top down, each layer gives what it has until the amount is removed; the
        // base below the last layer is infinite and never cut (§3.1).
        float remaining = amount_at(thickness_um, map, i);
        for (size_t k = layers.size(); k-- > 0 && remaining > 0.0f;) {
            float& t = layers[k][i];
            if (t <= remaining) {
                remaining -= t;
                t = 0.0f;
            } else {
                t -= remaining;
                remaining = 0.0f;
            }
        }
    });
}

void fill(LayerStack& stack, int material, float height_um, std::span<const float> map)
{
    check_material("fill", material);
    check_room("fill", stack);
    check_amount("fill", "height", height_um);
    check_map("fill", map, stack.texel_count);
    Layer layer;
    layer.material = material;
    layer.thickness_um.assign(stack.texel_count, 0.0f);
    float* added = layer.thickness_um.data();
    const LayerStack& s = stack;
    for_each_texel(stack.texel_count, [&](size_t i) {
        // Water up to h: only the valleys (total < h) receive material, peaks keep theirs.
        const float h = amount_at(height_um, map, i);
        const float total = s.total_height(i);
        if (total < h) {
            added[i] = adjust_to_target(total, h - total, h, true, 0.0f, kInfinity);
        }
    });
    stack.layers.push_back(std::move(layer));
}

void polish(LayerStack& stack, float height_um, std::span<const float> map)
{
    check_amount("polish", "height", height_um);
    check_map("polish", map, stack.texel_count);
    const std::vector<float*> layers = layer_pointers(stack);
    for_each_texel(stack.texel_count, [&](size_t i) {
        // Walk up the stack as total_height sums it; cut the layer that crosses h and clear
        // everything above it. Texels that never cross h are not touched.
        const float h = amount_at(height_um, map, i);
        float z = 0.0f;
        for (size_t k = 0; k < layers.size(); ++k) {
            const float t = layers[k][i];
            const float top = z + t;
            if (top <= h) {
                z = top;
                continue;
            }
            layers[k][i] = adjust_to_target(z, h - z, h, false, 0.0f, t);
            for (size_t j = k + 1; j < layers.size(); ++j) {
                layers[j][i] = 0.0f;
            }
            break;
        }
    });
}

float bearing_height(std::span<const float> heights, float fraction, std::span<const float> weights)
{
    const char* op = "polish until exposed";
    if (!(fraction >= 0.0f && fraction <= 1.0f)) {
        fail(op, "the fraction of area " + number(fraction) + " is not in [0, 1]");
    }
    if (!weights.empty() && weights.size() != heights.size()) {
        fail(op, "the area weights have " + std::to_string(weights.size()) + " texels, the stack " +
                     std::to_string(heights.size()));
    }
    // The texels that stand for area, highest first (ties by index: one order for any
    // thread count).
    struct Entry {
        float height;
        float weight;
        uint32_t index;
    };
    std::vector<Entry> entries;
    entries.reserve(heights.size());
    for (size_t i = 0; i < heights.size(); ++i) {
        const float w = weights.empty() ? 1.0f : weights[i];
        if (!std::isfinite(w) || w < 0.0f) {
            fail(op, "area weight " + number(w) + " at texel " + std::to_string(i) +
                         " is negative or not finite");
        }
        if (!std::isfinite(heights[i])) {
            fail(op, "height " + number(heights[i]) + " at texel " + std::to_string(i) +
                         " is not finite");
        }
        if (w > 0.0f) {
            entries.push_back({heights[i], w, static_cast<uint32_t>(i)});
        }
    }
    if (entries.empty()) {
        fail(op, "no texel has a positive area weight");
    }
    tbb::parallel_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
        return a.height != b.height ? a.height > b.height : a.index < b.index;
    });
    // Bearing area: the cumulative weight from the top. Summed in the sorted order both
    // times, so the last partial sum equals the total exactly and fraction 1 is reached.
    double total = 0.0;
    for (const Entry& e : entries) {
        total += e.weight;
    }
    const double target = static_cast<double>(fraction) * total;
    double cumulative = 0.0;
    for (const Entry& e : entries) {
        cumulative += e.weight;
        if (cumulative >= target) {
            return e.height;
        }
    }
    return entries.back().height;
}

float polish_until_exposed(LayerStack& stack, float fraction, std::span<const float> weights)
{
    if (!weights.empty() && weights.size() != stack.texel_count) {
        fail("polish until exposed", "the area weights have " + std::to_string(weights.size()) +
                                         " texels, the stack " + std::to_string(stack.texel_count));
    }
    const float h = bearing_height(stack.total_heights(), fraction, weights);
    polish(stack, h);
    return h;
}

void offset(LayerStack& stack, int material, std::span<const float> fill_thickness_um)
{
    check_room("offset", stack);
    check_material("offset", material);
    if (fill_thickness_um.size() != stack.texel_count) {
        fail("offset", "the fill has " + std::to_string(fill_thickness_um.size()) +
                           " texels, the stack " + std::to_string(stack.texel_count));
    }
    for (size_t i = 0; i < fill_thickness_um.size(); ++i) {
        const float t = fill_thickness_um[i];
        if (!std::isfinite(t) || t < 0.0f) {
            fail("offset", "fill thickness " + number(t) + " um at texel " + std::to_string(i) +
                               " is negative or not finite");
        }
    }
    Layer layer;
    layer.material = material;
    layer.thickness_um.assign(fill_thickness_um.begin(), fill_thickness_um.end());
    stack.layers.push_back(std::move(layer));
}

}  // namespace patina::texgen
