/* view.h — the plain views every backend stage works on: pointers and
 * counts of the particle state, the shape tables, the mixed parameters,
 * the walls and the pair lists, with no sd_world in sight (architecture
 * review §9.2, seam 1). The world fills them (world/view.c) at prepare and
 * after every rebuild, since the arrays they point into move when they
 * grow; a CUDA backend fills the same structs with device pointers.
 *
 * Invariants: a view never owns memory; particles 0 .. n_owned - 1 are the
 * owned ones and n_owned .. n_total - 1 the ghosts that follow them (none
 * yet: the broad phase will add them); the pair outputs keep their kinds in
 * segments, kind k owning pairs kind_start[k] .. kind_start[k + 1] - 1
 * (contact/kinds.h). The walls are copies of the world's wall geometry,
 * refreshed every step (walls move on the host: servo control).
 *
 * Single source: plain structs only, so SD_HD code (backend/items.h) can
 * take them; this header compiles as C17 and as CUDA C++.
 */
#ifndef SD_BACKEND_VIEW_H
#define SD_BACKEND_VIEW_H

#include "broad/pairs.h"
#include "contact/kinds.h"
#include "contact/params.h"
#include "core/quat.h"
#include "dynamics/meshwall.h"
#include "dynamics/walls.h"
#include "shape/shape.h"
#include "shape/shape2d.h"

/* One wall, as the items see it: its geometry and features
 * (dynamics/walls.h), its material and its velocity this step (m/s; a
 * moving wall, world/servo.c). */
typedef struct sd_wall_view {
    sd_wall_geom g;
    int material;
    sd_vec3 velocity;
    sd_vec3 omega;                 /* rad/s: a mesh's velocity at c is velocity + omega x (c - g.centre) */
} sd_wall_view;

/* The state one step reads (and the kick and drift write: x, v, w, q). */
typedef struct sd_step_view {
    size_t n_owned, n_total;       /* particles; ghosts are n_owned .. n_total - 1 */
    sd_vec3 *x, *v, *w;            /* m, m/s, rad/s (world frame) */
    sd_quat *q;                    /* body frame to world frame */
    sd_vec3 *f, *t;                /* N, N m: the gathered totals */
    const sd_real *radius;         /* m, bounding radius for shapes */
    const sd_real *inv_mass;       /* 1/kg, 0 for a fixed body */
    const sd_vec3 *inv_inertia;    /* 1/(kg m^2), principal, body frame */
    const sd_vec3 *x_ref;          /* m, positions at the last rebuild (skin test) */
    const sd_quat *q_ref;          /* orientations at the last rebuild */
    const int32_t *material;
    const int32_t *shape;          /* template index (3D or 2D table by mode), -1 plain sphere */
    const uint64_t *id;            /* stable ids */
    /* ghost g (particle n_owned + g) is a copy of owned particle
     * ghost_owner[g] shifted by ghost_shift[g] (m; a periodic image) */
    const uint32_t *ghost_owner;
    const sd_vec3 *ghost_shift;
    /* shape templates (3D) and their pools */
    const sd_shape *shapes;
    const sd_vec3 *verts;
    const sd_plane *planes;
    const sd_dtri *dtris;
    const sd_element *elements;    /* composite elements (sd_shape estart/ecount) */
    const sd_real *shape_req;      /* m, radius of the sphere of equal volume, per template */
    /* the tables' lengths (a device backend copies them) */
    size_t shape_count, vert_count, plane_count, dtri_count, element_count, shape2d_count, pool2d_count;
    /* planar mode: 2D templates and their pool */
    const sd_shape2d *shapes2d;
    const sd_real *pool2d;
    /* mixed parameters, index a * material_count + b (walls use their own material) */
    const sd_pair_params *mix;
    size_t material_count;
    const sd_wall_view *walls;
    size_t wall_count;
    const sd_mesh_view *meshes;    /* mesh walls' facets (dynamics/meshwall.h), by sd_wall_geom.mesh */
    size_t mesh_count;
    sd_real dt;                    /* s */
    sd_vec3 gravity;               /* m/s^2 */
    sd_real damping;               /* -, seed 002 local damping alpha (0: none) */
    sd_real skin;                  /* m, the Verlet skin in use */
    int dim2;                      /* the planar mode */
    int has_shapes;                /* some particle is not a plain sphere */
    int multi_contact;             /* sd_multi_contact: how element contacts combine (seed 004 §2.6) */
    int walls_moving;              /* some wall moves: its motion reads the wall totals every step (servo);
                                      else only output and queries read them, with the state */
} sd_step_view;

/* The particle-particle pair list as the items read and write it
 * (broad/pairs.h says what each array holds). */
typedef struct sd_pair_out {
    size_t n;
    size_t kind_start[SD_PAIR_KIND_COUNT + 1];
    const uint32_t *i, *j;
    const uint8_t *flip;
    const sd_pair_key *key;        /* history keys: the element sub-indices of ELEMENTS pairs */
    sd_vec3 *ds, *f, *t;           /* t[2e] on i, t[2e + 1] on j */
    sd_real *delta, *energy;
    sd_vec3 *warm;
    int32_t *iters, *supports;
    sd_vec3 *x0;
    uint8_t *x0_ok;
    const uint32_t *gstart, *gidx; /* the gather lists */
    size_t n_gstart, n_gidx;       /* their lengths; 0 while stale (particles added or removed since
                                      the last rebuild, which remakes them before any gather) */
} sd_pair_out;

/* The particle-wall pair list. */
typedef struct sd_wall_pair_out {
    size_t n;
    size_t kind_start[SD_WALL_PAIR_KIND_COUNT + 1];
    const uint32_t *i;
    const uint16_t *wall;          /* wall index */
    const uint32_t *sub;           /* its feature (box face 0..5, 0 for planes, a mesh's plane group) */
    const uint32_t *tstart, *tcount, *tri; /* mesh pairs: triangles tri[tstart[e] ..] of the group near the particle */
    size_t n_tri;                  /* entries of tri */
    const uint32_t *elem;          /* the particle's composite element (ELEMENTS pairs; 0 otherwise) */
    sd_vec3 *ds, *f, *t, *c;       /* spring, force and torque on the particle, contact point */
    sd_real *delta, *energy;
    const uint32_t *gstart, *gidx; /* owned particle k owns pairs gidx[gstart[k] .. gstart[k+1]-1] */
    size_t n_gstart, n_gidx;       /* their lengths, as sd_pair_out's */
} sd_wall_pair_out;

/* How a CPU backend runs its loops (a GPU backend ignores it): threads, and
 * whether to use them at all (decided at rebuilds: small worlds stay serial). */
typedef struct sd_exec {
    int threads;
    int parallel;
} sd_exec;

/* Everything a stage works on, held by the world (world/view.c). The
 * narrow-phase tallies point at the world's counters: evaluations,
 * iterations, support calls per sorted pair of 3D shape kinds, and in the
 * planar mode evaluations, contacts, support calls, support calls of the
 * contacts per sorted pair of 2D kinds. */
typedef struct sd_stage {
    sd_step_view v;
    sd_pair_out pairs;
    sd_wall_pair_out wpairs;
    sd_exec exec;
    long long (*narrow)[SD_SHAPE_KIND_COUNT][3];
    long long (*narrow2d)[SD_SHAPE2D_KIND_COUNT][4];
    sd_wall_view *walls;           /* the copies v.walls points at */
    sd_vec3 *wall_force, *wall_torque; /* N, N m: per wall, summed by the wall totals stage */
    size_t wall_cap;
    /* the CPU's skin test, made in the drift pass that moved the particles
     * (backend/cpu/particles.c): skin_used holds its answer while
     * skin_known; a rebuild (the views refilled) and an upload (the host may
     * have moved particles between calls) make it unknown */
    int skin_used, skin_known;
    struct sd_cuda_state *device;  /* the CUDA backend's device copies (backend/cuda/), NULL on the CPU */
    int device_index;              /* the CUDA device they live on (world/backend.c: sd_world_def.device
                                    * mod the devices present); 0 on the CPU */
} sd_stage;

#endif
