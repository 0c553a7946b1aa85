// The fields both of the stone simulation's row kernels read (front_rows.h, transport_rows.h):
// pointers into a StoneState's arrays and its lattice's stencil weights.
#pragma once

#include "texgen/stone/stone_state.h"

#include <array>
#include <cstdint>

namespace patina::texgen::stone {

struct RowFields {
    const uint8_t* flags = nullptr;
    const float *density = nullptr, *moisture = nullptr, *porosity = nullptr;
    const float *permeability = nullptr, *pressure = nullptr, *head = nullptr;
    std::array<const float*, 6> weight{};

    explicit RowFields(const StoneState& s)
        : flags(s.flags.data()), density(s.density.data()), moisture(s.moisture.data()),
          porosity(s.porosity.data()), permeability(s.permeability.data()),
          pressure(s.pressure.data()), head(s.head.data())
    {
        for (size_t d = 0; d < 6; ++d)
            weight[d] = s.lattice->weights()[d].data();
    }
};

} // namespace patina::texgen::stone
