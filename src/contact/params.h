/* params.h — contact parameters of one pair of materials, mixed once at
 * prepare time (world/material.c) so the per-pair loop only reads them;
 * and the law table's columns (shapedem.h SD_CONTACT_LAWS) as queries.
 *
 * Plain struct, SD_HD-safe: the GPU kernels read the same table.
 * Invariant: what a law needs and is comes from its row of
 * SD_CONTACT_LAWS only; the checks (world/material.c, the scene loader)
 * and the code that depends on a law's kind read these functions, so a new
 * law is one row plus its case in contact/law.h.
 */
#ifndef SD_CONTACT_PARAMS_H
#define SD_CONTACT_PARAMS_H

#include <stddef.h>

#include <shapedem/shapedem.h>

#include "core/base.h"

/* The needs column of a law (SD_LAW_NEEDS_*), 0 for an unknown law. */
SD_HD static SD_INLINE unsigned sd_law_needs(int law)
{
    switch (law) {
#define SD_X_NEEDS(e, name, doc, needs, traits) \
    case e:                                      \
        return needs;
        SD_CONTACT_LAWS(SD_X_NEEDS)
#undef SD_X_NEEDS
    default:
        return 0u;
    }
}

/* The traits column of a law (SD_LAW_IS_*), 0 for an unknown law. */
SD_HD static SD_INLINE unsigned sd_law_traits(int law)
{
    switch (law) {
#define SD_X_TRAITS(e, name, doc, needs, traits) \
    case e:                                       \
        return traits;
        SD_CONTACT_LAWS(SD_X_TRAITS)
#undef SD_X_TRAITS
    default:
        return 0u;
    }
}

/* What one material need is (host side: the checks' messages), from its
 * flag: the scene key and the def field holding the value (in the
 * material, and in the interaction when a pair may set it there), whether
 * only particles' materials need it (walls are rigid), and a note for the
 * message. SD_LAW_NEEDS_SHARP is about shapes, not a value: 0. */
typedef struct sd_law_need {
    const char *key;          /* material key, "youngs_modulus" */
    const char *unit;         /* "Pa" */
    const char *what;         /* "Young's modulus" */
    const char *note;         /* appended to the scene loader's message */
    size_t material_field;    /* offsetof(sd_material_def, ...) */
    long interaction_field;   /* offsetof(sd_interaction_def, ...), or -1 */
    int particles_only;
} sd_law_need;

static inline int sd_law_need_of(unsigned flag, sd_law_need *out)
{
    sd_law_need n = {"", "", "", "", 0, -1, 0};
    switch (flag) {
    case SD_LAW_NEEDS_MODULUS:
        n.key = "youngs_modulus", n.unit = "Pa", n.what = "Young's modulus";
        n.material_field = offsetof(sd_material_def, youngs_modulus);
        break;
    case SD_LAW_NEEDS_PARTICLE_MODULUS:
        n.key = "youngs_modulus", n.unit = "Pa", n.what = "Young's modulus", n.note = " (eq. 13 of [Xu n.d.])";
        n.material_field = offsetof(sd_material_def, youngs_modulus);
        n.particles_only = 1;
        break;
    case SD_LAW_NEEDS_STIFFNESS:
        n.key = "stiffness", n.unit = "N/m", n.what = "stiffness";
        n.material_field = offsetof(sd_material_def, stiffness);
        n.interaction_field = (long)offsetof(sd_interaction_def, stiffness);
        break;
    case SD_LAW_NEEDS_VOLUME_STIFFNESS:
        n.key = "volume_stiffness", n.unit = "N/m^3", n.what = "volume stiffness";
        n.material_field = offsetof(sd_material_def, volume_stiffness);
        n.interaction_field = (long)offsetof(sd_interaction_def, volume_stiffness);
        break;
    default:
        return 0;
    }
    *out = n;
    return 1;
}

/* The value a need reads from a def (sd_material_def or
 * sd_interaction_def) at one of the need's fields: a double. */
static inline double sd_law_need_field(const void *def, size_t field)
{
    return *(const double *)(const void *)((const char *)def + field);
}

/* Exponents p at which the volume laws' damping is calibrated (law_volume.h):
 * 1/3 .. 5 in steps of 1/3 (5: a vertex contact inside the volume law's
 * regularised range, F ~ |S| V ~ d^5). */
#define SD_VOLUME_ZETA_N 15

typedef struct sd_pair_params {
    int law;             /* sd_contact_law */
    sd_real y_star;      /* Pa, effective Young's modulus 1/((1-v1^2)/E1 + (1-v2^2)/E2) */
    sd_real g_star;      /* Pa, effective shear modulus */
    sd_real gt_over_gn;  /* -, Hertz: tangential over normal damping, sqrt(4 G* / Y*) */
    sd_real kn;          /* N/m, linear law normal stiffness */
    sd_real kt_ratio;    /* -, linear law k_t / k_n */
    sd_real eta;         /* N s/m, linear law viscous coefficient; 0 = from restitution */
    sd_real restitution; /* -, e_n */
    sd_real log_e_factor;/* -, beta = ln e / sqrt(ln^2 e + pi^2) (<= 0) */
    sd_real friction;    /* -, mu */
    sd_real rolling;     /* -, rolling resistance coefficient */
    /* volume laws (contact/law_volume.h): a = the material of body i (the
     * particle, against a wall), b = the material of body j */
    sd_real young_a, young_b; /* Pa, E of seed 000 eq. 13 */
    sd_real shear_a, shear_b; /* Pa, E / (2 (1 + nu)) of seed 000 eq. 19 */
    sd_real kv;          /* N/m^3, volume_linear stiffness k_V */
    sd_real face_omega;  /* -, volume law: omega dt of a face at zero overlap (regularisation), 0 = off */
    /* -, damping ratios zeta(e, p) on SD_VOLUME_ZETA_N force-overlap
     * exponents p, uniform in [1/3, 5] (calibrated in world/material.c) */
    sd_real zeta[SD_VOLUME_ZETA_N];
} sd_pair_params;

/* 1 when a mixed pair holds the values its law needs (its needs column):
 * Y* of two moduli, E of the first body (the particle, against a wall),
 * k_n, k_V. */
SD_HD static SD_INLINE int sd_law_params_ready(const sd_pair_params *p)
{
    unsigned needs = sd_law_needs(p->law);
    return !((needs & SD_LAW_NEEDS_MODULUS) && !(p->y_star > SD_R(0.0))) &&
           !((needs & SD_LAW_NEEDS_PARTICLE_MODULUS) && !(p->young_a > SD_R(0.0))) &&
           !((needs & SD_LAW_NEEDS_STIFFNESS) && !(p->kn > SD_R(0.0))) &&
           !((needs & SD_LAW_NEEDS_VOLUME_STIFFNESS) && !(p->kv > SD_R(0.0)));
}

#endif
