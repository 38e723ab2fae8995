/* state.h — the CUDA backend's state: device copies of every array of the
 * views (backend/view.h), the small device buffers of the reductions, the
 * polyhedron overlap workspaces, the stream, and the first error; and the
 * stages each source implements (device.cu: memory and copies; particles.cu,
 * pairs*.cu, walls*.cu: the kernels), gathered into the stage table by
 * table.c.
 *
 * Invariants: c->v, c->pairs, c->wpairs are the host stage's views with
 * every pointer replaced by its device copy (sd_cuda_bind, after each
 * upload); the device arrays are at least as long as the host ones at the
 * last upload; a kernel reads and writes only device memory. Once an
 * error is recorded (sd_cuda_fail) every later stage does nothing until
 * status reports it, so a failed copy never feeds a kernel.
 */
#ifndef SD_BACKEND_CUDA_STATE_H
#define SD_BACKEND_CUDA_STATE_H

#include <shapedem/shapedem.h>

#include "backend/cuda/cuda.h"
#include "backend/view.h"
#include "geom/overlap.h"

#ifdef __cplusplus
#include "backend/cuda/runtime.h"
#endif

/* The arrays of the views the device holds: X(view, member, type, count,
 * back). view: the member of sd_stage (v, pairs, wpairs); count: the
 * number of elements on the host stage s; back: 1 when the device writes
 * it and read_back copies it to the host. The one list behind the device
 * buffers, their uploads, read backs and pointers. */
#define SD_CUDA_ARRAYS(X)                                                                         \
    X(v, x, sd_vec3, s->v.n_total, 1)                                                             \
    X(v, v, sd_vec3, s->v.n_total, 1)                                                             \
    X(v, w, sd_vec3, s->v.n_total, 1)                                                             \
    X(v, q, sd_quat, s->v.n_total, 1)                                                             \
    X(v, f, sd_vec3, s->v.n_total, 1)                                                             \
    X(v, t, sd_vec3, s->v.n_total, 1)                                                             \
    X(v, radius, sd_real, s->v.n_total, 0)                                                        \
    X(v, inv_mass, sd_real, s->v.n_total, 0)                                                      \
    X(v, inv_inertia, sd_vec3, s->v.n_total, 0)                                                   \
    X(v, x_ref, sd_vec3, s->v.n_total, 0)                                                         \
    X(v, q_ref, sd_quat, s->v.n_total, 0)                                                         \
    X(v, material, int32_t, s->v.n_total, 0)                                                      \
    X(v, shape, int32_t, s->v.n_total, 0)                                                         \
    X(v, id, uint64_t, s->v.n_total, 0)                                                           \
    X(v, ghost_owner, uint32_t, s->v.n_total - s->v.n_owned, 0)                                   \
    X(v, ghost_shift, sd_vec3, s->v.n_total - s->v.n_owned, 0)                                    \
    X(v, shapes, sd_shape, s->v.shape_count, 0)                                                   \
    X(v, verts, sd_vec3, s->v.vert_count, 0)                                                      \
    X(v, planes, sd_plane, s->v.plane_count, 0)                                                   \
    X(v, dtris, sd_dtri, s->v.dtri_count, 0)                                                      \
    X(v, elements, sd_element, s->v.element_count, 0)                                             \
    X(v, shape_req, sd_real, s->v.shape_count, 0)                                                 \
    X(v, shapes2d, sd_shape2d, s->v.shape2d_count, 0)                                             \
    X(v, pool2d, sd_real, s->v.pool2d_count, 0)                                                   \
    X(v, mix, sd_pair_params, s->v.material_count * s->v.material_count, 0)                       \
    X(pairs, i, uint32_t, s->pairs.n, 0)                                                              \
    X(pairs, j, uint32_t, s->pairs.n, 0)                                                              \
    X(pairs, flip, uint8_t, s->pairs.n, 0)                                                            \
    X(pairs, key, sd_pair_key, s->pairs.n, 0)                                                         \
    X(pairs, ds, sd_vec3, s->pairs.n, 1)                                                              \
    X(pairs, f, sd_vec3, s->pairs.n, 1)                                                               \
    X(pairs, t, sd_vec3, 2 * s->pairs.n, 1)                                                           \
    X(pairs, delta, sd_real, s->pairs.n, 1)                                                           \
    X(pairs, energy, sd_real, s->pairs.n, 1)                                                          \
    X(pairs, warm, sd_vec3, s->pairs.n, 1)                                                            \
    X(pairs, iters, int32_t, s->pairs.n, 1)                                                           \
    X(pairs, supports, int32_t, s->pairs.n, 1)                                                        \
    X(pairs, x0, sd_vec3, s->pairs.n, 1)                                                              \
    X(pairs, x0_ok, uint8_t, s->pairs.n, 1)                                                           \
    X(pairs, gstart, uint32_t, s->pairs.n_gstart, 0)                                                  \
    X(pairs, gidx, uint32_t, s->pairs.n_gidx, 0)                                                      \
    X(wpairs, i, uint32_t, s->wpairs.n, 0)                                                            \
    X(wpairs, wall, uint16_t, s->wpairs.n, 0)                                                         \
    X(wpairs, sub, uint32_t, s->wpairs.n, 0)                                                          \
    X(wpairs, tstart, uint32_t, s->wpairs.n, 0)                                                       \
    X(wpairs, tcount, uint32_t, s->wpairs.n, 0)                                                       \
    X(wpairs, tri, uint32_t, s->wpairs.n_tri, 0)                                                      \
    X(wpairs, elem, uint32_t, s->wpairs.n, 0)                                                         \
    X(wpairs, ds, sd_vec3, s->wpairs.n, 1)                                                            \
    X(wpairs, f, sd_vec3, s->wpairs.n, 1)                                                             \
    X(wpairs, t, sd_vec3, s->wpairs.n, 1)                                                             \
    X(wpairs, c, sd_vec3, s->wpairs.n, 1)                                                             \
    X(wpairs, delta, sd_real, s->wpairs.n, 1)                                                         \
    X(wpairs, energy, sd_real, s->wpairs.n, 1)                                                        \
    X(wpairs, gstart, uint32_t, s->wpairs.n_gstart, 0)                                                \
    X(wpairs, gidx, uint32_t, s->wpairs.n_gidx, 0)

enum {
#define SD_X_ID(view, member, type, count, back) SD_CUDA_##view##_##member,
    SD_CUDA_ARRAYS(SD_X_ID)
#undef SD_X_ID
    SD_CUDA_ARRAY_COUNT
};

/* One device array and its capacity (bytes). */
typedef struct sd_cuda_buf {
    void *p;
    size_t cap;
} sd_cuda_buf;

/* A mesh wall's facet arrays on the device (meshes never change after
 * they are built: copied again only when the host's arrays move). */
typedef struct sd_cuda_mesh {
    const void *host_verts;        /* the host array they were copied from */
    size_t host_tris;
    sd_cuda_buf verts, tris, group, flags, normal, offset, key, tri;
} sd_cuda_mesh;

/* The narrow-phase tallies, as the host's counters (sd_stage.narrow,
 * narrow2d): integers, exact in any order. */
#define SD_CUDA_TALLY3 (SD_SHAPE_KIND_COUNT * SD_SHAPE_KIND_COUNT * 3)
#define SD_CUDA_TALLY2 (SD_SHAPE2D_KIND_COUNT * SD_SHAPE2D_KIND_COUNT * 4)

typedef struct sd_cuda_state {
    sd_step_view v;                /* device pointers (sd_cuda_bind) */
    sd_pair_out pairs;
    sd_wall_pair_out wpairs;
    sd_cuda_buf buf[SD_CUDA_ARRAY_COUNT];
    size_t held[SD_CUDA_ARRAY_COUNT]; /* elements on the device since the last upload */
    sd_cuda_buf walls, wall_force, wall_torque;
    sd_cuda_mesh *mesh;            /* host array of mesh_cap */
    size_t mesh_cap;
    sd_cuda_buf mesh_views;        /* sd_mesh_view[mesh_count], device pointers inside */
    sd_cuda_buf flag;              /* int: needs_rebuild, check_finite */
    sd_cuda_buf minbits;           /* unsigned long long: min_radius (the bits of a positive double) */
    sd_cuda_buf tally;             /* unsigned long long[SD_CUDA_TALLY3 + SD_CUDA_TALLY2] */
    sd_cuda_buf ws;                /* sd_overlap_workspace[ws_count] (volume law, composites) */
    size_t ws_count;
#ifdef __cplusplus
    cudaStream_t stream;
#else
    void *stream;
#endif
    int totals_pending;            /* the wall totals wait for the next read back (no wall moves) */
    int sync_stages;               /* SD_CUDA_SYNC_STAGES=1: wait for each stage's kernels (profiles) */
    sd_status status;              /* SD_OK, or the first failure */
    char message[512];             /* its message, naming the stage */
} sd_cuda_state;

#ifdef __cplusplus
extern "C" {
#endif

/* device.cu */
void sd_cuda_upload(sd_stage *s);
void sd_cuda_upload_walls(sd_stage *s);
void sd_cuda_read_back(sd_stage *s);
void sd_cuda_read_back_wall_pairs(sd_stage *s);
void sd_cuda_read_back_state(sd_stage *s, size_t first, size_t end);
void sd_cuda_upload_state(sd_stage *s, size_t first, size_t end);
void sd_cuda_release(sd_stage *s);
sd_status sd_cuda_status(sd_stage *s, sd_error *err);
/* particles.cu */
void sd_cuda_kick_drift(sd_stage *s);
void sd_cuda_gather(sd_stage *s);
void sd_cuda_gather_kick(sd_stage *s);
void sd_cuda_gather_kick_drift(sd_stage *s);
int sd_cuda_needs_rebuild(sd_stage *s);
int sd_cuda_check_finite(sd_stage *s);
sd_real sd_cuda_min_radius(sd_stage *s);
void sd_cuda_exchange_ghosts(sd_stage *s);
/* pairs.cu */
void sd_cuda_forces(sd_stage *s, sd_pair_kind kind);
/* walls.cu */
void sd_cuda_wall_forces(sd_stage *s);
void sd_cuda_wall_totals(sd_stage *s);

#ifdef __cplusplus
}

/* device.cu, for the kernels' sources: records the first failure (the
 * stage, what failed, the runtime's words) and returns 1 on failure;
 * sd_cuda_ok says whether the stages may still run. */
int sd_cuda_check(sd_cuda_state *c, cudaError_t e, const char *stage, const char *what);
static inline int sd_cuda_ok(const sd_stage *s) { return s->device && s->device->status == SD_OK; }
/* after a stage's launches: their launch error, and with sync_stages the
 * wait for them, so that sd_profile times the stage's kernels rather than
 * their launch (kernels are asynchronous: without it a stage's time shows
 * in the next stage that waits, a copy back); 1 on failure */
int sd_cuda_launched(sd_cuda_state *c, const char *stage);
/* blocks of SD_CUDA_BLOCK threads for n items */
static inline unsigned sd_cuda_blocks(size_t n) { return (unsigned)((n + SD_CUDA_BLOCK - 1) / SD_CUDA_BLOCK); }
/* grows a device array to at least bytes (contents lost); 1 on failure */
int sd_cuda_reserve(sd_cuda_state *c, sd_cuda_buf *b, size_t bytes, const char *stage, const char *what);
/* the batched segments of sd_cuda_forces (ws_count > 0): pairs_volume.cu,
 * pairs_elements.cu; the mesh wall-pair kinds of sd_cuda_wall_forces:
 * walls_mesh.cu (0 when kind is not a mesh kind) */
void sd_cuda_forces_volume(sd_cuda_state *c, size_t e0, size_t e1);
void sd_cuda_forces_elements(sd_cuda_state *c, size_t e0, size_t e1);
int sd_cuda_mesh_wall_kind(sd_cuda_state *c, int kind, size_t e0, size_t e1);
/* walls.cu: the wall totals now (read_back's, when they wait) */
void sd_cuda_wall_totals_now(sd_stage *s);
#endif

#endif
