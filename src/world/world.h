/* world.h — the world's state: particle arrays (structure of arrays),
 * materials, walls, the pair lists and the clock.
 *
 * Invariant: particle fields are declared once in SD_PARTICLE_FIELDS; the
 * arrays, their growth, their permutation at re-sorting and (later) output,
 * checkpoints and MPI packing are generated from that list (STYLE.md
 * convention 5). Storage order may change at every pair-list rebuild; the
 * stable id never does.
 */
#ifndef SD_WORLD_WORLD_H
#define SD_WORLD_WORLD_H

#include <signal.h>

#include <shapedem/shapedem.h>

#include "backend/view.h"
#include "broad/bins.h"
#include "broad/pairs.h"
#include "contact/params.h"
#include "core/quat.h"
#include "dynamics/meshwall.h"
#include "dynamics/walls.h"
#include "shape/shape.h"
#include "shape/shape2d.h"
#include "world/rebuild.h"

/* X(type, name, unit, meaning, default, query, member) — hot per-step
 * fields first.
 *  default: the value of a new particle (sd_particles_init); the add
 *           functions set only what differs.
 *  query, member: how sd_world_get_particle fills sd_particle_state
 *           (SD_QUERY_<query>(out->member, value), world.c): V3, QUAT,
 *           REAL, INVERSE (1/x, infinite for 0), INT, U64, or NONE (not
 *           public). The frames (io/vtk.c) write what the query returns. */
#define SD_PARTICLE_FIELDS(X)                                                                                 \
    X(sd_vec3, x, "m", "position of the centre of mass", sd_v3_zero(), V3, position)                          \
    X(sd_vec3, v, "m/s", "velocity", sd_v3_zero(), V3, velocity)                                              \
    X(sd_vec3, w, "rad/s", "angular velocity, world frame", sd_v3_zero(), V3, angular_velocity)               \
    X(sd_quat, q, "-", "orientation, body frame to world frame", sd_quat_identity(), QUAT, quat)              \
    X(sd_vec3, f, "N", "total contact force of the last step", sd_v3_zero(), V3, force)                       \
    X(sd_vec3, t, "N m", "total contact torque of the last step", sd_v3_zero(), V3, torque)                   \
    X(sd_real, radius, "m", "radius (bounding radius for non-spheres)", SD_R(0.0), REAL, radius)              \
    X(sd_real, inv_mass, "1/kg", "inverse mass, 0 for a fixed body", SD_R(0.0), INVERSE, mass)                \
    X(sd_vec3, inv_inertia, "1/(kg m^2)", "inverse principal moments, body frame", sd_v3_zero(), NONE, none) \
    X(sd_vec3, x_ref, "m", "position at the last pair-list rebuild", sd_v3_zero(), NONE, none)                \
    X(sd_quat, q_ref, "-", "orientation at the last pair-list rebuild", sd_quat_identity(), NONE, none)       \
    X(int32_t, material, "-", "material index", 0, INT, material)                                             \
    X(int32_t, shape, "-", "shape template index, -1 for a plain sphere", -1, INT, shape)                     \
    X(uint64_t, id, "-", "stable id", 0, U64, id)

typedef struct sd_particles {
    size_t n, cap;
    /* counts every change of where the arrays are or what slot holds whom:
     * growth (realloc), an added slot, the rebuild's permutation, a removal,
     * a restore, an MPI migration; never reset (sd_particles_free keeps it),
     * so a zero-copy view (sd_world_state_view) knows it went stale */
    uint64_t generation;
#define SD_X_FIELD(type, name, ...) type *name;
    SD_PARTICLE_FIELDS(SD_X_FIELD)
#undef SD_X_FIELD
} sd_particles;

typedef struct sd_material {
    char name[64];
    sd_material_def def;
} sd_material;

typedef struct sd_interaction {
    int a, b;
    sd_interaction_def def;
} sd_interaction;

/* A wall: its geometry (dynamics/walls.h, a POD the views carry; the
 * anonymous struct names the same members, so code that reads wl->kind,
 * wl->point, ... reads the geometry) plus its name, material and motion. */
typedef struct sd_wall {
    char name[64];
    union {
        sd_wall_geom geom;
        struct {
            int kind;               /* enum sd_wall_kind */
            sd_vec3 point, normal;  /* plane */
            sd_vec3 lo, hi;         /* box */
            unsigned open_faces;
            sd_quat q;              /* mesh: pose (world = R(q) x_mesh + trans) */
            sd_vec3 trans, centre;  /* m: translation; centre of the velocity field */
            int mesh;               /* mesh: index into the world's meshes (world/mesh.h) */
        };
    };
    sd_wall_geom geom0;     /* the geometry as added: the scene hash's (geom moves; world/scene_hash.c) */
    int material;
    sd_vec3 force, torque;  /* on the wall, last step */
    /* motion (dynamics/servo.h, world/servo.c): prescribed or servo-controlled */
    sd_wall_motion_def motion;
    int moving;             /* a motion was set */
    sd_vec3 velocity;       /* m/s, in use this step */
    sd_vec3 point_ref;      /* m, point at the last pair-list rebuild */
    sd_real stiffness;      /* N/m, sum of the normal stiffness of its contacts, last step */
    sd_real servo_i;        /* m/s, integral term of the servo (dynamics/servo.h) */
    sd_vec3 omega;          /* rad/s, angular velocity (mesh walls; 0 otherwise) */
    sd_vec3 torque_point;   /* m, the point sd_world_get_wall's torque is about (a mesh's: mesh frame) */
    int has_torque_point;   /* set by sd_world_set_wall_torque_point (meshes always have one) */
    /* drum (sd_drum_def): full angular speed (rad/s about normal) and its spin-up; from the scene */
    double drum_w0, drum_start, drum_ramp;
} sd_wall;

/* Below this many particles the CPU loops run serially: a sphere pair
 * costs tens of ns, less than handing out the work. A world with shape
 * templates (convex, polyhedra, 2D shapes, composites) pays a narrow phase
 * of microseconds per pair, so it shares the work from far fewer: the
 * 1,000-particle packings of docs/examples/process.md ran serially on
 * `threads: 2` below the sphere limit. */
#define SD_PARALLEL_MIN_PARTICLES 1024
#define SD_PARALLEL_MIN_SHAPED 128
/* The threading policy of the CPU loops (w->parallel, set at rebuilds):
 * more than one thread, and at least the limit above for the world's kind. */
int sd_world_wants_parallel(const sd_world *w);

struct sd_world {
    sd_world_def def;
    int dim2;              /* the planar mode (def.dimension == 2) */
    sd_real local_damping; /* -, seed 002 local damping coefficient alpha */
    int walls_moving;      /* some wall has a motion set */
    sd_vec3 biaxial_ref;   /* m, reference (width, height) of the biaxial box; z = 1 once set */
    int threads;
    int parallel;          /* run the CPU loops on threads (decided at rebuilds) */
    sd_real dt;
    sd_vec3 gravity;
    sd_real skin;          /* m, in use */
    long step;
    double time;
    uint64_t next_id;

    sd_particles p;

    size_t material_count;
    sd_material *materials;
    size_t interaction_count;
    sd_interaction *interactions;
    /* mixed parameters, index (a * nm + b); walls use their own material */
    sd_pair_params *mix;
    int has_volume_law;    /* some pair of materials uses a volume law (material.c) */

    size_t wall_count;
    sd_wall *walls;
    /* triangle-mesh walls (world/mesh.h): store and views, one per mesh wall */
    size_t mesh_count;
    struct sd_mesh_store *meshes;
    sd_mesh_view *mesh_views;

    /* shape templates and the polyhedron vertex pool they index */
    size_t shape_count;
    sd_shape *shapes;
    char (*shape_names)[64];
    sd_real *shape_req;       /* m, radius of the sphere of equal volume */
    sd_vec3 *shape_com;       /* m, centre of mass in the frame the shape was given in */
    size_t vert_count;
    sd_vec3 *verts;
    size_t plane_count;       /* polyhedron face planes (sd_shape fstart/fcount) */
    sd_plane *planes;
    size_t dtri_count;        /* polyhedron dual triangles (sd_shape tstart/tcount) */
    sd_dtri *dtris;
    size_t element_count;     /* composite elements (sd_shape estart/ecount, seed 004) */
    sd_element *elements;
    /* the copies sd_world_add_scaled_shape made (world/scaled.c), in the
     * order made: which template each copies and by what factor, so that a
     * checkpoint's reader can make the same copy again (io/scene_from.c);
     * index and base are 2D template indices in planar mode */
    size_t scaled_count;
    struct sd_scaled_copy {
        int index, base;
        double scale;
    } *scaled;
    int has_shapes;           /* some particle is not a plain sphere */
    /* narrow-phase totals per pair of shape kinds (sorted), since creation */
    long long narrow[SD_SHAPE_KIND_COUNT][SD_SHAPE_KIND_COUNT][3];

    /* planar mode: 2D shape templates and their pool of reals (shape/shape2d.h) */
    size_t shape2d_count;
    sd_shape2d *shapes2d;
    char (*shape2d_names)[64];
    size_t pool2d_count;
    sd_real *pool2d;
    /* 2D narrow-phase totals per pair of 2D kinds (sorted): evaluations,
     * contacts among them, support calls, support calls of the contacts */
    long long narrow2d[SD_SHAPE2D_KIND_COUNT][SD_SHAPE2D_KIND_COUNT][4];

    sd_pair_list pairs;       /* particle-particle candidates */
    sd_wall_pair_list wpairs; /* particle-wall candidates */
    sd_bins bins;             /* the broad phase's cells (broad/bins.h) */
    /* ghosts (world/rebuild.c): particles p.n .. p.n + n_ghost - 1 of the
     * particle arrays are copies of owned particle ghost_owner[g], shifted
     * by ghost_shift[g] (periodic images); remade at each rebuild */
    size_t n_ghost, ghost_cap;
    uint32_t *ghost_owner;
    sd_vec3 *ghost_shift;
    /* a decomposed run (src/mpi/): this rank's side of the exchanges, NULL
     * in a serial run (then nothing below changes a bit of it) */
    const struct sd_world_comm *comm;
    void *comm_ctx;
    struct sd_grid_state *grid_state; /* solver grid (src/grid), NULL otherwise */
    const struct sd_solver_ops *solver; /* the engine, chosen at creation (world/solver.h) */
    const struct sd_backend *backend; /* the cells solver's stages, chosen at creation (world/backend.c) */
    char backend_note[128];   /* why that backend, or its device's name (sd_world_backend_note) */
    sd_stage stage;           /* the backend's views of all the above (world/view.c) */
    sd_profile profile;       /* s per stage of the step (world/profile.c) */
    long rebuilds;
    struct sd_process *process; /* insertions and outlets (world/process.h), NULL when none */
    struct sd_region_meshes *region_meshes; /* insertions' mesh regions (world/process.h), NULL when none */
    int prepared;
    volatile sig_atomic_t interrupt; /* sd_world_request_interrupt: the step stops at its next look */
    int dirty;                /* particles added since the last rebuild */
    double dt_checked;        /* s, the time step sd_world_check_dt last passed (guards.c), 0 none */
    size_t dt_checked_n;      /* particles at that check */
    int guards_off;           /* tests only: sd_world_guards skips the speed and overlap guards (a set-up
                               * overlapped on purpose, e.g. tests/unit/broad.c); the NaN check stays */
};

/* The hooks a domain decomposition (src/mpi/) gives the cells solver; each
 * is collective: every rank calls it at the same point of the same step.
 * With a comm set, the pair lists are put in the canonical order of
 * sd_pairs_canonical (broad/bins.h), so a particle sums its pairs in an
 * order fixed by stable ids, the same on any rank count. */
typedef struct sd_world_comm {
    /* the logical or of flag over the ranks (the rebuild decision) */
    int (*any)(void *ctx, int flag);
    /* the least of v over the ranks (the skin from the smallest radius) */
    double (*min)(void *ctx, double v);
    /* at a rebuild, before the sort: owned particles that left this rank's
     * sub-domain go to their new rank, with their contact history */
    sd_status (*migrate)(void *ctx, sd_world *w, sd_error *err);
    /* at a rebuild, after the sort: the ghosts of other ranks' particles
     * (ghost_owner SD_GHOST_REMOTE), appended after the owned ones */
    sd_status (*ghosts)(void *ctx, sd_world *w, sd_error *err);
    /* each step, after the drift: the ghosts take their owners' state */
    void (*exchange)(void *ctx, sd_world *w);
    /* insertions and outlets (world/process.c), between steps: */
    /* the sum of v over the ranks (the particles at the first step) */
    unsigned long long (*sum)(void *ctx, unsigned long long v);
    /* every rank's owned particles as (x, y, z, bounding radius), in *xr
     * (4 *n doubles, the caller frees it): what an insertion must not
     * overlap, the same on every rank */
    sd_status (*all_spheres)(void *ctx, const sd_world *w, double **xr, size_t *n, sd_error *err);
    /* particles first .. n - 1, which every rank has just inserted alike
     * (the same draws, ids and checks), stay only on the rank that owns
     * them (the split's rule) */
    sd_status (*keep_owned)(void *ctx, sd_world *w, size_t first, sd_error *err);
    /* the count and mass (kg) of what the ranks' outlets take, each rank's
     * n particles given by id and mass: summed in stable-id order, the same
     * on every rank */
    sd_status (*removed_sum)(void *ctx, size_t n, const uint64_t *id, const double *mass, size_t *count,
                             double *total, sd_error *err);
    /* servo walls (world/servo.c), each step: per wall, the sums of the
     * ranks' wall-pair values (4 doubles per pair: force on the wall,
     * contact stiffness) in the order of the wall-pair keys, into out (4
     * per wall), the same on every rank */
    sd_status (*wall_sums)(void *ctx, size_t n, const sd_wall_pair_key *key, const double *v, size_t wall_count,
                           double *out, sd_error *err);
} sd_world_comm;

/* Grows the particle arrays to hold at least cap particles. */
sd_status sd_particles_reserve(sd_particles *p, size_t cap);
void sd_particles_free(sd_particles *p);
/* Gives slot e every field's default (SD_PARTICLE_FIELDS) and the stable
 * id; the caller then sets what differs (and x_ref, q_ref from x, q). */
void sd_particles_init(sd_particles *p, size_t e, uint64_t id);
/* Reorders every field: new[k] = old[perm[k]]; scratch holds n * 32 bytes;
 * threaded (threads, when parallel) a field at a time. */
void sd_particles_permute(sd_particles *p, const uint32_t *perm, void *scratch, int threads, int parallel);

/* servo.c: moves the walls that have a motion over one step starting at
 * time t (fails when a servo wall has no opposite walls to measure its
 * length); 1 when a wall moved more than half the skin since the last
 * rebuild; marks the wall positions at a rebuild. */
sd_status sd_world_walls_drift(sd_world *w, double t, sd_error *err);
int sd_world_walls_moved(const sd_world *w);
/* Sets each drum's angular velocity at time t (its spin-up ramp, world/process.c). */
void sd_world_drums_spin(sd_world *w, double t);
void sd_world_walls_mark(sd_world *w);

/* world.c: appends a wall (checks its material); its index or -1. */
int sd_world_push_wall(sd_world *w, const sd_wall *proto, sd_error *err);
/* mesh.c: the torque of wall k about its torque point (N m). */
sd_vec3 sd_world_wall_torque_about(const sd_world *w, size_t k);

/* guards.c: SD_ERR_INPUT when dt is above the stability limit (1/5 of the
 * shortest estimated contact); prepares the world first when needed. */
sd_status sd_world_check_dt(sd_world *w, sd_error *err);
/* guards.c: SD_ERR_PHYSICS naming the particle (stable id), the step and
 * the likely cause for a NaN or infinite state, a particle crossing more
 * than a broad-phase cell per step, or an overlap beyond def.max_overlap
 * (SD_GUARD_OVERLAP by default; 0 = off) of the smaller radius (cells
 * solver; read-only, any thread count). */
#define SD_GUARD_OVERLAP SD_R(0.5)
sd_status sd_world_guard_nonfinite(sd_world *w, sd_error *err);
sd_status sd_world_guards(sd_world *w, sd_error *err);
/* backend.c: sets w->backend and w->backend_note from def.backend and the
 * device probe (SD_ERR_INPUT when cuda was asked for and cannot run). */
sd_status sd_world_choose_backend(sd_world *w, sd_error *err);

/* A new shape's name is valid and free (bodies.c). */
sd_status sd_world_check_shape_name(const sd_world *w, const char *name, sd_error *err);
/* 1 when template shape is a copy sd_world_add_scaled_shape made (world/
 * scaled.c): *base the template it copies, *scale the factor as given;
 * 0 for any other template (a composite copy's element copies too: they
 * are made again with the composite's). */
int sd_world_scaled_of(const sd_world *w, size_t shape, int *base, double *scale);

/* bodies2d.c: the planar mode's halves of the shape and body functions of
 * bodies.c (which call them when w->dim2). */
sd_status sd_world_get_shape2d(const sd_world *w, size_t k, sd_shape_info *out);
sd_status sd_world_add_bodies2d(sd_world *w, size_t n, const sd_body_def *defs, sd_error *err);
size_t sd_world_narrow_stats2d(const sd_world *w, sd_narrow_stats *out, size_t max);

/* material.c: fills w->mix; fails for a linear law without stiffness etc. */
sd_status sd_world_mix_materials(sd_world *w, sd_error *err);
/* Fails when a pair of materials that can meet lacks what its law needs. */
sd_status sd_world_check_params(const sd_world *w, sd_error *err);
/* Volume laws: the damping ratios zeta(e, p) of contact/law_volume.h, and
 * the rebound of their 1D model (for tests). */
void sd_volume_zeta_table(double e, sd_real zeta[SD_VOLUME_ZETA_N]);
double sd_volume_rebound_model(double p, double zeta);

/* sd_world_request_interrupt's request, for the loops that look at it:
 * due when set on a world that is not decomposed (the ranks of an MPI run
 * must all stop at the same point, which a signal to one cannot give);
 * sd_world_interrupted clears it and returns SD_ERR_INTERRUPTED. */
int sd_world_interrupt_due(const sd_world *w);
sd_status sd_world_interrupted(sd_world *w, sd_error *err);

#endif
