/*
 * The vessel's mass matrix M = M_RB + M_A and its inverse. M is constant,
 * so it is inverted once at init (Gauss-Jordan elimination with partial
 * pivoting, in double) and every evaluation of the right-hand side costs a
 * 6x6 matrix-vector product.
 */
#include "math/umath.h"
#include "models/vessel/vessel_internal.h"

/* Rigid-body part: mass on the translational block, the CG offset coupling, I_G. */
static void vessel_mass_rigid(const vessel_model *m, double a[6][6]) {
    const vessel_params *p = &m->params;
    const double mass = m->mass_kg;
    const double xg = p->r_g_m[0];
    const double yg = p->r_g_m[1];
    const double zg = p->r_g_m[2];
    /* Upper right: -mass*S(r_G); lower left: mass*S(r_G), its transpose. */
    const double coupling[3][3] = {
        {0.0, mass * zg, -(mass * yg)},
        {-(mass * zg), 0.0, mass * xg},
        {mass * yg, -(mass * xg), 0.0},
    };
    /* The products of inertia enter the inertia dyadic with a minus sign. */
    const double inertia[3][3] = {
        {p->ix_kgm2, -p->ixy_kgm2, -p->ixz_kgm2},
        {-p->ixy_kgm2, p->iy_kgm2, -p->iyz_kgm2},
        {-p->ixz_kgm2, -p->iyz_kgm2, p->iz_kgm2},
    };
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            a[i][j] = (i == j) ? mass : 0.0;
            a[i][j + 3] = coupling[i][j];
            a[i + 3][j] = coupling[j][i];
            a[i + 3][j + 3] = inertia[i][j];
        }
    }
}

/* Added mass: the acceleration derivatives of the prime system, scaled to SI. */
static void vessel_mass_added(const vessel_model *m, double a[6][6]) {
    const vessel_params *p = &m->params;
    a[0][0] += -m->r3 * p->x.udot;
    a[1][1] += -m->r3 * p->y.vdot;
    a[1][3] += -m->r4 * p->y.pdot;
    a[1][5] += -m->r4 * p->y.rdot;
    a[2][2] += -m->r3 * p->z.wdot;
    a[2][4] += -m->r4 * p->z.qdot;
    a[3][1] += -m->r4 * p->k.vdot;
    a[3][3] += -m->r5 * p->k.pdot;
    a[3][5] += -m->r5 * p->k.rdot;
    a[4][2] += -m->r4 * p->m.wdot;
    a[4][4] += -m->r5 * p->m.qdot;
    a[5][1] += -m->r4 * p->n.vdot;
    a[5][3] += -m->r5 * p->n.pdot;
    a[5][5] += -m->r5 * p->n.rdot;
}

/* Swaps rows r1 and r2 of both halves of the augmented matrix. */
static void vessel_mass_swap(double a[6][6], double b[6][6], int r1, int r2) {
    for (int j = 0; j < 6; j++) {
        double t = a[r1][j];
        a[r1][j] = a[r2][j];
        a[r2][j] = t;
        t = b[r1][j];
        b[r1][j] = b[r2][j];
        b[r2][j] = t;
    }
}

/*
 * Inverts a (destroyed) into inv. A pivot smaller than 1e-12 times the
 * largest entry of M means M is singular for any practical purpose.
 */
static bool vessel_mass_invert(double a[6][6], double inv[6][6]) {
    double scale = 0.0;
    for (int i = 0; i < 6; i++) {
        for (int j = 0; j < 6; j++) {
            inv[i][j] = (i == j) ? 1.0 : 0.0;
            scale = (math_fabs_f64(a[i][j]) > scale) ? math_fabs_f64(a[i][j]) : scale;
        }
    }
    for (int c = 0; c < 6; c++) {
        int piv = c;
        for (int r = c + 1; r < 6; r++) {
            piv = (math_fabs_f64(a[r][c]) > math_fabs_f64(a[piv][c])) ? r : piv;
        }
        if (!(math_fabs_f64(a[piv][c]) > 1e-12 * scale)) {
            return false;
        }
        vessel_mass_swap(a, inv, c, piv);
        const double d = a[c][c];
        for (int j = 0; j < 6; j++) {
            a[c][j] /= d;
            inv[c][j] /= d;
        }
        for (int r = 0; r < 6; r++) {
            const double f = a[r][c];
            if ((r == c) || (f == 0.0)) {
                continue;
            }
            for (int j = 0; j < 6; j++) {
                a[r][j] -= f * a[c][j];
                inv[r][j] -= f * inv[c][j];
            }
        }
    }
    return true;
}

bool vessel_mass_build(vessel_model *m) {
    double work[6][6];
    vessel_mass_rigid(m, m->mass_matrix);
    vessel_mass_added(m, m->mass_matrix);
    for (int i = 0; i < 6; i++) {
        for (int j = 0; j < 6; j++) {
            work[i][j] = m->mass_matrix[i][j];
        }
    }
    return vessel_mass_invert(work, m->mass_inverse);
}
