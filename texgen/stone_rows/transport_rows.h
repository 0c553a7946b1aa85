// The per-voxel work of a transport step (transport.cpp) over one row of a slab (the n_t
// voxels along u), a few voxels at a time in the lanes of a vector. Every lane does the
// scalar operations of its voxel in the same order, without contraction, so the results
// are the same bits as a loop over the voxels; partners at a fixed offset from a row are a
// row too, so their fields load without gathers, and the branches of the partner tests
// become masks.
#pragma once

#include "texgen/stone_rows/row_fields.h"
#include "texgen/stone/stone_state.h"

#include <array>
#include <cstdint>
#include <vector>

namespace patina::texgen::stone {

/// The 12 stencil partners of the voxels of layer k of slab s: entry e = 2 d + (sign > 0)
/// of direction d, at offset[e], and whether the partner's layer lies inside the shell (the
/// halo above and below it is no-flux).
struct Partners {
    std::array<long, 12> offset{};
    std::array<bool, 12> inside{};
    int slab = 0;

    Partners(const SlabLattice& lat, int s, int k);
};

/// The fields a transport step reads and writes, and its per-step constants.
struct TransportRows : RowFields {
    using Fields = std::array<float*, kSpecies>;

    const StoneState* st = nullptr;
    const uint8_t* partner = nullptr;  ///< SlabLattice::flux_partner per cell
    uint8_t* full_stencil = nullptr;
    const float* volume = nullptr;
    Fields concentration{}, dissolved{}, solid{}, crust{}, ledger{};
    uint8_t* ghost_hit = nullptr;                  ///< StoneState::ghost_hit
    std::vector<uint32_t>* ghost_hits = nullptr;   ///< StoneState::ghost_hits, per slab
    float* decay = nullptr;
    float* black = nullptr;

    bool wet = false;
    /// Wet, and the deposit map has deposits somewhere: surface voxels that are not moist
    /// change only then (deposit() adds +0 where the map is 0).
    bool deposits = false;
    float dt = 0.0f, inv_eta = 0.0f, crystallise = 0.0f;
    float decay_water = 0.0f, decay_dissolution = 0.0f;
    float black_crust_rate = 0.0f, salt_supply = 0.0f;
    std::array<float, kSpecies> half_diffusivity{};  ///< alpha D_i / 2
    std::array<float, kSpecies> saturation{}, rate_cap{};

    TransportRows(StoneState& st, bool wet, float dt);

    /// What concentration_row did to a row.
    struct ConcentrationRow {
        bool zero = false;     ///< every concentration of the row is +0
        bool changed = false;  ///< some bits changed (and were written)
    };
    /// Species m's concentrations C = amount / (phi rho) of the voxels of the row that
    /// starts at cell `row`, written where their bits change. `known_zero`: the row's
    /// concentrations are known +0, so a row without amounts is not read further.
    ConcentrationRow concentration_row(size_t row, size_t m, bool known_zero) const;
    /// full_stencil of the voxels of row (j, k) of slab s: moist, with all 12 stencil
    /// partners moist solute partners.
    void full_stencil_row(int s, int j, int k) const;
    /// Deposits, dissolution, transport and crusts of the voxels of row (j, k) of slab s, in
    /// place; fluxes into ghosts are added to `ledger`, voxel by voxel in order.
    void transport_row(int s, int j, int k) const;
};

} // namespace patina::texgen::stone
