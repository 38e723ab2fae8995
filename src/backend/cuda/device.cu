/* device.cu — the CUDA backend's device memory: the probe of the device,
 * the device copies of the views (backend/cuda/state.h's SD_CUDA_ARRAYS)
 * and of the mesh walls' facets, the copies both ways, and the first
 * error.
 *
 * Invariants: every runtime call is checked (sd_cuda_check) and the first
 * failure sticks with the stage that met it, until `status` hands it to
 * step.c as an sd_status; a stage after a failure does nothing. An upload
 * copies every array of the views, so the device holds exactly the host's
 * state after it (and a read back the reverse for the arrays the device
 * writes): the host may change anything between two sd_world_step calls.
 * Within a step only narrow copies: the wall pairs before the wall motion,
 * and under MPI the particle state rows around the ghost exchange. Every
 * call goes to the device the world chose (sd_stage.device_index, set
 * before the first allocation).
 * Out of device memory names the bytes the upload needed in all. No
 * floating point is computed here.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend/cuda/state.h"
extern "C" { /* C headers without their own guards */
#include "core/alloc.h"
#include "core/error.h"
}

/* The most overlap workspaces of one batch: enough threads to fill a large
 * GPU; a few under emulation, where they are host memory and one runs at a
 * time. */
#ifdef SHAPEDEM_CUDA_EMULATE
#define SD_CUDA_MAX_WORKSPACES 64
#else
#define SD_CUDA_MAX_WORKSPACES 65536
#endif

extern "C" sd_cuda_probe_result sd_cuda_probe(int slot, int *device, char *note, size_t size)
{
    int driver = 0, runtime = 0, n = 0;
    *device = 0;
    if (cudaDriverGetVersion(&driver) != cudaSuccess || driver == 0) {
        snprintf(note, size, "no CUDA device (no NVIDIA driver)");
        return SD_CUDA_NO_DEVICE;
    }
    (void)cudaRuntimeGetVersion(&runtime);
    cudaError_t e = cudaGetDeviceCount(&n);
    if (e == cudaErrorInsufficientDriver || driver < runtime) {
        snprintf(note, size, "driver too old: it supports CUDA %d.%d, the backend was built for %d.%d", driver / 1000,
                 driver % 1000 / 10, runtime / 1000, runtime % 1000 / 10);
        (void)cudaGetLastError();
        return SD_CUDA_OLD_DRIVER;
    }
    if (e == cudaErrorNoDevice || (e == cudaSuccess && n == 0)) {
        snprintf(note, size, "no CUDA device");
        (void)cudaGetLastError();
        return SD_CUDA_NO_DEVICE;
    }
    if (e != cudaSuccess) {
        snprintf(note, size, "the CUDA device query failed: %s", cudaGetErrorString(e));
        (void)cudaGetLastError();
        return SD_CUDA_ERROR;
    }
    int d = (slot > 0 ? slot : 0) % n; /* one rank per GPU: rank r of a node takes device r mod n */
    cudaDeviceProp p;
    if ((e = cudaGetDeviceProperties(&p, d)) != cudaSuccess) {
        snprintf(note, size, "the CUDA device query failed: %s", cudaGetErrorString(e));
        return SD_CUDA_ERROR;
    }
    /* the kernels are built for sm_80 and sm_90 (and PTX of 9.0 for later
     * devices): an older device cannot run them */
    if (p.major < 8) {
        snprintf(note, size, "device %d (%s) has compute capability %d.%d; the backend was built for 8.0 and later",
                 d, p.name, p.major, p.minor);
        return SD_CUDA_ERROR;
    }
    snprintf(note, size, "device %d of %d: %s, compute %d.%d, %.0f GiB", d, n, p.name, p.major, p.minor,
             (double)p.totalGlobalMem / (1024.0 * 1024.0 * 1024.0));
    *device = d;
    return SD_CUDA_USABLE;
}

int sd_cuda_check(sd_cuda_state *c, cudaError_t e, const char *stage, const char *what)
{
    if (e == cudaSuccess)
        return 0;
    if (c->status == SD_OK) {
        c->status = e == cudaErrorMemoryAllocation ? SD_ERR_MEMORY : SD_ERR_INTERNAL;
        snprintf(c->message, sizeof c->message, "CUDA backend, %s: %s failed: %s", stage, what,
                 cudaGetErrorString(e));
    }
    (void)cudaGetLastError(); /* clear a non-sticky error */
    return 1;
}

int sd_cuda_launched(sd_cuda_state *c, const char *stage)
{
    if (sd_cuda_check(c, cudaGetLastError(), stage, "the kernel launch"))
        return 1;
    return c->sync_stages && sd_cuda_check(c, cudaStreamSynchronize(c->stream), stage, "the kernels");
}

int sd_cuda_reserve(sd_cuda_state *c, sd_cuda_buf *b, size_t bytes, const char *stage, const char *what)
{
    if (bytes <= b->cap)
        return 0;
    if (b->p && sd_cuda_check(c, cudaFree(b->p), stage, what))
        return 1;
    b->p = NULL;
    b->cap = 0;
    size_t cap = bytes + bytes / 4; /* head room: the lists grow a little at most rebuilds */
    void *p = NULL;
    if (sd_cuda_check(c, cudaMalloc(&p, cap), stage, what))
        return 1;
    b->p = p;
    b->cap = cap;
    return 0;
}

/* The state of a stage, made on its first upload (NULL when even that
 * failed: the failure is then in a state of its own, without buffers). */
static sd_cuda_state *sd_cuda_state_of(sd_stage *s)
{
    if (s->device)
        return s->device;
    sd_cuda_state *c = (sd_cuda_state *)sd_calloc(1, sizeof *c);
    if (!c)
        return NULL;
    s->device = c;
    c->status = SD_OK;
    const char *sync = getenv("SD_CUDA_SYNC_STAGES");
    c->sync_stages = sync && sync[0] == '1';
    /* the device the world chose (world/backend.c); this process's calls
     * all go to it (one rank per GPU under mpirun) */
    if (sd_cuda_check(c, cudaSetDevice(s->device_index), "start", "cudaSetDevice"))
        return c;
    (void)sd_cuda_check(c, cudaStreamCreate(&c->stream), "start", "cudaStreamCreate");
    return c;
}

/* The device pointers into the views (c->v, c->pairs, c->wpairs): the
 * host's views with each array replaced by its copy. */
static void sd_cuda_bind(sd_cuda_state *c, const sd_stage *s)
{
    c->v = s->v;
    c->pairs = s->pairs;
    c->wpairs = s->wpairs;
#define SD_X_BIND(view, member, type, count, back) c->view.member = (type *)c->buf[SD_CUDA_##view##_##member].p;
    SD_CUDA_ARRAYS(SD_X_BIND)
#undef SD_X_BIND
    c->v.walls = (const sd_wall_view *)c->walls.p;
    c->v.meshes = (const sd_mesh_view *)c->mesh_views.p;
}

/* Bytes of device memory an upload of s needs in all (for the message). */
static size_t sd_cuda_bytes_needed(const sd_stage *s)
{
    size_t b = 0;
#define SD_X_BYTES(view, member, type, count, back) b += (size_t)(count) * sizeof(type);
    SD_CUDA_ARRAYS(SD_X_BYTES)
#undef SD_X_BYTES
    for (size_t k = 0; k < s->v.mesh_count; ++k) {
        const sd_mesh_view *m = &s->v.meshes[k];
        b += m->tri_count * (3 * sizeof(uint32_t) + sizeof(uint32_t) + sizeof(uint8_t)) +
             m->group_count * (sizeof(sd_vec3) + sizeof(sd_real)) + m->entry_count * (sizeof(uint64_t) + sizeof(uint32_t)) +
             3 * m->tri_count * sizeof(sd_vec3);
    }
    return b + s->v.wall_count * (sizeof(sd_wall_view) + 2 * sizeof(sd_vec3));
}

/* One host array to its device copy (grown when needed). */
static int sd_cuda_put(sd_cuda_state *c, sd_cuda_buf *b, const void *host, size_t bytes, const char *what)
{
    if (sd_cuda_reserve(c, b, bytes, "upload", what))
        return 1;
    if (bytes == 0 || !host)
        return 0;
    return sd_cuda_check(c, cudaMemcpyAsync(b->p, host, bytes, cudaMemcpyHostToDevice, c->stream), "upload", what);
}

/* The mesh walls' facets: copied when a mesh is new or its host arrays
 * moved (a mesh never changes in its own frame: dynamics/meshwall.h). */
static int sd_cuda_put_meshes(sd_cuda_state *c, const sd_stage *s)
{
    size_t nm = s->v.mesh_count;
    if (nm == 0)
        return 0;
    if (nm > c->mesh_cap) {
        sd_cuda_mesh *m = (sd_cuda_mesh *)sd_realloc(c->mesh, nm * sizeof *m);
        if (!m) {
            c->status = SD_ERR_MEMORY;
            snprintf(c->message, sizeof c->message, "CUDA backend, upload: out of host memory for %zu meshes", nm);
            return 1;
        }
        memset(m + c->mesh_cap, 0, (nm - c->mesh_cap) * sizeof *m);
        c->mesh = m;
        c->mesh_cap = nm;
    }
    sd_mesh_view *dv = (sd_mesh_view *)sd_malloc(nm * sizeof *dv);
    if (!dv) {
        c->status = SD_ERR_MEMORY;
        snprintf(c->message, sizeof c->message, "CUDA backend, upload: out of host memory for %zu meshes", nm);
        return 1;
    }
    int bad = 0;
    for (size_t k = 0; k < nm && !bad; ++k) {
        const sd_mesh_view *h = &s->v.meshes[k];
        sd_cuda_mesh *m = &c->mesh[k];
        if (m->host_verts != (const void *)h->verts || m->host_tris != h->tri_count) {
            /* vertices: as many as the triangles name */
            size_t nv = 0;
            for (size_t t = 0; t < h->tri_count; ++t)
                for (int a = 0; a < 3; ++a)
                    nv = h->tris[t][a] + 1 > nv ? h->tris[t][a] + 1 : nv;
            bad = sd_cuda_put(c, &m->verts, h->verts, nv * sizeof(sd_vec3), "mesh vertices") ||
                  sd_cuda_put(c, &m->tris, h->tris, h->tri_count * sizeof h->tris[0], "mesh triangles") ||
                  sd_cuda_put(c, &m->group, h->group, h->tri_count * sizeof(uint32_t), "mesh plane groups") ||
                  sd_cuda_put(c, &m->flags, h->flags, h->tri_count * sizeof(uint8_t), "mesh features") ||
                  sd_cuda_put(c, &m->normal, h->group_normal, h->group_count * sizeof(sd_vec3), "mesh normals") ||
                  sd_cuda_put(c, &m->offset, h->group_offset, h->group_count * sizeof(sd_real), "mesh offsets") ||
                  sd_cuda_put(c, &m->key, h->entry_key, h->entry_count * sizeof(uint64_t), "mesh bins") ||
                  sd_cuda_put(c, &m->tri, h->entry_tri, h->entry_count * sizeof(uint32_t), "mesh bins");
            m->host_verts = h->verts;
            m->host_tris = h->tri_count;
        }
        dv[k] = *h;
        dv[k].verts = (const sd_vec3 *)m->verts.p;
        dv[k].tris = (const uint32_t(*)[3])m->tris.p;
        dv[k].group = (const uint32_t *)m->group.p;
        dv[k].flags = (const uint8_t *)m->flags.p;
        dv[k].group_normal = (const sd_vec3 *)m->normal.p;
        dv[k].group_offset = (const sd_real *)m->offset.p;
        dv[k].entry_key = (const uint64_t *)m->key.p;
        dv[k].entry_tri = (const uint32_t *)m->tri.p;
    }
    if (!bad) {
        bad = sd_cuda_put(c, &c->mesh_views, dv, nm * sizeof *dv, "mesh views");
        /* dv is read by the copy: wait for it before freeing */
        bad = bad || sd_cuda_check(c, cudaStreamSynchronize(c->stream), "upload", "mesh views");
    }
    sd_free(dv);
    return bad;
}

extern "C" void sd_cuda_upload(sd_stage *s)
{
    sd_cuda_state *c = sd_cuda_state_of(s);
    if (!c || c->status != SD_OK)
        return;
    int bad = 0;
#define SD_X_PUT(view, member, type, count, back)                                                              \
    if (!bad) {                                                                                               \
        size_t n_ = (size_t)(count);                                                                          \
        bad = sd_cuda_put(c, &c->buf[SD_CUDA_##view##_##member], s->view.member, n_ * sizeof(type),           \
                          #view "." #member);                                                                 \
        c->held[SD_CUDA_##view##_##member] = n_;                                                             \
    }
    SD_CUDA_ARRAYS(SD_X_PUT)
#undef SD_X_PUT
    bad = bad || sd_cuda_put_meshes(c, s);
    /* the reductions' cells, the tallies (zeroed), and the polyhedron
     * workspaces: one per thread of a batch (pairs.cu) */
    int fresh = c->tally.p == NULL;
    bad = bad || sd_cuda_reserve(c, &c->flag, sizeof(int), "upload", "flags") ||
          sd_cuda_reserve(c, &c->minbits, sizeof(unsigned long long), "upload", "the minimum") ||
          sd_cuda_reserve(c, &c->tally, (SD_CUDA_TALLY3 + SD_CUDA_TALLY2) * sizeof(unsigned long long), "upload",
                          "tallies");
    if (!bad && fresh) /* the tallies count from zero; read back adds them to the world's and clears them */
        bad = sd_cuda_check(c, cudaMemsetAsync(c->tally.p, 0, c->tally.cap, c->stream), "upload", "tallies");
    if (!bad && c->ws_count == 0 && (s->pairs.kind_start[SD_PAIR_POLY_VOLUME + 1] > s->pairs.kind_start[SD_PAIR_POLY_VOLUME] ||
                                     s->pairs.kind_start[SD_PAIR_ELEMENTS + 1] > s->pairs.kind_start[SD_PAIR_ELEMENTS])) {
        /* a batch of workspaces sized to a share of the free memory
         * (seed 000 §2.3: overlap volumes in batches) */
        size_t free_b = 0, total = 0;
        (void)cudaMemGetInfo(&free_b, &total);
        size_t n = free_b / 8 / sizeof(sd_overlap_workspace);
        n = n > SD_CUDA_MAX_WORKSPACES ? SD_CUDA_MAX_WORKSPACES : (n < 1 ? 1 : n);
        if (!sd_cuda_reserve(c, &c->ws, n * sizeof(sd_overlap_workspace), "upload", "overlap workspaces"))
            c->ws_count = n;
        else
            bad = 1;
    }
    if (bad && c->status == SD_ERR_MEMORY) {
        size_t free_b = 0, total = 0;
        (void)cudaMemGetInfo(&free_b, &total);
        char why[sizeof c->message];
        snprintf(why, sizeof why, "%s", c->message);
        snprintf(c->message, sizeof c->message,
                 "out of device memory: the state of %zu particles and %zu pairs needs %.1f MiB on the device "
                 "(%.1f MiB free of %.1f MiB; %.200s)",
                 s->v.n_total, s->pairs.n + s->wpairs.n, (double)sd_cuda_bytes_needed(s) / 1048576.0,
                 (double)free_b / 1048576.0, (double)total / 1048576.0, why);
        return;
    }
    if (!bad)
        sd_cuda_upload_walls(s);
}

extern "C" void sd_cuda_upload_walls(sd_stage *s)
{
    sd_cuda_state *c = sd_cuda_state_of(s);
    if (!c || c->status != SD_OK)
        return;
    size_t nw = s->v.wall_count;
    if (sd_cuda_reserve(c, &c->walls, nw * sizeof(sd_wall_view), "walls", "wall views") ||
        sd_cuda_reserve(c, &c->wall_force, nw * sizeof(sd_vec3), "walls", "wall totals") ||
        sd_cuda_reserve(c, &c->wall_torque, nw * sizeof(sd_vec3), "walls", "wall totals"))
        return;
    if (nw && sd_cuda_check(c, cudaMemcpyAsync(c->walls.p, s->walls, nw * sizeof(sd_wall_view), cudaMemcpyHostToDevice,
                                               c->stream),
                            "walls", "wall views"))
        return;
    /* the host's views may have new scalars too (dt, gravity, damping:
     * sd_world_views_params) */
    sd_cuda_bind(c, s);
    /* the host's wall views are reused by the next step: wait for the copy */
    (void)sd_cuda_check(c, cudaStreamSynchronize(c->stream), "walls", "wall views");
}

/* The arrays the device writes, back into the host's (the lengths of the
 * last upload: the host's views have not been refilled since). */
extern "C" void sd_cuda_read_back(sd_stage *s)
{
    sd_cuda_state *c = s->device;
    if (!c || c->status != SD_OK)
        return;
    if (c->totals_pending) /* into s->wall_force, s->wall_torque (walls.cu) */
        sd_cuda_wall_totals_now(s);
    int bad = c->status != SD_OK;
#define SD_X_GET(view, member, type, count, back)                                                              \
    if (back && !bad && c->held[SD_CUDA_##view##_##member])                                                   \
        bad = sd_cuda_check(c,                                                                                 \
                            cudaMemcpyAsync((void *)s->view.member, c->buf[SD_CUDA_##view##_##member].p,       \
                                            c->held[SD_CUDA_##view##_##member] * sizeof(type),                \
                                            cudaMemcpyDeviceToHost, c->stream),                                \
                            "read back", #view "." #member);
    SD_CUDA_ARRAYS(SD_X_GET)
#undef SD_X_GET
    /* the narrow-phase tallies since the last read back, into the world's */
    unsigned long long t[SD_CUDA_TALLY3 + SD_CUDA_TALLY2];
    bad = bad || sd_cuda_check(c, cudaMemcpyAsync(t, c->tally.p, sizeof t, cudaMemcpyDeviceToHost, c->stream),
                               "read back", "tallies");
    bad = bad || sd_cuda_check(c, cudaStreamSynchronize(c->stream), "read back", "the copies");
    if (bad)
        return;
    long long *n3 = &s->narrow[0][0][0], *n2 = &s->narrow2d[0][0][0];
    int any = 0;
    for (int k = 0; k < SD_CUDA_TALLY3; ++k)
        any |= t[k] != 0, n3[k] += (long long)t[k];
    for (int k = 0; k < SD_CUDA_TALLY2; ++k)
        any |= t[SD_CUDA_TALLY3 + k] != 0, n2[k] += (long long)t[SD_CUDA_TALLY3 + k];
    if (any)
        (void)sd_cuda_check(c, cudaMemsetAsync(c->tally.p, 0, sizeof t, c->stream), "read back", "tallies");
}

extern "C" void sd_cuda_read_back_wall_pairs(sd_stage *s)
{
    sd_cuda_state *c = s->device;
    if (!c || c->status != SD_OK || !c->held[SD_CUDA_wpairs_delta])
        return;
    /* the overlaps (each wall's contact stiffness) and the forces (a servo
     * wall's force summed over the ranks, world/servo.c) */
    if (!sd_cuda_check(c, cudaMemcpyAsync((void *)s->wpairs.delta, c->buf[SD_CUDA_wpairs_delta].p,
                                          c->held[SD_CUDA_wpairs_delta] * sizeof(sd_real), cudaMemcpyDeviceToHost,
                                          c->stream),
                       "wall motion", "wall pair overlaps") &&
        !sd_cuda_check(c, cudaMemcpyAsync((void *)s->wpairs.f, c->buf[SD_CUDA_wpairs_f].p,
                                          c->held[SD_CUDA_wpairs_f] * sizeof(sd_vec3), cudaMemcpyDeviceToHost,
                                          c->stream),
                       "wall motion", "wall pair forces"))
        (void)sd_cuda_check(c, cudaStreamSynchronize(c->stream), "wall motion", "wall pairs");
}

/* Which views' arrays are the particle state (state.h's view column). */
#define SD_CUDA_ROWS_v 1
#define SD_CUDA_ROWS_pairs 0
#define SD_CUDA_ROWS_wpairs 0

/* The particle state the stages write (the arrays of view v with back 1:
 * x, v, w, q, f, t), rows [first, end) (within the last upload's), to
 * the device (up) or back to the host; then waits, as the host reads or
 * refills those rows next. */
static void sd_cuda_state_rows(sd_stage *s, size_t first, size_t end, int up, const char *stage)
{
    sd_cuda_state *c = s->device;
    if (!c || c->status != SD_OK || end <= first)
        return;
    int bad = 0;
#define SD_X_ROWS(view, member, type, count, back)                                                               \
    if (back && SD_CUDA_ROWS_##view && !bad) {                                                                    \
        size_t e_ = end < c->held[SD_CUDA_##view##_##member] ? end : c->held[SD_CUDA_##view##_##member];          \
        if (first < e_) {                                                                                         \
            char *h_ = (char *)(void *)s->view.member + first * sizeof(type);                                    \
            char *d_ = (char *)c->buf[SD_CUDA_##view##_##member].p + first * sizeof(type);                        \
            bad = sd_cuda_check(c,                                                                               \
                                cudaMemcpyAsync(up ? d_ : h_, up ? h_ : d_, (e_ - first) * sizeof(type),         \
                                                up ? cudaMemcpyHostToDevice : cudaMemcpyDeviceToHost, c->stream), \
                                stage, #view "." #member);                                                        \
        }                                                                                                         \
    }
    SD_CUDA_ARRAYS(SD_X_ROWS)
#undef SD_X_ROWS
    if (!bad)
        (void)sd_cuda_check(c, cudaStreamSynchronize(c->stream), stage, "the state rows");
}

extern "C" void sd_cuda_read_back_state(sd_stage *s, size_t first, size_t end)
{
    sd_cuda_state_rows(s, first, end, 0, "ghost exchange (read back)");
}

extern "C" void sd_cuda_upload_state(sd_stage *s, size_t first, size_t end)
{
    sd_cuda_state_rows(s, first, end, 1, "ghost exchange (upload)");
}

#ifdef SHAPEDEM_CUDA_EMULATE
extern "C" int sd_cuda_emulated_device(void) { return sd_emu_device; }
#endif

static void sd_cuda_free_buf(sd_cuda_buf *b)
{
    if (b->p)
        (void)cudaFree(b->p);
    b->p = NULL;
    b->cap = 0;
}

extern "C" void sd_cuda_release(sd_stage *s)
{
    sd_cuda_state *c = s->device;
    if (!c)
        return;
    for (int k = 0; k < SD_CUDA_ARRAY_COUNT; ++k)
        sd_cuda_free_buf(&c->buf[k]);
    for (size_t k = 0; k < c->mesh_cap; ++k) {
        sd_cuda_mesh *m = &c->mesh[k];
        sd_cuda_buf *all[] = {&m->verts, &m->tris, &m->group, &m->flags, &m->normal, &m->offset, &m->key, &m->tri};
        for (size_t a = 0; a < sizeof all / sizeof all[0]; ++a)
            sd_cuda_free_buf(all[a]);
    }
    sd_cuda_buf *own[] = {&c->walls, &c->wall_force, &c->wall_torque, &c->mesh_views, &c->flag,
                          &c->minbits, &c->tally, &c->ws};
    for (size_t a = 0; a < sizeof own / sizeof own[0]; ++a)
        sd_cuda_free_buf(own[a]);
    if (c->stream)
        (void)cudaStreamDestroy(c->stream);
    sd_free(c->mesh);
    sd_free(c);
    s->device = NULL;
}

extern "C" sd_status sd_cuda_status(sd_stage *s, sd_error *err)
{
    sd_cuda_state *c = s->device;
    if (!c) /* the state itself could not be made */
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "CUDA backend: out of host memory for its state");
    if (c->status == SD_OK)
        return SD_OK;
    return sd_error_set(err, c->status, "", 0, "", "%s", c->message);
}
