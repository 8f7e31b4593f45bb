/*
 * The propeller of the seed paper (see propeller.h). The thrust serves the
 * vessel's `paper` propulsion law at the slow frame; the drag torque serves
 * the motor at every motor step, so it is one multiplication by a
 * coefficient derived at init.
 */
#include "models/propeller/propeller.h"

#include <stddef.h>

#include "math/umath.h"

/*
 * I0 comes from a 4-bladed nickel-aluminium bronze propeller of 0.3 m
 * diameter (docs/vessel.md shows the estimate): a hub of 60 mm diameter
 * and 80 mm length gives 7.7e-4 kg m^2, four blades of 120 mm span, 60 mm
 * mean chord and 5 mm mean thickness give 1.02e-2 kg m^2.
 */
const propeller_params propeller_params_default = {
    .diameter_m = 0.3,
    .alpha1 = 0.019,
    .alpha2 = -0.16,
    .efficiency = 0.7,
    .rho_kgpm3 = 1025.0,
    .drag_coeff = 1.369e-3,
    .inertia_kgm2 = 0.011,
};

propeller_status propeller_init(propeller_model *m, const propeller_params *p) {
    if ((m == NULL) || (p == NULL)) {
        return PROPELLER_ERR_NULL;
    }
    const double fields[7] = {p->diameter_m, p->alpha1,     p->alpha2,      p->efficiency,
                              p->rho_kgpm3,  p->drag_coeff, p->inertia_kgm2};
    for (size_t i = 0; i < 7u; i++) {
        if (!math_isfinite_f64(fields[i])) {
            return PROPELLER_ERR_PARAM;
        }
    }
    if (!(p->diameter_m > 0.0) || !(p->rho_kgpm3 > 0.0) || !(p->efficiency > 0.0) ||
        (p->efficiency > 1.0) || (p->drag_coeff < 0.0) || (p->inertia_kgm2 < 0.0)) {
        return PROPELLER_ERR_PARAM;
    }
    const double d = p->diameter_m;
    const double radius = 0.5 * d;
    m->tnn = p->rho_kgpm3 * (d * d * d * d) * p->alpha1;
    m->tnu = p->rho_kgpm3 * (d * d * d) * p->alpha2;
    m->efficiency = p->efficiency;
    m->k_drag = 0.5 * p->rho_kgpm3 * p->drag_coeff * (radius * radius * radius);
    m->k_drag_f32 = (float)m->k_drag;
    m->inertia_kgm2 = p->inertia_kgm2;
    return PROPELLER_OK;
}

double propeller_thrust_f64(const propeller_model *m, double w_radps, double u_mps) {
    const double aw = math_fabs_f64(w_radps);
    return m->tnn * aw * w_radps + m->tnu * aw * u_mps;
}

double propeller_surge_force_f64(const propeller_model *m, double w_radps, double u_mps) {
    return m->efficiency * propeller_thrust_f64(m, w_radps, u_mps);
}

double propeller_drag_torque_f64(const propeller_model *m, double w_radps) {
    return -m->k_drag * w_radps * math_fabs_f64(w_radps);
}

float propeller_drag_torque_f32(const propeller_model *m, float w_radps) {
    return -m->k_drag_f32 * w_radps * math_fabs_f32(w_radps);
}

double propeller_load_torque_f64(const propeller_model *m, double w_radps,
                                 double w_dot_radps2) {
    return -m->inertia_kgm2 * w_dot_radps2 + propeller_drag_torque_f64(m, w_radps);
}
