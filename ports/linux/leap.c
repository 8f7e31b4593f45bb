/*
 * Exact leaps between switching events on the desk (leap.h).
 */
#include "leap.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "drive_segment.h"

#if UUV_NUMERIC == UUV_NUMERIC_FLOAT

/* z: the leap's state and inputs (leap.h); the clamped components first. */
enum {
    Z_IL_A = 0, Z_VC_A, Z_ID_A, Z_IL_B, Z_VC_B, Z_ID_B, Z_VDC,
    Z_JSH_A, Z_JSH_B, Z_IF_A, Z_IF_B,
    Z_E_A, Z_E_B, Z_EV,
    NZ
};
#define NX 11 /* the state part of z; the rest are inputs held over a leap */
#define NCLAMP 7 /* z[0..6] are clamped (leap.h) */

/*
 * All bits set where z's component is a voltage (else a current: the
 * coarse bound's two kinds), over z's 16 padded places: v_C a, v_C b, v_dc,
 * e_a, e_b, e_v. The AVX forms load it as a mask.
 */
static const int64_t volt_mask[16] __attribute__((aligned(64))) = {
    [Z_VC_A] = -1, [Z_VC_B] = -1, [Z_VDC] = -1, [Z_E_A] = -1, [Z_E_B] = -1, [Z_EV] = -1,
};

/* Whether z's component c is a voltage (volt_mask). */
static bool z_volt(int c) { return volt_mask[c] != 0; }

/* A filter phase's components in z. */
static const int z_il[2] = {Z_IL_A, Z_IL_B};
static const int z_vc[2] = {Z_VC_A, Z_VC_B};
static const int z_id[2] = {Z_ID_A, Z_ID_B};
static const int z_jsh[2] = {Z_JSH_A, Z_JSH_B};

/* The rows a leap computes: the 11 states, the frame sums of v_C a, v_C b, v_dc; padded. */
#define NR 16
#define R_SUM 11
/* The rows the bound covers: z[0..7] (row 7, j_sh a, is not clamped: no limit). */
#define NB 8
/* Rows 14, 15: the last step's DC-link voltage at its start and its DC-link current (the
 * trace's inverter voltages and i_dc after a run that ends in a leap). */
#define R_VDC_LAST 14
#define R_IDC_LAST 15

#define NS 8 /* switch states, bit x = leg x high */

/* The coefficients the map depends on: their places in key[] (and kd[]). */
enum {
    K_NEG_EPS_L = 0, K_G_L2, K_NEG_G_L, K_G_D, K_A_D, K_NEG_A_D, K_NODE, K_NEG_K_C, K_KG, K_L,
    NK
};

/*
 * The leap's product y = T z and the bound's sum B |z|: in AVX2 with FMA
 * where the build's flags allow them (LEAP_ARCH in the Makefile), else in
 * plain loops that the compiler vectorises for its baseline (SSE2, NEON)
 * or not at all. Either is a fixed order of operations.
 */
#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#define LEAP_AVX2 1
#if defined(__AVX512F__)
#define LEAP_AVX512 1
#else
#define LEAP_AVX512 0
#endif
#else
#define LEAP_AVX2 0
#define LEAP_AVX512 0
#endif

/*
 * One table entry, in blocks of eight rows, each column-major (block 0:
 * rows 0..7 of T, block 1: rows 8..15, block 2: the bound's B): a leap
 * reads each block as 14 contiguous groups of eight. bs: the bound's row
 * sums over the current columns (bs[0]) and the voltage columns (bs[1])
 * of z, for a coarser bound that needs only the largest |z| of each kind.
 */
typedef struct {
    double m[3][NZ][8] __attribute__((aligned(64)));
    double bs[2][8] __attribute__((aligned(64)));
} leap_entry;

#define T_AT(e, c, r) ((e)->m[(r) >> 3][c][(r) & 7])
#define B_AT(e, c, i) ((e)->m[2][c][i])

/*
 * An edge step's map (edge_build()): the step of switch state s with leg
 * x's duty d in [0, 1] instead of its state, the other legs held. The
 * step is linear in z and quadratic in d, and d enters only through the
 * inverter voltages (n v_dc / 3: the v_dc column) and the DC-link current's
 * sum of the phases (rows v_dc and i_dc), so
 *   y = A z + z_vdc d (b + d c) + d (rows 14, 15 of A z) in rows v_dc, i_dc,
 * A the step at d = 0 (rows 0..10 the new states, 11..13 u_a, u_b, i_dc;
 * rows 14, 15 the d terms of rows v_dc and i_dc of the other columns), b
 * and c the v_dc column's terms in d and d^2. One product like a leap's:
 * its chain is a leap's, where the step's own (v_dc, inverter, filter,
 * DC-link current, v_dc) is about twice as long.
 */
#define R_U_A 11
#define R_U_B 12
#define R_IDC 13
#define R_D_VDC 14
#define R_D_IDC 15
typedef struct {
    leap_entry a;
    double b[16] __attribute__((aligned(64)));
    double c[16] __attribute__((aligned(64)));
} edge_map;

struct leap_tables {
    leap_entry e[NS][LEAP_K_MAX + 1u];
    edge_map edge[NS][3];     /* per state at the step's start and edge leg */
    bool have_edge[NS][3];
    double m[NS][NZ][NZ];     /* one step, column-major (m[c][r] = d out_r / d z_c) */
    double mo[NS][NZ][3];     /* one step's outputs */
    double qmax[NS][NZ][NB];  /* running max of |Q_m| */
    uint32_t built[NS];       /* entries 0..built[s] are valid (0: only the identity) */
    bool have_m[NS];
    float key[NK];            /* the coefficients the tables were built from */
    double kd[NK];            /* the same in double, for step_d() */
    bool keyed;
    leap_stats st;
};

bool leap_available(void) { return true; }

/* The coefficients the map depends on, in key[]'s places (K_*). */
static void key_of(const drive_segment *d, float key[NK]) {
    const ps_coef_f32 *k = &d->ps.k;
    key[K_NEG_EPS_L] = k->neg_eps_l;
    key[K_G_L2] = k->g_l2;
    key[K_NEG_G_L] = k->neg_g_l;
    key[K_G_D] = k->g_d;
    key[K_A_D] = k->a_d;
    key[K_NEG_A_D] = k->neg_a_d;
    key[K_NODE] = k->k_node;
    key[K_NEG_K_C] = k->neg_k_c;
    key[K_KG] = d->in.battery.kg;
    key[K_L] = d->k_l;
}

/* The legs' duties of each switch state s: each leg's 0 or 1 (bit x: leg x high). */
static const double dq_tab[NS][3] = {
    {0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {1.0, 1.0, 0.0},
    {0.0, 0.0, 1.0}, {1.0, 0.0, 1.0}, {0.0, 1.0, 1.0}, {1.0, 1.0, 1.0},
};

/*
 * The two filter phases side by side: lane 0 phase a, lane 1 phase b. The
 * compiler's vector extension (SSE2 on x86-64, NEON on AArch64), with the
 * IEEE operations of the scalar code lane by lane (no contraction:
 * -ffp-contract=off), so each lane has the bits the phase's scalar
 * arithmetic would give.
 */
typedef double v2d __attribute__((vector_size(16)));
typedef int64_t v2l __attribute__((vector_size(16))); /* v2d's comparisons */

static inline v2d v2(double a, double b) {
    const v2d v = {a, b};
    return v;
}

/* The inverter voltages u_a, u_b of DC link v_dc and the legs' duties dq (ps_inverter_f32()). */
static inline v2d u_of(double v_dc, const double dq[3]) {
    const double v3 = v_dc * (double)(1.0f / 3.0f);
    const v2d dq2 = v2(dq[2], dq[2]);
    return v2(v3, v3) * (((v2(2.0, 2.0) * v2(dq[0], dq[1])) - v2(dq[1], dq[0])) - dq2);
}

/*
 * One ordinary step of the real-time path in double, on z (linear in z:
 * the inputs are entries of z), in the exact path's operations
 * (fast_tick_rt(), power_stage_nodes.h) without its roundings, for the
 * legs' duties dq (shares of the step, 0 to 1: a held state's 0 or 1, an
 * edge's fraction): the new states (the two phases side by side), the
 * DC link, and the step's outputs u_a, u_b, i_dc. step_put() writes them
 * as a new z.
 */
typedef struct {
    v2d il, vc, id, jsh, im; /* the phases' new states */
    v2d u;                   /* the step's inverter voltages */
    double v_dc, i_dc;       /* the new DC link, the step's DC-link current */
} step_out;

static inline void step_d(const double kd[NK], const double dq[3], const double z[NZ],
                          step_out *o) __attribute__((always_inline));
static inline void step_d(const double kd[NK], const double dq[3], const double z[NZ],
                          step_out *o) {
#define KV(i) v2(kd[i], kd[i])
    const v2d dd = v2(dq[0], dq[1]) - v2(dq[2], dq[2]);
    const v2d u = u_of(z[Z_VDC], dq);
    const v2d i0 = v2(z[z_il[0]], z[z_il[1]]);
    const v2d vc = v2(z[z_vc[0]], z[z_vc[1]]);
    const v2d id = v2(z[z_id[0]], z[z_id[1]]);
    const v2d jsh = v2(z[z_jsh[0]], z[z_jsh[1]]);
    const v2d im = v2(z[Z_IF_A], z[Z_IF_B]);
    const v2d jl = (i0 + KV(K_NEG_EPS_L) * i0) + KV(K_G_L2) * (u - vc);
    const v2d dv = KV(K_NODE) * ((jl + jsh) - im);
    const v2d il = jl + KV(K_NEG_G_L) * dv;
    const v2d idn = (id + KV(K_NEG_A_D) * id) + KV(K_G_D) * dv;
    const v2d vcn = vc + dv;
    o->il = il;
    o->vc = vcn;
    o->id = idn;
    o->jsh = ((il - im) - v2(2.0, 2.0) * idn) + KV(K_A_D) * idn;
    o->im = im + (vcn - v2(z[Z_E_A], z[Z_E_B])) * KV(K_L);
    o->u = u;
#undef KV
    const v2d ti = dd * (i0 + il);
    const double t = (0.0 + ti[0]) + ti[1]; /* the phases' sum as the scalar loop forms it */
    o->i_dc = 0.5 * t;
    o->v_dc = z[Z_VDC] + (kd[K_KG] * (z[Z_EV] - z[Z_VDC]) + kd[K_NEG_K_C] * t); /* of the sum t */
}

/* A step's new states into out (z's places 0..10; out may be z itself). */
static inline void step_put(const step_out *o, double out[NZ]) {
    for (int x = 0; x < 2; x++) {
        out[z_il[x]] = o->il[x];
        out[z_vc[x]] = o->vc[x];
        out[z_id[x]] = o->id[x];
        out[z_jsh[x]] = o->jsh[x];
        out[Z_IF_A + x] = o->im[x];
    }
    out[Z_VDC] = o->v_dc;
}

/*
 * One step on z as a column (the tables' and the edge maps' building
 * block): rows 0..10 the new states, then u_a, u_b, i_dc (R_U_A..R_IDC).
 */
static void step_col(const double kd[NK], const double dq[3], const double z[NZ], double col[16]) {
    step_out o;
    step_d(kd, dq, z, &o);
    step_put(&o, col);
    col[R_U_A] = o.u[0];
    col[R_U_B] = o.u[1];
    col[R_IDC] = o.i_dc;
}

/* The one-step map of state s, from the step on the unit vectors. */
static void build_step(leap_tables *L, unsigned s) {
    for (int c = 0; c < NZ; c++) {
        double z[NZ] = {0.0};
        z[c] = 1.0;
        double col[16];
        step_col(L->kd, dq_tab[s], z, col);
        for (int i = 0; i < NZ; i++) {
            L->m[s][c][i] = (i < NX) ? col[i] : z[i]; /* the inputs, held */
        }
        for (int i = 0; i < 3; i++) {
            L->mo[s][c][i] = col[R_U_A + i];
        }
    }
    L->have_m[s] = true;
}

/* P_k[c][r] of entry k (rows 0..10 stored, the input rows the identity). */
static double p_at(const leap_entry *e, int c, int r) {
    if (r < NX) {
        return T_AT(e, c, r);
    }
    return (r == c) ? 1.0 : 0.0;
}

/* Entry 0: the identity, no sums, no bound. */
static void entry_zero(leap_entry *e) {
    memset(e, 0, sizeof *e);
    for (int c = 0; c < NX; c++) {
        T_AT(e, c, c) = 1.0;
    }
}

/* Builds entries built[s] + 1 .. k of state s (out of the leap's line: rare). */
static void build_to(leap_tables *L, unsigned s, uint32_t k) __attribute__((noinline, cold));
static void build_to(leap_tables *L, unsigned s, uint32_t k) {
    if (!L->have_m[s]) {
        build_step(L, s);
    }
    leap_entry *es = L->e[s];
    if (L->built[s] == 0u) {
        entry_zero(&es[0]);
        memset(L->qmax[s], 0, sizeof L->qmax[s]);
    }
    for (uint32_t n = L->built[s] + 1u; n <= k; n++) {
        const leap_entry *prev = &es[n - 1u];
        leap_entry *cur = &es[n];
        memset(cur, 0, sizeof *cur);
        for (int c = 0; c < NZ; c++) {
            /* P_n[:, c] = M P_{n-1}[:, c]; the outputs of the last step O P_{n-1}[:, c]. */
            double col[NZ] = {0.0};
            double oc[3] = {0.0};
            for (int q = 0; q < NZ; q++) {
                const double pq = p_at(prev, c, q);
                if (pq == 0.0) {
                    continue;
                }
                for (int r = 0; r < NX; r++) {
                    col[r] += L->m[s][q][r] * pq;
                }
                for (int r = 0; r < 3; r++) {
                    oc[r] += L->mo[s][q][r] * pq;
                }
            }
            for (int r = 0; r < NX; r++) {
                T_AT(cur, c, r) = col[r];
            }
            T_AT(cur, c, R_SUM + 0) = T_AT(prev, c, R_SUM + 0) + col[Z_VC_A];
            T_AT(cur, c, R_SUM + 1) = T_AT(prev, c, R_SUM + 1) + col[Z_VC_B];
            T_AT(cur, c, R_SUM + 2) = T_AT(prev, c, R_SUM + 2) + col[Z_VDC];
            T_AT(cur, c, R_VDC_LAST) = p_at(prev, c, Z_VDC);
            T_AT(cur, c, R_IDC_LAST) = oc[2];
            /* The second difference Q_{n-2} = P_n - 2 P_{n-1} + P_{n-2} on the clamped rows. */
            if (n >= 2u) {
                const leap_entry *pp = &es[n - 2u];
                for (int i = 0; i < NCLAMP; i++) {
                    const int r = i;
                    const double q2 = fabs(col[r] - 2.0 * p_at(prev, c, r) + p_at(pp, c, r));
                    if (q2 > L->qmax[s][c][i]) {
                        L->qmax[s][c][i] = q2;
                    }
                }
            }
            const double kk = (double)n * (double)n / 8.0;
            for (int i = 0; i < NCLAMP; i++) {
                B_AT(cur, c, i) = kk * L->qmax[s][c][i];
            }
        }
        for (int c = 0; c < NZ; c++) {
            for (int i = 0; i < NB; i++) {
                cur->bs[z_volt(c) ? 1 : 0][i] += B_AT(cur, c, i);
            }
        }
        L->st.entries++;
    }
    L->built[s] = k;
}

/* The edge map of state s and leg x (edge_map) from the step on the unit vectors. */
static void edge_build(leap_tables *L, unsigned s, unsigned x) __attribute__((noinline, cold));
static void edge_build(leap_tables *L, unsigned s, unsigned x) {
    edge_map *E = &L->edge[s][x];
    memset(E, 0, sizeof *E);
    double dq0[3] = {dq_tab[s][0], dq_tab[s][1], dq_tab[s][2]};
    double dq1[3] = {dq0[0], dq0[1], dq0[2]};
    double dqh[3] = {dq0[0], dq0[1], dq0[2]};
    dq0[x] = 0.0;
    dq1[x] = 1.0;
    dqh[x] = 0.5;
    for (int c = 0; c < NZ; c++) {
        double z[NZ] = {0.0};
        z[c] = 1.0;
        double c0[16];
        double c1[16];
        step_col(L->kd, dq0, z, c0);
        step_col(L->kd, dq1, z, c1);
        for (int r = 0; r <= R_IDC; r++) {
            T_AT(&E->a, c, r) = c0[r];
        }
        if (c == Z_VDC) {
            /* A quadratic in d from its values at 0, 1/2 and 1. */
            double ch[16];
            step_col(L->kd, dqh, z, ch);
            for (int r = 0; r <= R_IDC; r++) {
                E->b[r] = 4.0 * ch[r] - 3.0 * c0[r] - c1[r];
                E->c[r] = 2.0 * c1[r] - 4.0 * ch[r] + 2.0 * c0[r];
            }
        } else {
            /* Without v_dc no inverter voltage: d is only in the DC-link current's sum. */
            T_AT(&E->a, c, R_D_VDC) = c1[Z_VDC] - c0[Z_VDC];
            T_AT(&E->a, c, R_D_IDC) = c1[R_IDC] - c0[R_IDC];
        }
    }
    L->have_edge[s][x] = true;
}

/* The tables follow the coefficients: built again from scratch when any changed. */
static void tables_check(leap_tables *L, const drive_segment *d) {
    float key[NK];
    key_of(d, key);
    if (L->keyed && memcmp(key, L->key, sizeof key) == 0) {
        return;
    }
    memcpy(L->key, key, sizeof key);
    for (int i = 0; i < NK; i++) {
        L->kd[i] = (double)key[i];
    }
    L->keyed = true;
    for (unsigned s = 0u; s < NS; s++) {
        L->built[s] = 0u;
        L->have_m[s] = false;
        for (unsigned x = 0u; x < 3u; x++) {
            L->have_edge[s][x] = false;
        }
    }
    L->st.rebuilds++;
}

/* ---- The switching events ------------------------------------------------ */

#define SCAN_MAX 63u /* steps scanned for edges at a time (their 64 grid points: one word) */

/*
 * The leg signs at grid points k..k + n of the frame in force (n <=
 * SCAN_MAX), as the exact path forms them (pwm_rt_ends()): bit j of leg[x] is e_x > 0 at point j,
 * at point k + j, e_x = r_x - c the leg's comparison; a step j has an edge when bit j and
 * bit j + 1 of some leg differ. The comparisons themselves go to e[x][j]
 * (pwm_rt_e_at()'s integers, for the edge steps' duties). Integer only: in
 * AVX2 eight points at a time where the build has it (the same integers),
 * else a plain loop.
 */
typedef struct {
    uint64_t leg[3];                                      /* the signs, a bit per point */
    int32_t e[3][SCAN_MAX + 1u] __attribute__((aligned(32))); /* the comparisons */
} scan_t;

static void scan_signs(const pwm_rt *p, uint32_t k, uint32_t n, scan_t *sc) {
    const pwm_rt_frame *f = &p->fr[pwm_rt_cur(p)];
    const uint32_t inc = p->inc_c;
    const uint32_t ph0 = f->ph0 + k * inc;
    const uint32_t r0a = (uint32_t)pwm_rt_ref(f, 0, k);
    const uint32_t r0b = (uint32_t)pwm_rt_ref(f, 1, k);
    const uint32_t dra = (uint32_t)f->dr[0];
    const uint32_t drb = (uint32_t)f->dr[1];
    uint64_t m[3] = {0u, 0u, 0u};
#if LEAP_AVX2
    /* The carrier's fold as integers: for ph >= 2^31 (s = -1), 2^25 - x = (x ^ s) - s + 2^25. */
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    __m256i ph = _mm256_add_epi32(_mm256_set1_epi32((int32_t)ph0),
                                  _mm256_mullo_epi32(lane, _mm256_set1_epi32((int32_t)inc)));
    __m256i ra = _mm256_add_epi32(_mm256_set1_epi32((int32_t)r0a),
                                  _mm256_mullo_epi32(lane, _mm256_set1_epi32((int32_t)dra)));
    __m256i rb = _mm256_add_epi32(_mm256_set1_epi32((int32_t)r0b),
                                  _mm256_mullo_epi32(lane, _mm256_set1_epi32((int32_t)drb)));
    const __m256i d_ph = _mm256_set1_epi32((int32_t)(8u * inc));
    const __m256i d_ra = _mm256_set1_epi32((int32_t)(8u * dra));
    const __m256i d_rb = _mm256_set1_epi32((int32_t)(8u * drb));
    const __m256i one = _mm256_set1_epi32(PWM_RT_ONE);
    const __m256i top = _mm256_set1_epi32(0x2000000);
    const __m256i zero = _mm256_setzero_si256();
    for (uint32_t j = 0u; j <= n; j += 8u) {
        const __m256i x = _mm256_srli_epi32(ph, 7);
        const __m256i sg = _mm256_srai_epi32(ph, 31);
        const __m256i y = _mm256_add_epi32(_mm256_sub_epi32(_mm256_xor_si256(x, sg), sg),
                                           _mm256_and_si256(sg, top));
        const __m256i c = _mm256_sub_epi32(y, one);
        const __m256i ea = _mm256_sub_epi32(ra, c);
        const __m256i eb = _mm256_sub_epi32(rb, c);
        const __m256i ec = _mm256_sub_epi32(_mm256_sub_epi32(_mm256_sub_epi32(zero, ra), rb), c);
        const __m256i e[3] = {ea, eb, ec};
        for (int l = 0; l < 3; l++) {
            _mm256_store_si256((__m256i *)(void *)&sc->e[l][j], e[l]);
            const int bits = _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(e[l], zero)));
            m[l] |= (uint64_t)(uint32_t)bits << j;
        }
        ph = _mm256_add_epi32(ph, d_ph);
        ra = _mm256_add_epi32(ra, d_ra);
        rb = _mm256_add_epi32(rb, d_rb);
    }
#else
    for (uint32_t j = 0u; j <= n; j++) {
        const uint32_t ph = ph0 + j * inc;
        const uint32_t x = ph >> 7;
        const uint32_t y = ((ph & 0x80000000u) != 0u) ? (0x2000000u - x) : x;
        const int32_t c = (int32_t)y - PWM_RT_ONE;
        const int32_t ra = (int32_t)(r0a + j * dra);
        const int32_t rb = (int32_t)(r0b + j * drb);
        const int32_t e[3] = {ra - c, rb - c, -ra - rb - c};
        for (int l = 0; l < 3; l++) {
            sc->e[l][j] = e[l];
            m[l] |= (uint64_t)(e[l] > 0) << j;
        }
    }
#endif
    /* Points past n (the last block's) dropped: n + 1 <= 64 points. */
    const uint64_t keep = (n >= 63u) ? ~(uint64_t)0 : (((uint64_t)1 << (n + 1u)) - 1u);
    for (int l = 0; l < 3; l++) {
        sc->leg[l] = m[l] & keep;
    }
}

/* The legs' states at point j (bit x: leg x high). */
static unsigned signs_at(const uint64_t leg[3], uint32_t j) {
    return (unsigned)(((leg[0] >> j) & 1u) | (((leg[1] >> j) & 1u) << 1) |
                      (((leg[2] >> j) & 1u) << 2));
}

/* ---- The leap ---------------------------------------------------------------- */

/* The clamp limits less 0.1 % (leap.h), for z[0..7]; j_sh a has none. */
static const double bound_lim[NB] __attribute__((aligned(64))) = {
    256.0 * 0.999, 1024.0 * 0.999, 256.0 * 0.999, 256.0 * 0.999,
    1024.0 * 0.999, 256.0 * 0.999, 1024.0 * 0.999, HUGE_VAL,
};

#if LEAP_AVX2
/*
 * out = M z for a block of eight rows (magnitude: M |z|), as four sums (the
 * columns by their index mod 4) added in a tree, so that each chain of
 * products is a quarter as long: the leap's latency, which the next step
 * waits for.
 */
static inline void block8(const double (*m)[8], const double *z, bool magnitude, double *out) {
    const __m256d mag =
        _mm256_castsi256_pd(_mm256_set1_epi64x(magnitude ? 0x7FFFFFFFFFFFFFFF : (int64_t)-1));
    __m256d lo[4];
    __m256d hi[4];
#pragma GCC unroll 16
    for (int c = 0; c < NZ; c++) {
        const int q = c & 3;
        /* The magnitude's mask only where asked: the compiler keeps an AND with all ones. */
        const __m256d zb = _mm256_broadcast_sd(&z[c]);
        const __m256d zc = magnitude ? _mm256_and_pd(zb, mag) : zb;
        if (c < 4) {
            /* Each sum starts with its first product (a product added to zero is that
             * product but for the sign of a zero, which no sum's use tells apart). */
            lo[q] = _mm256_mul_pd(_mm256_load_pd(m[c]), zc);
            hi[q] = _mm256_mul_pd(_mm256_load_pd(m[c] + 4), zc);
        } else {
            lo[q] = _mm256_fmadd_pd(_mm256_load_pd(m[c]), zc, lo[q]);
            hi[q] = _mm256_fmadd_pd(_mm256_load_pd(m[c] + 4), zc, hi[q]);
        }
    }
    _mm256_store_pd(out, _mm256_add_pd(_mm256_add_pd(lo[0], lo[1]), _mm256_add_pd(lo[2], lo[3])));
    _mm256_store_pd(out + 4,
                    _mm256_add_pd(_mm256_add_pd(hi[0], hi[1]), _mm256_add_pd(hi[2], hi[3])));
}
#endif

#if LEAP_AVX2
/* y = T z (16 rows) of entry en, a block of eight rows at a time: the empty asm keeps the
 * compiler from holding one block's broadcasts of z for the next (more registers than x86-64
 * has). The 512-bit form (product16_512()) has the same bits. */
static inline void product_only(const leap_entry *en, const double *z, double *y) {
    block8(en->m[0], z, false, y);
    __asm__ volatile("" : : "r"(z) : "memory");
    block8(en->m[1], z, false, y + 8);
}

/* The largest of each lane's four values, in every lane. */
static inline __m256d hmax4(__m256d v) {
    const __m256d h = _mm256_max_pd(v, _mm256_permute2f128_pd(v, v, 1));
    return _mm256_max_pd(h, _mm256_permute_pd(h, 5));
}

/* Whether max(|z|, |y|) + bnd is within the limits on rows 0..7 (false for a NaN too). */
static inline bool bound_in(const double *z, const double *y, const __m256d bnd[2]) {
    const __m256d mag = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7FFFFFFFFFFFFFFF));
    bool ok = true;
    for (int h = 0; h < 2; h++) {
        const __m256d a0 = _mm256_and_pd(_mm256_load_pd(z + 4 * h), mag);
        const __m256d a1 = _mm256_and_pd(_mm256_load_pd(y + 4 * h), mag);
        const __m256d hi = _mm256_add_pd(_mm256_max_pd(a0, a1), bnd[h]);
        /* Ordered, non-signalling: false for a NaN too. */
        const __m256d in = _mm256_cmp_pd(hi, _mm256_load_pd(bound_lim + 4 * h), _CMP_LE_OQ);
        ok = ok && (_mm256_movemask_pd(in) == 0xF);
    }
    return ok;
}

/*
 * y = T z (16 rows) of entry en, and whether the bound allows the leap:
 * first the coarse one, B |z| <= bs[0] max |z_I| + bs[1] max |z_V| (the
 * largest current and voltage of z; B is not negative), else B |z| itself.
 * z: 16 values, the last two zero.
 */
static bool product_bounded_256(const leap_entry *en, const double *z, double *y) {
    product_only(en, z, y);
    __asm__ volatile("" : : "r"(z) : "memory");
    const __m256d mag = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7FFFFFFFFFFFFFFF));
    __m256d zi = _mm256_setzero_pd();
    __m256d zv = _mm256_setzero_pd();
    for (int q = 0; q < 4; q++) {
        const __m256d a = _mm256_and_pd(_mm256_load_pd(z + 4 * q), mag);
        const __m256d v =
            _mm256_castsi256_pd(_mm256_load_si256((const __m256i *)(const void *)(volt_mask + 4 * q)));
        zi = _mm256_max_pd(zi, _mm256_andnot_pd(v, a));
        zv = _mm256_max_pd(zv, _mm256_and_pd(v, a));
    }
    zi = hmax4(zi);
    zv = hmax4(zv);
    __m256d bnd[2];
    for (int h = 0; h < 2; h++) {
        bnd[h] = _mm256_add_pd(_mm256_mul_pd(_mm256_load_pd(en->bs[0] + 4 * h), zi),
                               _mm256_mul_pd(_mm256_load_pd(en->bs[1] + 4 * h), zv));
    }
    if (bound_in(z, y, bnd)) {
        return true;
    }
    double b[NB] __attribute__((aligned(64)));
    __asm__ volatile("" : : "r"(z) : "memory");
    block8(en->m[2], z, true, b);
    bnd[0] = _mm256_load_pd(b);
    bnd[1] = _mm256_load_pd(b + 4);
    return bound_in(z, y, bnd);
}

#if LEAP_AVX512
/*
 * product_bounded_256() above in 512-bit vectors: all sixteen rows of T in one
 * pass over z (a block of eight rows a vector), the bound's eight rows in
 * one. Each row's sums are AVX2's (four by the column's index mod 4, each
 * started with its first product and continued by fused multiply-adds in
 * column order, then added in the same tree), the maxima are exact and
 * the coarse bound's products are not fused in either, so y and the
 * verdict have the AVX2 form's bits (leap_forms_check() compares the two).
 */
static inline __m512d sum4_512(const __m512d a[4]) {
    return _mm512_add_pd(_mm512_add_pd(a[0], a[1]), _mm512_add_pd(a[2], a[3]));
}

/* Whether max(|z|, |y|) + bnd is within the limits on rows 0..7 (false for a NaN too). */
static inline bool bound_in512(const double *z, const double *y, __m512d bnd) {
    const __m512d hi = _mm512_add_pd(
        _mm512_max_pd(_mm512_abs_pd(_mm512_load_pd(z)), _mm512_abs_pd(_mm512_load_pd(y))), bnd);
    return _mm512_cmp_pd_mask(hi, _mm512_load_pd(bound_lim), _CMP_LE_OQ) == 0xFF;
}

/* T z of entry en: rows 0..7 in *y0, rows 8..15 in *y1 (AVX2's sums, product_bounded_256()). */
static inline void product16_512(const leap_entry *en, const double *z, __m512d *y0, __m512d *y1) {
    __m512d lo[4];
    __m512d hi[4];
#pragma GCC unroll 16
    for (int c = 0; c < NZ; c++) {
        const int q = c & 3;
        const __m512d zc = _mm512_set1_pd(z[c]);
        if (c < 4) {
            lo[q] = _mm512_mul_pd(_mm512_load_pd(en->m[0][c]), zc);
            hi[q] = _mm512_mul_pd(_mm512_load_pd(en->m[1][c]), zc);
        } else {
            lo[q] = _mm512_fmadd_pd(_mm512_load_pd(en->m[0][c]), zc, lo[q]);
            hi[q] = _mm512_fmadd_pd(_mm512_load_pd(en->m[1][c]), zc, hi[q]);
        }
    }
    *y0 = sum4_512(lo);
    *y1 = sum4_512(hi);
}

static bool product_bounded_512(const leap_entry *en, const double *z, double *y) {
    __m512d y0;
    __m512d y1;
    product16_512(en, z, &y0, &y1);
    _mm512_store_pd(y, y0);
    _mm512_store_pd(y + 8, y1);
    /* The largest |z| of each kind (z's 16 places: two vectors; volt_mask's voltages). */
    const __m512i vm0 = _mm512_load_si512((const void *)volt_mask);
    const __m512i vm1 = _mm512_load_si512((const void *)(volt_mask + 8));
    const __mmask8 volt[2] = {_mm512_test_epi64_mask(vm0, vm0), _mm512_test_epi64_mask(vm1, vm1)};
    const __m512d a0 = _mm512_abs_pd(_mm512_load_pd(z));
    const __m512d a1 = _mm512_abs_pd(_mm512_load_pd(z + 8));
    const __m512d zero = _mm512_setzero_pd();
    const double zi = _mm512_reduce_max_pd(_mm512_max_pd(_mm512_mask_blend_pd(volt[0], a0, zero),
                                                         _mm512_mask_blend_pd(volt[1], a1, zero)));
    const double zv = _mm512_reduce_max_pd(_mm512_max_pd(_mm512_mask_blend_pd(volt[0], zero, a0),
                                                         _mm512_mask_blend_pd(volt[1], zero, a1)));
    const __m512d bnd = _mm512_add_pd(_mm512_mul_pd(_mm512_load_pd(en->bs[0]), _mm512_set1_pd(zi)),
                                      _mm512_mul_pd(_mm512_load_pd(en->bs[1]), _mm512_set1_pd(zv)));
    if (bound_in512(z, y, bnd)) {
        return true;
    }
    __m512d b[4];
#pragma GCC unroll 16
    for (int c = 0; c < NZ; c++) {
        const int q = c & 3;
        const __m512d zc = _mm512_set1_pd(fabs(z[c]));
        b[q] = (c < 4) ? _mm512_mul_pd(_mm512_load_pd(en->m[2][c]), zc)
                       : _mm512_fmadd_pd(_mm512_load_pd(en->m[2][c]), zc, b[q]);
    }
    return bound_in512(z, y, sum4_512(b));
}

#endif
#else
/* y = T z (16 rows) and bnd = B |z| (8 rows) of entry en (in the leap's line: inlined). */
static inline void product(const leap_entry *en, const double *z, double *y, double *bnd)
    __attribute__((always_inline));
static inline void product(const leap_entry *en, const double *z, double *y, double *bnd) {
    for (int r = 0; r < NR; r++) {
        y[r] = 0.0;
    }
    for (int r = 0; r < NB; r++) {
        bnd[r] = 0.0;
    }
    for (int c = 0; c < NZ; c++) {
        const double zc = z[c];
        const double ac = fabs(zc);
        for (int r = 0; r < NR; r++) {
            y[r] += T_AT(en, c, r) * zc;
        }
        for (int r = 0; r < NB; r++) {
            bnd[r] += B_AT(en, c, r) * ac;
        }
    }
}

/* y = T z (16 rows) of entry en (the bound's rows computed and dropped: the edge maps' check). */
static inline void product_only(const leap_entry *en, const double *z, double *y) {
    double bnd[NB];
    product(en, z, y, bnd);
}
#endif

/* xorshift64: a fixed sequence of test values. */
static uint64_t forms_next(uint64_t *x) {
    *x ^= *x << 13;
    *x ^= *x >> 7;
    *x ^= *x << 17;
    return *x;
}

/* A value in [-scale, scale) from the sequence. */
static double forms_value(uint64_t *x, double scale) {
    return scale * ((double)(forms_next(x) >> 11) * 0x1p-52 - 1.0);
}

/*
 * An edge map's y for the duty dq (edge_map), after its product A z: the
 * v_dc column's terms in d and d^2, then the d terms of rows v_dc and i_dc
 * (each a product then a sum, in every form).
 */
static inline void edge_fix(const edge_map *E, double zv, double dq, double *y) {
    for (int i = 0; i < 16; i++) {
        y[i] = y[i] + zv * (dq * (E->b[i] + dq * E->c[i]));
    }
    y[Z_VDC] = y[Z_VDC] + dq * y[R_D_VDC];
    y[R_IDC] = y[R_IDC] + dq * y[R_D_IDC];
}

/* The edge step's y (16 rows) and whether rows 0..7 are within bound_lim (false for a NaN too),
 * in the build's product form: the 512-bit form's reference (leap_forms_check()) and the map's
 * against the step (leap_edge_check()). */
static bool edge_bounded_plain(const edge_map *E, const double *z, double dq, double *y) {
    product_only(&E->a, z, y);
    edge_fix(E, z[Z_VDC], dq, y);
    bool ok = true;
    for (int i = 0; i < NB; i++) {
        ok &= (fabs(y[i]) <= bound_lim[i]);
    }
    return ok;
}

#if LEAP_AVX512
/*
 * edge_bounded_plain() in 512-bit vectors, in registers from the product
 * to the verdict (the same operations lane by lane: the same bits,
 * leap_forms_check()).
 */
static bool edge_bounded_512(const edge_map *E, const double *z, double dq, double *y) {
    __m512d y0;
    __m512d y1;
    product16_512(&E->a, z, &y0, &y1);
    const __m512d d = _mm512_set1_pd(dq);
    const __m512d zv = _mm512_set1_pd(z[Z_VDC]);
    const __m512d w0 = _mm512_mul_pd(
        d, _mm512_add_pd(_mm512_load_pd(E->b), _mm512_mul_pd(d, _mm512_load_pd(E->c))));
    const __m512d w1 = _mm512_mul_pd(
        d, _mm512_add_pd(_mm512_load_pd(E->b + 8), _mm512_mul_pd(d, _mm512_load_pd(E->c + 8))));
    y0 = _mm512_add_pd(y0, _mm512_mul_pd(zv, w0));
    y1 = _mm512_add_pd(y1, _mm512_mul_pd(zv, w1));
    /* Row v_dc (lane 6 of y0) takes row 14 (lane 6 of y1), row i_dc (lane 5 of y1) row 15. */
    y0 = _mm512_mask_add_pd(y0, (__mmask8)(1u << Z_VDC), y0, _mm512_mul_pd(d, y1));
    const __m512i up2 = _mm512_set_epi64(7, 6, 7, 4, 3, 2, 1, 0);
    y1 = _mm512_mask_add_pd(y1, (__mmask8)(1u << (R_IDC - 8)), y1,
                            _mm512_mul_pd(d, _mm512_permutexvar_pd(up2, y1)));
    _mm512_store_pd(y, y0);
    _mm512_store_pd(y + 8, y1);
    return bound_in512(y, y, _mm512_setzero_pd());
}
#endif

#if LEAP_AVX512
long leap_forms_check(uint32_t n, uint32_t *accepted) {
    static leap_entry en;
    double z[16] __attribute__((aligned(64)));
    double y0[NR] __attribute__((aligned(64)));
    double y1[NR] __attribute__((aligned(64)));
    uint64_t x = 0x9E3779B97F4A7C15u;
    long differ = 0;
    *accepted = 0u;
    for (uint32_t i = 0u; i < n; i++) {
        /* Near the identity in T's state rows, B and bs not negative; z at the scale of
         * the limits (a voltage to 1000 V, a current to 250 A), so the verdicts vary. */
        for (int c = 0; c < NZ; c++) {
            for (int r = 0; r < 8; r++) {
                en.m[0][c][r] = ((c == r) ? 1.0 : 0.0) + forms_value(&x, 0.05);
                en.m[1][c][r] = ((c == r + 8) ? 1.0 : 0.0) + forms_value(&x, 0.05);
                en.m[2][c][r] = fabs(forms_value(&x, 0.02));
            }
        }
        for (int h = 0; h < 2; h++) {
            for (int r = 0; r < 8; r++) {
                en.bs[h][r] = fabs(forms_value(&x, 0.1));
            }
        }
        for (int c = 0; c < 16; c++) {
            z[c] = (c >= NZ) ? 0.0 : forms_value(&x, z_volt(c) ? 1000.0 : 250.0);
        }
        const bool a = product_bounded_256(&en, z, y0);
        const bool b = product_bounded_512(&en, z, y1);
        differ += (a != b || memcmp(y0, y1, sizeof y0) != 0) ? 1 : 0;
        /* The edge step's two forms on the same matrix as an edge map's A. */
        static edge_map em;
        em.a = en;
        for (int r = 0; r < 16; r++) {
            em.b[r] = forms_value(&x, 0.05);
            em.c[r] = forms_value(&x, 0.01);
        }
        const double dq = 0.5 + forms_value(&x, 0.5);
        const bool ea = edge_bounded_plain(&em, z, dq, y0);
        const bool eb = edge_bounded_512(&em, z, dq, y1);
        differ += (ea != eb || memcmp(y0, y1, sizeof y0) != 0) ? 1 : 0;
        *accepted += a ? 1u : 0u;
    }
    return differ;
}
#else
/* One form of the product in this build: nothing to compare (leap.h). */
long leap_forms_check(uint32_t n, uint32_t *accepted) {
    (void)n;
    *accepted = 0u;
    return -1;
}
#endif

/*
 * A run's state in double between its two ends (run_load(), run_store()):
 * the leaps and the steps in double work on it, and the drive's float
 * state is formed from it once, at the run's end or before an ordinary
 * step.
 */
typedef struct {
    double z[16] __attribute__((aligned(64))); /* z (leap.h), the last two zero */
    double y[NR] __attribute__((aligned(64))); /* a leap's product (leap_take()) */
    double sum[3];  /* the frame sums of v_C a, v_C b, v_dc since the load */
    double u[2];    /* the last step's inverter voltages (a step in double) ... */
    double v_dc;    /* ... or its DC link at its start, for them (a leap: u_valid false) */
    double i_dc;    /* its DC-link current */
    unsigned s;     /* the legs' states at the last step's end */
    uint32_t taken; /* steps taken since the load: the modulator is moved past them at the
                     * store, and a step's comparisons are at its count plus them */
    bool u_valid;   /* u holds the last step's voltages (else they come from v_dc and s) */
    bool stepped;   /* a step was taken since the load (u or v_dc, i_dc, s hold) */
} run_z;

/* The run's state from the drive's. */
static void run_load(run_z *r, const drive_segment *d) {
    const power_stage_f32 *ps = &d->ps;
    const float zf[NZ] = {
        ps->ph[0].i_l, ps->ph[0].v_c, ps->ph[0].i_d, ps->ph[1].i_l,
        ps->ph[1].v_c, ps->ph[1].i_d, ps->v_dc,      ps->ph[0].j_sh,
        ps->ph[1].j_sh, d->i_fast[0], d->i_fast[1],  d->e[0],
        d->e[1],       d->in.battery.e_v,
    };
    for (int c = 0; c < NZ; c++) {
        r->z[c] = (double)zf[c];
    }
    r->z[14] = 0.0;
    r->z[15] = 0.0;
    r->sum[0] = 0.0;
    r->sum[1] = 0.0;
    r->sum[2] = 0.0;
    r->taken = 0u;
    r->stepped = false;
}

/*
 * The drive's state from the run's: its float states, the frame sums, the
 * last step's outputs; the modulator moved past the steps taken.
 */
static void run_store(const run_z *r, drive_segment *d) {
    if (!r->stepped) {
        return;
    }
    pwm_rt_skip_substep(&d->rt, r->taken); /* unplanned (leap_attach()) */
    power_stage_f32 *ps = &d->ps;
    for (int x = 0; x < 2; x++) {
        ps_phase_f32 *ph = &ps->ph[x];
        ph->i_l = (float)r->z[z_il[x]];
        ph->v_c = (float)r->z[z_vc[x]];
        ph->i_d = (float)r->z[z_id[x]];
        ph->j_sh = (float)r->z[z_jsh[x]];
        d->i_fast[x] = (float)r->z[Z_IF_A + x];
        d->sums.v_cap[x] += (float)r->sum[x];
    }
    if (r->u_valid) {
        ps->u[0] = (float)r->u[0];
        ps->u[1] = (float)r->u[1];
    } else {
        /* A leap's last step: its inverter voltages as the step forms them from its v_dc. */
        const v2d u = u_of(r->v_dc, dq_tab[r->s]);
        ps->u[0] = (float)u[0];
        ps->u[1] = (float)u[1];
    }
    ps->v_dc = (float)r->z[Z_VDC];
    d->sums.v_dc += (float)r->sum[2];
    ps->i_dc = (float)r->i_dc;
    for (unsigned x = 0u; x < 3u; x++) {
        d->s[x] = (int32_t)((r->s >> x) & 1u);
    }
}

/*
 * k steps of switch state s as one map on the run's state, if the bound
 * allows (leap.h): returns false, the run unchanged, otherwise.
 */
static bool leap_take(leap_tables *L, run_z *r, unsigned s, uint32_t k) __attribute__((noinline));
static bool leap_take(leap_tables *L, run_z *r, unsigned s, uint32_t k) {
    if (L->built[s] < k) {
        build_to(L, s, k);
    }
    const leap_entry *en = &L->e[s][k];
    double *z = r->z;
    double *y = r->y;
    /* The bound on rows 0..7: max(|z|, |y|) + the second-difference term. */
#if LEAP_AVX512
    const bool ok = product_bounded_512(en, z, y);
#elif LEAP_AVX2
    const bool ok = product_bounded_256(en, z, y);
#else
    double bnd[NB] __attribute__((aligned(64)));
    product(en, z, y, bnd);
    bool ok = true;
    for (int i = 0; i < NB; i++) {
        const double a0 = fabs(z[i]);
        const double a1 = fabs(y[i]);
        ok &= (((a0 > a1) ? a0 : a1) + bnd[i] <= bound_lim[i]); /* false for a NaN too */
    }
#endif
    if (!ok) {
        L->st.bound_fails++;
        return false;
    }
    for (int c = 0; c < NX; c++) {
        z[c] = y[c];
    }
    r->sum[0] += y[R_SUM + 0];
    r->sum[1] += y[R_SUM + 1];
    r->sum[2] += y[R_SUM + 2];
    r->v_dc = y[R_VDC_LAST];
    r->i_dc = y[R_IDC_LAST];
    r->s = s;
    r->u_valid = false;
    r->taken += k;
    r->stepped = true;
    L->st.leaps++;
    L->st.leap_steps += k;
    return true;
}

/*
 * A step in double taken (its new state already in r->z): the frame sums
 * of its new v_C a, v_C b and v_dc, its outputs, the legs' states sb at its end.
 */
static inline void step_taken(leap_tables *L, run_z *r, unsigned sb, double v_a, double v_b,
                              double v_dc, double u_a, double u_b, double i_dc) {
    r->sum[0] += v_a;
    r->sum[1] += v_b;
    r->sum[2] += v_dc;
    r->u[0] = u_a;
    r->u[1] = u_b;
    r->i_dc = i_dc;
    r->s = sb;
    r->u_valid = true;
    r->taken++;
    r->stepped = true;
    L->st.dsteps++;
}

/* The duty of leg x in the step at the scan's point j, as the stage takes it (ps_fast_legs_f32(): a
 * float share of the step) of pwm_rt_edge_duty(). */
static inline double edge_duty(const drive_segment *d, const scan_t *sc, uint32_t j, unsigned x) {
    return (double)((float)pwm_rt_edge_duty(sc->e[x][j], sc->e[x][j + 1u], d->rt.den_sh) *
                    (1.0f / 32768.0f));
}

#if LEAP_AVX512
/*
 * step_take() of a step in which one leg has an edge, by its edge map
 * (edge_map: the same step in other roundings; the builds without AVX-512
 * take the step itself, faster there: leap.h).
 */
static bool edge_take(leap_tables *L, const drive_segment *d, run_z *r, unsigned sa, unsigned sb,
                      const scan_t *sc, uint32_t j) {
    const unsigned x = (unsigned)__builtin_ctz(sa ^ sb);
    if (!L->have_edge[sa][x]) {
        edge_build(L, sa, x);
    }
    const edge_map *E = &L->edge[sa][x];
    const double dq = edge_duty(d, sc, j, x);
    double *y = r->y;
    if (!edge_bounded_512(E, r->z, dq, y)) {
        return false;
    }
    for (int c = 0; c < NX; c++) {
        r->z[c] = y[c];
    }
    step_taken(L, r, sb, y[Z_VC_A], y[Z_VC_B], y[Z_VDC], y[R_U_A], y[R_U_B], y[R_IDC]);
    return true;
}
#endif

double leap_edge_check(uint32_t n) {
    void *mem = NULL;
    if (posix_memalign(&mem, 64u, sizeof(leap_tables)) != 0) {
        return -1.0;
    }
    leap_tables *L = mem;
    uint64_t x = 0x2545F4914F6CDD1Du;
    double worst = 0.0;
    for (uint32_t i = 0u; i < n; i++) {
        if (i % 64u == 0u) {
            /* Coefficients of the step's sizes and signs, new every 64 cases. */
            const double scale[NK] = {-1e-3, 1e-2, -0.5, 1e-2, 0.5, -0.5, 0.5, -1e-3, 1e-3, 1e-3};
            for (int k = 0; k < NK; k++) {
                L->kd[k] = scale[k] * (1.5 + forms_value(&x, 0.5));
            }
            memset(L->have_edge, 0, sizeof L->have_edge);
        }
        const unsigned s = (unsigned)(forms_next(&x) % NS);
        const unsigned leg = (unsigned)(forms_next(&x) % 3u);
        const double dq = 0.5 + forms_value(&x, 0.5);
        double z[16] __attribute__((aligned(64))) = {0.0};
        for (int c = 0; c < NZ; c++) {
            z[c] = forms_value(&x, z_volt(c) ? 1000.0 : 250.0);
        }
        if (!L->have_edge[s][leg]) {
            edge_build(L, s, leg);
        }
        double y[16] __attribute__((aligned(64)));
        (void)edge_bounded_plain(&L->edge[s][leg], z, dq, y);
        double dv[3] = {dq_tab[s][0], dq_tab[s][1], dq_tab[s][2]};
        dv[leg] = dq;
        double ref[16];
        step_col(L->kd, dv, z, ref);
        double big = 0.0;
        double diff = 0.0;
        for (int r = 0; r <= R_IDC; r++) {
            big = fmax(big, fabs(ref[r]));
            diff = fmax(diff, fabs(y[r] - ref[r]));
        }
        worst = fmax(worst, diff / big);
    }
    free(L);
    return worst;
}

/*
 * One step on the run's state in double (step_d()), from the legs' states
 * sa at its start to sb at its end (scan_signs()'s signs), if no clamped
 * component comes near its limit (the bound's limits, bound_lim): returns
 * false, the run and the modulator unchanged, otherwise. The duties are
 * the modulator's (pwm_rt_substep_each()'s, by pwm_rt_duty()): a leg whose
 * sign does not change holds it over the step (duty 0 or 1), a leg whose
 * sign changes has pwm_rt_edge_duty() of the step's ends (e0, e1: the
 * scan's comparisons at the step's count and the next, pwm_rt_e_at()'s
 * and so pwm_rt_ends()'s).
 */
static bool step_take(leap_tables *L, const drive_segment *d, run_z *r, unsigned sa, unsigned sb,
                      const scan_t *sc, uint32_t j) {
    const unsigned edge = sa ^ sb;
#if LEAP_AVX512
    if (edge != 0u && (edge & (edge - 1u)) == 0u) {
        return edge_take(L, d, r, sa, sb, sc, j); /* one leg's edge: its edge map (leap.h) */
    }
#endif
    double dq[3] = {dq_tab[sa][0], dq_tab[sa][1], dq_tab[sa][2]};
    for (unsigned x = 0u; x < 3u; x++) {
        if (((edge >> x) & 1u) != 0u) {
            /* The duty as the stage takes it (ps_fast_legs_f32(): a float share of the step). */
            dq[x] = edge_duty(d, sc, j, x);
        }
    }
    step_out o;
    step_d(L->kd, dq, r->z, &o);
    /* The clamped components within bound_lim (and j_sh a not a NaN: its limit is infinite);
     * false for a NaN too. */
    const v2d li = v2(bound_lim[Z_IL_A], bound_lim[Z_IL_B]);
    const v2d lv = v2(bound_lim[Z_VC_A], bound_lim[Z_VC_B]);
    const v2d lh = v2(bound_lim[Z_JSH_A], HUGE_VAL);
    const v2d ld = v2(bound_lim[Z_VDC], bound_lim[Z_VDC]);
    const v2d vd = v2(o.v_dc, o.v_dc);
    const v2l in = (o.il <= li) & (o.il >= -li) & (o.id <= li) & (o.id >= -li) &
                   (o.vc <= lv) & (o.vc >= -lv) & (vd <= ld) & (vd >= -ld) & (o.jsh <= lh) &
                   (o.jsh >= -lh);
    if ((in[0] & in[1]) == 0) {
        return false;
    }
    step_put(&o, r->z);
    step_taken(L, r, sb, o.vc[0], o.vc[1], o.v_dc, o.u[0], o.u[1], o.i_dc);
    return true;
}

/* Whether the run may leap at all: the path leap.h describes. */
static bool leap_path(const drive_segment *d) {
    return d->rt_path && d->fast_now == NULL && d->cfg.inverter == DRIVE_INVERTER_SWITCHING &&
           d->cfg.modulator == DRIVE_MODULATOR_SUBSTEP && d->cfg.dead_time_ns == 0u &&
           d->cfg.down == COUPLE_ZOH && d->cfg.up == COUPLE_AVG && !d->cfg.energy_audit;
}

static void ordinary(leap_tables *L, drive_segment *d, uint32_t n) {
    if (n == 1u) {
        drive_fast_step(d); /* the same bits as a run of one, without its copies */
    } else {
        drive_fast_run(d, n);
    }
    L->st.steps += n;
}

/*
 * One step of the run from the legs' states sa to sb: in double, or (near a
 * clamp) an ordinary step on the drive's state.
 */
static void step_one(leap_tables *L, drive_segment *d, run_z *r, unsigned sa, unsigned sb,
                     const scan_t *sc, uint32_t j) {
    if (!step_take(L, d, r, sa, sb, sc, j)) {
        run_store(r, d);
        ordinary(L, d, 1u);
        run_load(r, d);
    }
}

/* A stretch of k steps with no edge in switch state s, from the scan's point j: leaps, or
 * steps one by one. */
static void stretch(leap_tables *L, drive_segment *d, run_z *r, unsigned s, uint32_t k,
                    const scan_t *sc, uint32_t j) {
    while (k >= LEAP_K_MIN) {
        uint32_t m = (k < LEAP_K_MAX) ? k : LEAP_K_MAX;
        while (m >= LEAP_K_MIN && !leap_take(L, r, s, m)) {
            m /= 2u; /* the bound refused: a shorter leap */
        }
        if (m < LEAP_K_MIN) {
            break;
        }
        k -= m;
    }
    for (; k > 0u; k--) {
        step_one(L, d, r, s, s, sc, j); /* no edge: the comparisons are not read */
    }
}

static void leap_run(void *ctx, drive_segment *d, uint32_t n) {
    leap_tables *L = ctx;
    if (n < LEAP_K_MIN || !leap_path(d)) {
        ordinary(L, d, n);
        return;
    }
    tables_check(L, d);
    run_z r;
    run_load(&r, d);
    uint32_t done = 0u;
    while (done < n) {
        const uint32_t m = (n - done < SCAN_MAX) ? n - done : SCAN_MAX;
        scan_t sc;
        scan_signs(&d->rt, pwm_rt_k(&d->rt) + r.taken, m, &sc);
        const uint64_t *leg = sc.leg;
        /* Bit j: step j (j < m) has an edge. */
        const uint64_t edges = ((leg[0] ^ (leg[0] >> 1)) | (leg[1] ^ (leg[1] >> 1)) |
                                (leg[2] ^ (leg[2] >> 1))) &
                               (((uint64_t)1 << m) - 1u);
        uint32_t j = 0u;
        unsigned s = signs_at(leg, 0u); /* the legs' states at point j */
        while (j < m) {
            const uint64_t ahead = edges >> j;
            uint32_t i = (ahead != 0u) ? j + (uint32_t)__builtin_ctzll(ahead) : m;
            /* Steps j..i-1 hold the legs' states s; step i (if i < m) has an edge. */
            if (i > j) {
                stretch(L, d, &r, s, i - j, &sc, j);
            }
            if (i < m) {
                const unsigned sb = signs_at(leg, i + 1u);
                step_one(L, d, &r, s, sb, &sc, i);
                s = sb;
                i++;
            }
            j = i;
        }
        done += m;
    }
    run_store(&r, d);
}

bool leap_attach(exec *e) {
    void *mem = NULL;
    if (posix_memalign(&mem, 64u, sizeof(leap_tables)) != 0) {
        return false;
    }
    leap_tables *L = mem;
    memset(L, 0, sizeof *L);
    if (e->drive.cfg.inverter == DRIVE_INVERTER_SWITCHING) {
        /* The leaps find the edges themselves (scan_signs()) and the steps in double form
         * their duties from the comparisons: the motor task's frame plans would only serve
         * the rare ordinary steps, at more than those steps cost, and the steps computed one
         * by one give the plans' duties and states bit for bit (pwm_rt.h).
         * Without plans (n = 0) every frame starts again in the one in force (pwm_rt_apply()). */
        pwm_rt_frames(&e->drive.rt, 0u);
    }
    e->desk_run = leap_run;
    e->desk_ctx = L;
    return true;
}

void leap_detach(exec *e) {
    if (e->desk_run == leap_run) {
        free(e->desk_ctx);
        e->desk_run = NULL;
        e->desk_ctx = NULL;
    }
}

leap_stats leap_stats_of(const exec *e) {
    leap_stats z = {0};
    if (e->desk_run == leap_run) {
        return ((const leap_tables *)e->desk_ctx)->st;
    }
    return z;
}

#else /* UUV_NUMERIC_FIXED: no leaps (leap.h) */

bool leap_available(void) { return false; }

bool leap_attach(exec *e) {
    (void)e;
    return false;
}

void leap_detach(exec *e) { (void)e; }

leap_stats leap_stats_of(const exec *e) {
    (void)e;
    leap_stats z = {0};
    return z;
}

long leap_forms_check(uint32_t n, uint32_t *accepted) {
    (void)n;
    *accepted = 0u;
    return -1;
}

double leap_edge_check(uint32_t n) {
    (void)n;
    return -1.0;
}

#endif
