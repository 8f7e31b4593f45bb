/*
 * The vehicle's battery pack (declared in battery.h).
 *
 * Cell: the high-power Kokam lithium-polymer pouch cell (NMC / graphite,
 * by its 3.51-4.19 V open-circuit range) characterised by T. Huria, M. Ceraolo, J. Gazzarri and
 * R. Jackey, "High fidelity electrical model with thermal dependence for
 * characterization and simulation of high power lithium battery cells",
 * IEEE International Electric Vehicle Conference (IEVC), March 2012. The
 * values are the 20 degC column of the tables of Em (open-circuit voltage),
 * R0, R1 and C1 over the state of charge with which the MathWorks Simscape
 * example "Lithium Battery Cell - One RC-Branch Equivalent Circuit"
 * implements that paper; the capacity is the example's 20 degC value.
 * The 5 and 40 degC columns are in docs/battery.md, not here, because the
 * model has no thermal state.
 *
 * Pack: 144 cells in series keep the DC bus above the 410 V the inverter
 * needs at full load down to the cut-off (docs/battery.md, "Pack sizing");
 * two strings in parallel give about 30 kWh, 8.6 h of cruise at 3.5 kW.
 * Cut-off 3.0 V and charge limit 4.2 V are the usual limits of an NMC
 * cell.
 */
#include "models/battery/battery.h"

const battery_params battery_params_uuv = {
    .cell =
        {
            .n_points = 7u,
            .soc = {0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0},
            .ocv_v = {3.5057, 3.5660, 3.6337, 3.7127, 3.9259, 4.0777, 4.1928},
            .r0_ohm = {0.0085, 0.0085, 0.0087, 0.0082, 0.0083, 0.0085, 0.0085},
            .r1_ohm = {0.0029, 0.0024, 0.0026, 0.0016, 0.0023, 0.0018, 0.0017},
            .c1_f = {12447.0, 18872.0, 40764.0, 18721.0, 33630.0, 18360.0, 23394.0},
        },
    .capacity_ah = 27.63,
    .n_series = 144u,
    .n_parallel = 2u,
    .v_cutoff_cell_v = 3.0,
    .v_max_cell_v = 4.2,
    .frame_s = 0.1,
};
