#include "texgen/patina/layer_stack.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace patina::texgen {

float LayerStack::total_height(size_t texel) const
{
    // Bottom to top, in float: the one order every operator measures heights with.
    float total = 0.0f;
    for (const Layer& layer : layers) {
        total += layer.thickness_um[texel];
    }
    return total;
}

std::vector<float> LayerStack::total_heights() const
{
    std::vector<float> totals(texel_count, 0.0f);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, texel_count, 4096),
                      [&](const tbb::blocked_range<size_t>& range) {
                          for (const Layer& layer : layers) {
                              const float* t = layer.thickness_um.data();
                              for (size_t i = range.begin(); i != range.end(); ++i) {
                                  totals[i] += t[i];
                              }
                          }
                      });
    return totals;
}

int LayerStack::exposed_layer(size_t texel) const
{
    for (size_t k = layers.size(); k-- > 0;) {
        if (layers[k].thickness_um[texel] > 0.0f) {
            return static_cast<int>(k);
        }
    }
    return -1;
}

int LayerStack::exposed_material(size_t texel) const
{
    const int k = exposed_layer(texel);
    return k < 0 ? base_material : layers[static_cast<size_t>(k)].material;
}

size_t drop_empty_layers(LayerStack& stack)
{
    const size_t before = stack.layers.size();
    std::erase_if(stack.layers, [](const Layer& layer) {
        return std::all_of(layer.thickness_um.begin(), layer.thickness_um.end(),
                           [](float t) { return t == 0.0f; });
    });
    return before - stack.layers.size();
}

}  // namespace patina::texgen
