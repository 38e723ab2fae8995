/* params.h — contact parameters of one pair of materials, mixed once at
 * prepare time (world/material.c) so the per-pair loop only reads them.
 *
 * Plain struct, SD_HD-safe: the GPU kernels read the same table.
 */
#ifndef SD_CONTACT_PARAMS_H
#define SD_CONTACT_PARAMS_H

#include "core/base.h"

/* Exponents p at which the volume laws' damping is calibrated (law_volume.h). */
#define SD_VOLUME_ZETA_N 9

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
    /* -, damping ratios zeta(e, p) on SD_VOLUME_ZETA_N force-overlap
     * exponents p, uniform in [1/3, 3] (calibrated in world/material.c) */
    sd_real zeta[SD_VOLUME_ZETA_N];
} sd_pair_params;

#endif
