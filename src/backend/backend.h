/* backend.h — the backend stage interface: the stages of one time step as
 * a host-side table of functions, so that world/step.c names stages and a
 * backend (the CPU's OpenMP loops now, CUDA kernels next) says how each
 * runs (architecture review §9.2, seam 4).
 *
 * Invariants: every stage works on the views of backend/view.h (struct
 * sd_stage), never on sd_world, except rebuild, which hands the world to
 * the broad phase (broad/ builds the pair lists on the host; the world
 * refills the views after it; under MPI the migration and the ghosts run
 * inside it, on the host). Every entry is set. Whatever the host reads or
 * writes between stages a device backend copies around it: read_back
 * before the host reads the state (output, guards, a rebuild), upload
 * after the host changed it, and within a step only the narrow copies
 * (the wall pairs for the wall motion, the state rows around the ghost
 * exchange of a decomposed run). The table is called a
 * few times per step, never per particle or per pair: the indirect calls
 * cost nothing, and DESIGN.md rule 6 forbids function pointers in device
 * code only. Stages run in the order step.c gives; each one writes only
 * its own outputs, so the results do not depend on the thread count.
 * Stages return no status: a failure (only a device can fail) sticks in
 * the backend until step.c asks `status` at its next check.
 */
#ifndef SD_BACKEND_BACKEND_H
#define SD_BACKEND_BACKEND_H

#include <shapedem/shapedem.h>

#include "backend/view.h"

typedef struct sd_backend {
    const char *name;
    /* the views were refilled (prepare, rebuild): copy what the backend
     * keeps on its side (a device copies the arrays; the CPU has nothing
     * to do) */
    void (*upload)(sd_stage *s);
    /* the walls moved or changed speed (every step): their views */
    void (*upload_walls)(sd_stage *s);
    /* first half kick and drift of every particle (velocity Verlet) */
    void (*kick_drift)(sd_stage *s);
    /* 1 when some particle used up half the skin since the last rebuild */
    int (*needs_rebuild)(sd_stage *s);
    /* new pair lists (broad phase), history carried by key */
    sd_status (*rebuild)(sd_world *w, sd_error *err);
    /* refreshes the local ghosts' state from their owners (periodic
     * images; another rank's particles are the decomposition's) */
    void (*exchange_ghosts)(sd_stage *s);
    /* forces of one kind segment of the particle pairs (contact/kinds.h) */
    void (*forces)(sd_stage *s, sd_pair_kind kind);
    /* forces of every particle-wall pair, kind by kind */
    void (*wall_forces)(sd_stage *s);
    /* total force and torque on each wall (s->wall_force, s->wall_torque);
     * when no wall moves (s->v.walls_moving 0) a device backend may leave
     * them to read_back, which sums the same pairs in the same order */
    void (*wall_totals)(sd_stage *s);
    /* each particle sums its pairs in list order */
    void (*gather)(sd_stage *s);
    /* the same, then the second half kick */
    void (*gather_kick)(sd_stage *s);
    /* the same, then the first half kick and the drift of the next step,
     * in one pass (the same operations in the same order: the same bits) */
    void (*gather_kick_drift)(sd_stage *s);
    /* 1 when some particle's position, velocity, spin or orientation is
     * not finite */
    int (*check_finite)(sd_stage *s);
    /* smallest particle radius (m; +inf without particles): the default skin */
    sd_real (*min_radius)(sd_stage *s);
    /* the state is wanted on the host (output, queries, the guards, a
     * rebuild): copies the particle state, the pairs' history and results
     * and the narrow-phase tallies back (the CPU's state is the host's:
     * nothing to do) */
    void (*read_back)(sd_stage *s);
    /* the wall pairs' overlaps and forces only: what the host's wall
     * motion reads each step (servo stiffness; under MPI the servo walls'
     * forces summed over the ranks, world/servo.c) */
    void (*read_back_wall_pairs)(sd_stage *s);
    /* a decomposed run's ghost exchange (step.c, w->comm) sends the owned
     * particles' rows from the host's arrays and writes the ghosts' rows
     * there, each step: read_back_state copies the particle state the
     * stages write (x, v, w, q, f, t) of rows [first, end) to the host,
     * upload_state those rows from the host (the rows only: the views are
     * those of the last upload; the CPU's state is the host's: nothing to
     * do) */
    void (*read_back_state)(sd_stage *s, size_t first, size_t end);
    void (*upload_state)(sd_stage *s, size_t first, size_t end);
    /* the world is destroyed: frees what the backend keeps (s->device) */
    void (*release)(sd_stage *s);
    /* SD_OK, or the first error since the last call (a device backend's
     * calls fail asynchronously: out of device memory with the bytes it
     * needed, a kernel fault; the message names the stage); step.c asks
     * after every upload and at every finite check */
    sd_status (*status)(sd_stage *s, sd_error *err);
} sd_backend;

/* The CPU backend (backend/cpu/); the CUDA backend's table comes from
 * sd_cuda_backend() (backend/cuda/cuda.h), NULL when not compiled in. */
extern const sd_backend sd_backend_cpu;

#endif
