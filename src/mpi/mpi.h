/* mpi.h — domain decomposition over MPI ranks (built with SHAPEDEM_MPI;
 * the serial build has none of it): every particle kind (spheres, convex
 * shapes, sharp polyhedra under the volume law, composites, the planar
 * mode) with fixed and moving walls (prescribed motions, servo walls,
 * drums, triangle meshes), insertions and outlets, on the cells solver and
 * the CPU backend, a split along x.
 *
 * Each rank builds the same world (the same scene: every particle on every
 * rank), then sd_mpi_attach keeps the particles of its own sub-domain and
 * hooks the exchanges into the world's rebuild and step (sd_world_comm,
 * world/world.h):
 *
 *   split: the particles sorted by (x, stable id) and cut into runs of
 *          equal count, one per rank (weighted by particle count); rank r
 *          owns the particles whose (x, id) lies in [cut_r, cut_r+1)
 *   migration: at each rebuild (every rank rebuilds when any must), an
 *          owned particle whose (x, id) left its sub-domain goes to the rank
 *          that owns it now, with its pair and wall history entries (by
 *          key: the receiving rank's next list finds them as its own;
 *          every HISTORY field of broad/pairs.h: springs, and the volume
 *          law's overlap hints x0)
 *   ghosts: at each rebuild every owned particle within the contact reach
 *          2 r_max + skin (r_max: the largest bounding radius of all
 *          ranks, a composite's enclosing its elements) of another rank's
 *          slab is sent there as a ghost
 *          (ghost_owner SD_GHOST_REMOTE); each step the same particles'
 *          rows are sent again, after the drift
 *   periodic axes: every owned particle's images (world/rebuild.c's rule
 *          and its arithmetic, x + shift) are local ghosts, as in the
 *          serial run; an image within reach of another rank's slab goes
 *          there (SD_GHOST_REMOTE_IMAGE), and so does the particle as it is
 *          when it is within reach of that slab one period away in x: a
 *          contact through an image is evaluated at the true position of
 *          the lower id on both ranks (broad/bins.h, the one ghost-ghost
 *          pair kept)
 *   insertions and outlets (world/process.c): every rank draws, checks
 *          (against every rank's particles) and adds each inserted particle
 *          alike, then keeps those it owns; outlets' counts and masses are
 *          summed over the ranks in stable-id order
 *   servo walls (world/servo.c): the force and contact stiffness a servo
 *          reads are summed over every rank's wall pairs in key order
 *   order: the pair lists take the canonical order (sd_pairs_canonical),
 *          so each particle's force sum, and so the state, has the same
 *          bits on any rank count (a composite pair's run of element
 *          pairs in the order of its keys' sub-indices)
 *
 * Errors: a failing MPI call aborts every rank (MPI_ERRORS_ARE_FATAL, the
 * default); a guard or the finite check failing on one rank stops every
 * rank at that step (they run at the same steps everywhere: mpi/drive.c);
 * another engine error on one rank is reported by that rank and ends the
 * job with sd_mpi_fail, never a hang of the others in a collective.
 */
#ifndef SD_MPI_MPI_H
#define SD_MPI_MPI_H

#include <shapedem/shapedem.h>

/* ---- the split (mpi/decomp.c: no MPI in it) --------------------------------- */

/* A cut of the x axis: (x, id) pairs at or above it are on the next rank's
 * side. */
typedef struct sd_mpi_cut {
    double x;
    uint64_t id;
} sd_mpi_cut;

/* The ranks-1 cuts that share n particles (positions x, ids id) out in
 * runs of equal count, sorted by (x, id): rank r gets particles
 * floor(r n / ranks) .. floor((r + 1) n / ranks) - 1 of that order. cuts
 * gets ranks - 1 entries. Fails only without memory. */
sd_status sd_mpi_split(size_t n, const double *x, const uint64_t *id, int ranks, sd_mpi_cut *cuts);
/* The rank that owns (x, id) under the cuts. */
int sd_mpi_rank_of(const sd_mpi_cut *cuts, int ranks, double x, uint64_t id);
/* Rank r's slab [lo, hi] along x (-inf / +inf at the ends). */
void sd_mpi_slab(const sd_mpi_cut *cuts, int ranks, int r, double *lo, double *hi);

/* ---- the decomposed run (mpi/comm.c) ------------------------------------------ */

typedef struct sd_mpi sd_mpi;

/* Splits world w (every rank's copy holding the same particles, not yet
 * prepared: sd_mpi_attach_built takes a world sd_scene_build made) over
 * the ranks of MPI_COMM_WORLD: keeps this rank's particles and installs
 * the hooks. MPI must be initialised. Refuses what
 * is not decomposed yet (the grid solver, a device backend) with
 * SD_ERR_INPUT. */
sd_status sd_mpi_attach(sd_world *w, sd_mpi **out, sd_error *err);
/* The hooks off and the memory freed (the world stays, holding its own
 * particles). */
void sd_mpi_detach(sd_world *w, sd_mpi *m);
int sd_mpi_rank(const sd_mpi *m);
int sd_mpi_size(const sd_mpi *m);
/* Particles this rank has sent to others since attach; ghosts it holds. */
size_t sd_mpi_migrated(const sd_mpi *m);
/* History entries (pair and wall springs, overlap hints) sent with the
 * migrated particles; of them, those holding a volume law's overlap hint
 * (the interior point x0, broad/pairs.h), and those of wall pairs. */
size_t sd_mpi_carried(const sd_mpi *m);
size_t sd_mpi_carried_hints(const sd_mpi *m);
size_t sd_mpi_carried_walls(const sd_mpi *m);
size_t sd_mpi_ghosts(const sd_mpi *m);
/* The owned particles of every rank, on rank 0, in stable-id order: *out
 * gets *n states (sd_free them; NULL and 0 on the other ranks). Collective. */
sd_status sd_mpi_gather(const sd_mpi *m, const sd_world *w, sd_particle_state **out, size_t *n, sd_error *err);
/* Ends the whole job after an error on this rank: one message on stderr,
 * naming the rank and the stage, then MPI_Abort with status 2 (input) or 1. */
_Noreturn void sd_mpi_fail(const sd_mpi *m, const char *stage, sd_status st, const sd_error *err);
/* The rank - 1 cuts of the split in use. */
const sd_mpi_cut *sd_mpi_cuts(const sd_mpi *m);

/* Rebalancing (mpi/rebalance.c): at the first rebuild at or after every
 * `every` steps from from_step, before the migration, the cuts are made
 * again from every rank's particles (sd_mpi_split: equal counts by (x,
 * id)), and the migration moves the particles to their new ranks. The
 * state does not change (its bits do not depend on the split), nor do the
 * rebuilds' steps: no rebuild is added. */
void sd_mpi_set_rebalance(sd_mpi *m, long every, long from_step);
long sd_mpi_rebalances(const sd_mpi *m);
/* Collective: new cuts (ranks - 1) from the owned particles of every rank
 * of w. */
sd_status sd_mpi_recut(const sd_world *w, int ranks, sd_mpi_cut *cuts, sd_error *err);

/* A particle as one row of bytes: every SD_PARTICLE_FIELDS field in turn
 * (comm.c; what migration and the ghosts send). */
struct sd_particles;
size_t sd_mpi_row_size(void);
unsigned char *sd_mpi_row_pack(const struct sd_particles *p, size_t k, unsigned char *b);
const unsigned char *sd_mpi_row_unpack(struct sd_particles *p, size_t k, const unsigned char *b);

/* ---- the whole world on rank 0 (mpi/view.c) ------------------------------------ */

/* Collective. Puts into g, on rank 0, the state of the decomposed world w
 * as one serial world would hold it: every rank's owned particles in
 * stable-id order; the pairs (each once: from the rank that owns its lower
 * id) and the wall pairs, in (kind, key) order, their bodies indexed in g;
 * the walls with their totals summed over those wall pairs in that order;
 * the clock. g is a world built from the same scene and never stepped
 * (the output reads it: frames, stats.csv, walls.csv, the analyses,
 * checkpoints); the other ranks pass NULL. The sums over g are therefore
 * in an order of stable ids, the same bits on any rank count. */
sd_status sd_mpi_view(const sd_mpi *m, const sd_world *w, sd_world *g, sd_error *err);

/* ---- checkpoints from every rank (mpi/ckpt.c) ------------------------------------ */

/* Collective. Writes the decomposed world w as the checkpoint at path that
 * rank 0 would write from the view g (sd_checkpoint_write(g, ...): the same
 * datasets, rows and attributes), every rank writing its block of the
 * rows into the one file through MPI-IO (io/checkpoint.h,
 * sd_checkpoint_write_collective; where sd_checkpoint_collective() is 0 it
 * returns SD_ERR_INTERNAL). g is rank 0's current view (its small datasets
 * are written from it), NULL on the other ranks. The status is the same on
 * every rank; err is filled on rank 0. */
sd_status sd_mpi_checkpoint_write(const sd_mpi *m, const sd_world *w, const sd_world *g, const char *path,
                                  sd_error *err);

/* ---- `shapedem run` under mpirun (mpi/drive.c) ------------------------------------ */

/* Rank 0 runs the scene's schedule (io/run.c) on the view g and tells the
 * other ranks, which follow, when to step: a command is broadcast, every
 * rank steps its particles, then the view is gathered. */
typedef struct sd_mpi_drive {
    sd_mpi *m;
    sd_world *w; /* this rank's part */
    sd_world *g; /* rank 0: the view (sd_mpi_view) */
} sd_mpi_drive;

/* Rank 0, the run's stepper (io/run.h): every rank steps n steps, then g
 * is gathered. A guard or the finite check failing on some rank stops
 * every rank at that step (the checks run at the same steps on every
 * rank): the lowest such rank's error is returned, naming it, and g holds
 * the state then (the run writes failed-<step>.h5 from it). Another error
 * inside a rank's step ends the job from that rank (sd_mpi_fail); a failed
 * gather is returned. */
sd_status sd_mpi_drive_step(void *drive, long n, sd_error *err);
/* Rank 0, collective with the followers: g gathered again (after a
 * restore or a change outside the steps). */
sd_status sd_mpi_drive_view(sd_mpi_drive *d, sd_error *err);
/* Rank 0: the followers stop; note gets summary.txt's lines on the ranks
 * (the split, particles per rank now, migrations). */
void sd_mpi_drive_end(sd_mpi_drive *d, char *note, size_t size);
/* sd_mpi_attach for a world that sd_scene_build made (prepared, at step
 * 0): its pair lists, ghosts and rebuild count are dropped first, so the
 * decomposed world prepares as one never prepared would. */
sd_status sd_mpi_attach_built(sd_world *w, sd_mpi **out, sd_error *err);
/* sd_mpi_attach for a world restored from a checkpoint (prepared, its
 * forces those saved): the pair lists keep only the springs, by key, of
 * every pair, and the world is marked for a rebuild at its next step
 * (the rebuild carries them), which the run that wrote the checkpoint
 * made too (sd_mpi_drive_write). */
sd_status sd_mpi_attach_restored(sd_world *w, sd_mpi **out, sd_error *err);
/* Rank 0, the run's checkpoint writer (io/run.h): every rank's world, and
 * the view, marked for a rebuild at the next step; then the state written
 * at path, from every rank into one file where the build writes through
 * MPI-IO (sd_mpi_checkpoint_write), else by rank 0 from the view. */
sd_status sd_mpi_drive_write(void *drive, const char *path, sd_error *err);
/* Every rank, after the attach: the time of this rank's steps and of its
 * exchanges is kept, for sd_mpi_drive_end's lines (mpi_step_seconds,
 * mpi_exchange_seconds, mpi_exchange_share). */
void sd_mpi_drive_time(sd_world *w);
/* Ranks other than 0: follow rank 0's commands until it ends the run. */
void sd_mpi_follow(sd_mpi *m, sd_world *w);

#endif
