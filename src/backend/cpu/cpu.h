/* cpu.h — the CPU backend's stages (OpenMP loops over the views of
 * backend/view.h), gathered into sd_backend_cpu by cpu.c. No physics
 * lives here; the loop bodies are the item functions of backend/items.h
 * and the integrator of dynamics/integrate.h. */
#ifndef SD_BACKEND_CPU_CPU_H
#define SD_BACKEND_CPU_CPU_H

#include "backend/backend.h"

/* particles.c */
void sd_cpu_kick_drift(sd_stage *s);
void sd_cpu_gather(sd_stage *s);
void sd_cpu_gather_kick(sd_stage *s);
void sd_cpu_gather_kick_drift(sd_stage *s);
int sd_cpu_needs_rebuild(sd_stage *s);
int sd_cpu_check_finite(sd_stage *s);
sd_real sd_cpu_min_radius(sd_stage *s);
void sd_cpu_exchange_ghosts(sd_stage *s);
void sd_cpu_wall_totals(sd_stage *s);
/* pairs.c */
void sd_cpu_forces(sd_stage *s, sd_pair_kind kind);
/* walls.c */
void sd_cpu_wall_forces(sd_stage *s);

#endif
