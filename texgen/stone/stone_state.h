// The state of a weathering simulation (Dorsey et al. 1999 §4.3, Table 1) on a slab
// lattice, and its parameters. Every field is one float per cell of the haloed slab arrays
// (SlabGrid); amounts of minerals are volume fractions of the voxel (volume per voxel
// volume), so sum(volume * amount) is a mass (at unit density) and conserved.
#pragma once

#include "texgen/stone/quarry.h"
#include "texgen/slabs/slab_lattice.h"
#include "texgen/slabs/voxelizer.h"

#include <Imath/ImathVec.h>

#include <array>
#include <cstdint>
#include <vector>

namespace patina::texgen::stone {

struct StoneParameters {
    // Moisture (§4.3.2). Pressure is in units of the surface pressure of a wetness of 1.
    double surface_pressure = 1.0;      ///< p on the surface in a wet phase, times wetness
    double pressure_diffusivity = 1.0;  ///< alpha in dp/dt = div(alpha phi grad p)
    double viscosity = 1.0;             ///< eta in Darcy's law v = -K/eta (grad p - rho g)
    double gravity = 10.0;              ///< rho |g| in pressure units per metre
    Imath::V3d up{0.0, 1.0, 0.0};       ///< against gravity
    double permeability_scale = 1.0;    ///< multiplies the quarry's permeability
    double evaporation_speed = 0.02;    ///< m per unit time the moist zone dries in dry phases
    // Dissolution and transport (§4.3.3), per species (soluble binder, iron, salt).
    std::array<double, kSpecies> solubility{2.0, 1.0, 20.0};     ///< k_i (rate, 1/time)
    std::array<double, kSpecies> saturation{0.02, 0.005, 0.05};  ///< m_i (volume fraction)
    /// D_i: the solute diffuses in the pores at alpha D_i phi (transport.cpp)
    std::array<double, kSpecies> diffusivity{0.5, 0.5, 0.5};
    double crystallisation_rate = 20.0; ///< 1/time: dissolved matter crystallising at the
                                        ///< surface in dry phases
    // Crusts from the environment.
    double black_crust_rate = 0.5;   ///< binder turned to black crust per unit deposit/time
    double salt_supply = 0.0;        ///< salt brought in per unit deposit/time, wet phases
    // Decay and erosion (§4.3.4).
    double decay_water = 1.0;        ///< decay per unit time of being moist
    double decay_dissolution = 200.0;///< decay per volume fraction of binder dissolved
    double erosion_events = 0.05;    ///< events per surface voxel per cycle
    double erosion_radius = 1.5;     ///< zone of influence, in voxels (depth step)
    double erosion_amount = 0.3;     ///< density removed at the centre of an event
    // Cycles.
    int wet_steps = 8;               ///< explicit steps per wet phase
    int dry_steps = 8;               ///< explicit steps per dry phase
    uint64_t seed = 1;
    // Output scales: the amount that counts as a full crust (volume fraction).
    double crust_scale = 0.02, iron_scale = 0.005, salt_scale = 0.02;
    /// The solid iron-bearing mineral fraction that colours the stone as much as a full iron
    /// crust: the output's iron channel is crust / iron_scale + solid / this, so sandstone's
    /// iron-rich bedding planes (0.06 against 0.01, quarry.cpp) show as ochre bands.
    double mineral_iron_scale = 0.1;
};

enum CellFlags : uint8_t { kStone = 1, kSurface = 2 };

struct StoneState {
    const SlabLattice* lattice = nullptr;
    StoneParameters params;
    double dt = 0.0;      ///< explicit step (stability limit of the pressure diffusion)
    /// Moisture steps per transport step: one transport step spans this many dt, its own
    /// stability limit (transport_interval_limit).
    int transport_interval = 1;
    double time = 0.0;
    int cycles_done = 0;
    /// Wall seconds run_cycle spent in each phase so far (for benchmarks and profiles).
    struct PhaseSeconds {
        double moisture = 0.0, transport = 0.0, erosion = 0.0;
    } phase_seconds;

    // Pressure and moisture are updated in place, one layer behind (moisture.cpp): no
    // double buffers.
    std::vector<float> density, porosity, permeability, head, moisture, pressure;
    std::array<std::vector<float>, kSpecies> solid, dissolved, crust, concentration;
    /// Rows changed since each field's last halo fill (moisture.cpp, transport.cpp,
    /// erosion.cpp).
    HaloChanges density_halo, pressure_halo, moisture_halo, concentration_halo;
    /// Per row (cell / sx): bit m set when species m's concentrations there are known +0.
    std::vector<uint8_t> concentration_zero;
    std::array<std::vector<float>, kSpecies> ghost_flux;  ///< seam fluxes (transport.cpp)
    /// Per cell: the ghost received a flux in the last transport step.
    std::vector<uint8_t> ghost_hit;
    /// Per slab: its ghosts that received a flux in the last transport step (ghost_flux is
    /// 0 at every other ghost), in the order they first did.
    std::vector<std::vector<uint32_t>> ghost_hits;
    /// The seam pass's scratch: per cell, whether it is due; per slab, the due voxels.
    std::vector<uint8_t> seam_mark;
    std::vector<std::vector<uint32_t>> seam_due;
    std::vector<uint8_t> full_stencil;  ///< moist with all 12 stencil partners moist
    std::vector<float> black, decay, wet_time;
    std::vector<uint8_t> flags;
    /// Per slab: layers k < active_depth can change in a step (the deepest surface or moist
    /// voxel + 2: the front advances at most one layer per step); deeper ones are dry and
    /// skipped, which is most of the shell while the front is shallow.
    std::vector<int> active_depth;
    std::vector<int> surface_depth;  ///< per slab: deepest surface voxel layer + 1
    /// The pressure's Dirichlet values (air and surface voxels, moisture.cpp) are in place in
    /// layers [0, pressure_preset_depth[s]) of slab s for the phase pressure_preset_wet
    /// (nothing else writes them). update_flags empties it, as the surface moved; so must a
    /// caller that changes column_wetness or surface_pressure between steps.
    std::vector<int> pressure_preset_depth;
    bool pressure_preset_wet = false;
    std::vector<uint8_t> surface_layer;  ///< per slab and layer: holds a surface voxel
    std::vector<Imath::V3f> colour;        ///< fresh stone albedo
    std::vector<ColumnSurface> columns;
    std::vector<float> column_wetness;     ///< per column, [0, 1]
    std::vector<float> column_deposit;     ///< per column, >= 0
};

/// Set up the state: voxelise `mesh`, fill the quarry, boundary values per column
/// (`wetness` and `deposit` are per column, see voxelizer.h; empty: 1 and 0), the head
/// rho g z, flags and dt. Throws std::runtime_error for bad parameters.
void initialise_state(StoneState& st, const SlabLattice& lattice, const TriangleMesh& mesh,
                      const Quarry& quarry, const StoneParameters& params,
                      std::vector<float> wetness = {}, std::vector<float> deposit = {});

/// Stone and surface flags from the density (refills the density halo), surface depths.
void update_flags(StoneState& st);
/// active_depth from the moisture and the surface depths (every layer scanned).
void update_active_depth(StoneState& st);
/// The same after a moisture step, which changes the moisture only in the active layers and
/// moves the front by at most one layer: only the layers above the old active_depth are
/// scanned.
void refresh_active_depth(StoneState& st);

/// Total of species i (solid + dissolved + crust, and black crust for the binder), volume
/// weighted over the interior voxels.
double species_mass(const StoneState& st, int species);

/// Throws std::runtime_error naming the field, slab, voxel and cycle if any interior voxel
/// of the state is NaN or infinite, so that no output is written from a broken simulation.
void check_state_finite(const StoneState& st);

/// Mean depth of the moist zone below the surface, in metres, over the columns whose
/// surface lies in `selector` (nullptr: all).
double moist_depth(const StoneState& st, const std::vector<char>* column_selector = nullptr);

/// Mean density loss (1 - density of the stone voxels below the initial surface) per
/// column group; see erosion.h.

// The steps; `wet` selects the phase.
void moisture_step(StoneState& st, bool wet);   // moisture.cpp: pressure and front
/// transport.cpp: dissolution, transport and crusts over `steps` x dt.
void transport_step(StoneState& st, bool wet, int steps = 1);
/// transport_bound.cpp: a bound on the spectral radius of the transport's diffusion
/// operator in every state of the run, from `products` products of a majorant of it with a
/// vector (1: the largest Gershgorin row; each more is sharper). Needs the lattice, flags
/// and porosity (halo filled) of `st`.
double transport_rate_bound(const StoneState& st, int products);
/// The products transport_interval_limit uses.
inline constexpr int kTransportBoundProducts = 6;
/// transport_bound.cpp: how many moisture steps dt one transport step may span and keep 0.9
/// of its stability limit over the whole run (at least 1), from transport_rate_bound. Needs
/// dt too.
int transport_interval_limit(const StoneState& st);
void erosion_events(StoneState& st);            // erosion.cpp: events from the decay index

/// One wet/dry cycle: wet_steps wet steps, dry_steps dry ones (a transport step after every
/// transport_interval of them and at the end of each phase), then erosion events.
void run_cycle(StoneState& st);

} // namespace patina::texgen::stone
