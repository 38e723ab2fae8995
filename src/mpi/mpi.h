/* mpi.h — domain decomposition over MPI ranks (the exchanges, the view,
 * the drive and the checkpoints are built with SHAPEDEM_MPI only; the
 * split, mpi/decomp.c and mpi/plan.c, calls no MPI and is in every build,
 * for `shapedem check --ranks N`): every particle kind (spheres, convex
 * shapes, sharp polyhedra under the volume law, composites, the planar
 * mode) with fixed and moving walls (prescribed motions, servo walls,
 * drums, triangle meshes), insertions and outlets, on the cells solver,
 * the CPU or the CUDA backend (one rank per GPU), a split into a grid of
 * boxes.
 *
 * Each rank builds the same world (the same scene: every particle on every
 * rank), then sd_mpi_attach keeps the particles of its own sub-domain and
 * hooks the exchanges into the world's rebuild and step (sd_world_comm,
 * world/world.h):
 *
 *   split: px x py x pz boxes (simulation.mpi_split; auto: the least cut
 *          area, mpi/plan.c), nested cuts by count: the particles sorted
 *          by (x, stable id) cut into px runs of equal count, each run
 *          sorted by (y, id) into py, each of those by (z, id) into pz;
 *          rank (i0 py + i1) pz + i2 owns the particles of run (i0, i1,
 *          i2), a box (+-inf at the outer faces). A world filled by
 *          insertion (fewer particles than ranks) is cut evenly over the
 *          insertion regions instead
 *   migration: at each rebuild (every rank rebuilds when any must), an
 *          owned particle whose position and id left its box goes to the rank
 *          that owns it now, with its pair and wall history entries (by
 *          key: the receiving rank's next list finds them as its own;
 *          every HISTORY field of broad/pairs.h: springs, and the volume
 *          law's overlap hints x0)
 *   ghosts: at each rebuild every owned particle within the contact reach
 *          2 r_max + skin (r_max: the largest bounding radius of all
 *          ranks, a composite's enclosing its elements) of another rank's
 *          box on every axis (the boxes across an edge or a corner too)
 *          is sent there as a ghost
 *          (ghost_owner SD_GHOST_REMOTE); each step the same particles'
 *          rows are sent again, after the drift
 *   periodic axes: every owned particle's images (world/rebuild.c's rule
 *          and its arithmetic, x + shift) are local ghosts, as in the
 *          serial run; an image within reach of another rank's box goes
 *          there (SD_GHOST_REMOTE_IMAGE), and so does the particle as it is
 *          when it is within reach of that box one period away on one or
 *          more periodic axes: a
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
#include <signal.h>

/* ---- the split (mpi/decomp.c: no MPI in it) --------------------------------- */

/* At most this many ranks (sd_mpi_attach refuses more). */
#define SD_MPI_MAX_RANKS 64

/* A cut of one axis: (c, id) pairs at or above it, c the coordinate along
 * that axis, are on the next run's side. */
typedef struct sd_mpi_cut {
    double x; /* m, along the cut's axis */
    uint64_t id;
} sd_mpi_cut;

/* The split: n[0] x n[1] x n[2] boxes, nested cuts. Level 0 holds the
 * n[0] - 1 cuts of x; level 1, for each run i0 along x, n[1] - 1 cuts of y
 * (from i0 (n[1] - 1)); level 2, for each (i0, i1), n[2] - 1 cuts of z
 * (from (i0 n[1] + i1)(n[2] - 1)). Rank r = (i0 n[1] + i1) n[2] + i2. */
typedef struct sd_mpi_grid {
    int n[3];
    sd_mpi_cut cut[3][SD_MPI_MAX_RANKS];
    int by_extent; /* 1: cut evenly over an extent (sd_mpi_grid_even), not by count */
} sd_mpi_grid;

/* The grid a scene asks for (simulation.mpi_split): {0, 0, 0} auto, -1 on
 * one axis and 1 on the others: slabs along that axis, else [px, py, pz];
 * line: where the key is (for messages; 0 when not given). */
typedef struct sd_mpi_split_req {
    int n[3];
    int line;
} sd_mpi_split_req;

/* The cuts of g (g->n set) that share n particles (positions x: 3 per
 * particle; ids id) out by count: the particles sorted by (x, id) cut into
 * n[0] runs of equal count (run i gets floor(i n / n[0]) .. floor((i + 1)
 * n / n[0]) - 1 of that order, a run past the last particle an empty one
 * cut at +inf), each run sorted by (y, id) cut into n[1], each of those by
 * (z, id) into n[2]. Fails only without memory. */
sd_status sd_mpi_grid_split(sd_mpi_grid *g, size_t n, const double *x, const uint64_t *id);
/* The cuts of g (g->n set) at even spacing over the box [lo, hi] (m): for
 * a world with fewer particles than ranks at the start (sd_mpi_attach). */
void sd_mpi_grid_even(sd_mpi_grid *g, const double lo[3], const double hi[3]);
/* The rank that owns (x, id) under g. */
int sd_mpi_grid_rank(const sd_mpi_grid *g, const double x[3], uint64_t id);
/* Rank r's box [lo, hi] (m; -inf / +inf at the outer faces, both +inf for
 * a box past the last particle). */
void sd_mpi_grid_box(const sd_mpi_grid *g, int r, double lo[3], double hi[3]);
/* The grid shape out for ranks ranks as req asks: auto ({0, 0, 0}) takes
 * the factorisation px py pz = ranks (pz = 1 when planar) of the least
 * cut area (px - 1) Ly Lz + (py - 1) Lx Lz + (pz - 1) Lx Ly over a box of
 * extent (Lx, Ly, Lz), m; ties go to more cuts along x, then y. -1 when
 * req's product is not ranks, or asks for z cuts in the planar mode. */
int sd_mpi_grid_shape(const int req[3], int ranks, const double extent[3], int planar, int out[3]);

/* Rank r's box as text, "[x0, x1] x [y0, y1] x [z0, z1]" (m, %.6g). */
void sd_mpi_grid_box_text(const sd_mpi_grid *g, int r, char *buf, size_t size);
/* How g's cuts were made, in words. */
const char *sd_mpi_grid_how(const sd_mpi_grid *g);

/* The split of world w (every particle, as every rank holds it before the
 * attach) over ranks ranks as req asks (NULL: auto) (mpi/plan.c): the
 * grid's shape from the extent of the particles (centres +- bounding
 * radius), then the cuts by count; with fewer particles than ranks and an
 * insertion, the cuts evenly over the box of the particles and the
 * insertion regions instead. SD_ERR_INPUT naming simulation.mpi_split
 * when req does not fit the rank count. */
sd_status sd_mpi_plan(const sd_world *w, const sd_mpi_split_req *req, int ranks, sd_mpi_grid *g, sd_error *err);

/* ---- the decomposed run (mpi/comm.c) ------------------------------------------ */

typedef struct sd_mpi sd_mpi;

/* Splits world w (every rank's copy holding the same particles, not yet
 * prepared: sd_mpi_attach_built takes a world sd_scene_build made) over
 * the ranks of MPI_COMM_WORLD as split asks (sd_mpi_plan; NULL: auto):
 * keeps this rank's particles and installs the hooks. MPI must be
 * initialised. Refuses what is not decomposed yet (the grid solver), and
 * a split that does not fit the rank count, with SD_ERR_INPUT. */
sd_status sd_mpi_attach(sd_world *w, const sd_mpi_split_req *split, sd_mpi **out, sd_error *err);
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

/* After a vote on a failure (bad: this rank's, any: some rank's): 1 when
 * another rank failed and this one did not, marking this rank so that its
 * sd_mpi_fail keeps quiet and waits for the failing rank's message and
 * abort (at most 20 s). */
int sd_mpi_failed_elsewhere(int bad, int any);
/* The split in use. */
const sd_mpi_grid *sd_mpi_grid_of(const sd_mpi *m);

/* Rebalancing (mpi/rebalance.c): at the first rebuild at or after every
 * `every` steps from from_step, before the migration, the cuts are made
 * again from every rank's particles (sd_mpi_grid_split: equal counts, the
 * same grid shape), and the migration moves the particles to their new
 * ranks. The state does not change (its bits do not depend on the split),
 * nor do the rebuilds' steps: no rebuild is added. */
void sd_mpi_set_rebalance(sd_mpi *m, long every, long from_step);
long sd_mpi_rebalances(const sd_mpi *m);
/* Collective: new cuts of g (its shape kept) from the owned particles of
 * every rank of w. */
sd_status sd_mpi_recut(const sd_world *w, sd_mpi_grid *g, sd_error *err);

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
 * (the split, particles per rank now, migrations, each rank's device). */
void sd_mpi_drive_end(sd_mpi_drive *d, char *note, size_t size);
/* sd_mpi_attach for a world that sd_scene_build made (prepared, at step
 * 0): its pair lists, ghosts and rebuild count are dropped first, so the
 * decomposed world prepares as one never prepared would. */
sd_status sd_mpi_attach_built(sd_world *w, const sd_mpi_split_req *split, sd_mpi **out, sd_error *err);
/* sd_mpi_attach for a world restored from a checkpoint (prepared, its
 * forces those saved): the pair lists keep only the springs, by key, of
 * every pair, and the world is marked for a rebuild at its next step
 * (the rebuild carries them), which the run that wrote the checkpoint
 * made too (sd_mpi_drive_write). */
sd_status sd_mpi_attach_restored(sd_world *w, const sd_mpi_split_req *split, sd_mpi **out, sd_error *err);
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
/* Every rank: flag (a signal handler's) is ORed over the ranks after each
 * run of steps (sd_mpi_drive_step), so a signal sent to any rank sets it
 * on rank 0 too, where the run stops at its next output chunk; NULL none. */
void sd_mpi_drive_watch(volatile sig_atomic_t *flag);
/* Collective: this rank's index among the ranks of its node (those that
 * share memory, MPI_COMM_TYPE_SHARED, in world-rank order): the device
 * slot of its world (sd_world_def.device, sd_scene_set_device), so that
 * rank r of a node takes CUDA device r mod the node's devices. */
int sd_mpi_local_rank(void);

#endif
