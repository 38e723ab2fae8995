/* overlap_gpu.cu — the exact polyhedron overlap volume (geom/overlap.h) run
 * on a GPU, one pair per thread with its own workspace (seed 000 §2.3), and
 * compared with the same function on the CPU: a check that the single-source
 * numerics (DESIGN.md rule 1) give the same numbers on both, plus the GPU's
 * pairs per second. Needs a CUDA GPU; not part of the test suite.
 *
 * Build (the templates are made on the host by the C library files):
 *   cc -std=c17 -O2 -c -Isrc -Iinclude src/shape/shape.c src/shape/polylib.c src/core/alloc.c src/core/error.c
 *   nvcc -std=c++17 -O2 -arch=native -Isrc -Iinclude bench/overlap_gpu.cu shape.o polylib.o alloc.o error.o \
 *        -o overlap_gpu
 * Run: overlap_gpu [pairs, default 65536]
 */
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

extern "C" {
#include "core/error.h"
#include "shape/polylib.h"
#include "shape/shape_make.h"
}
#include "core/rng.h"
#include "geom/overlap.h"

#define TV 256

struct tpl {
    sd_shape s;
    sd_vec3 v[TV];
    sd_plane p[2 * TV];
    sd_dtri t[4 * TV];
};

static int tpl_make(tpl *T, int preset, int faces)
{
    sd_poly_def d;
    memset(&d, 0, sizeof d);
    d.preset = preset;
    d.diameter = 1.0;
    d.faces = faces;
    d.seed = 5;
    sd_v3d vv[TV];
    sd_vec3 pts[TV];
    size_t n, used, np, nt;
    sd_error err;
    if (sd_polylib_vertices(&d, vv, TV, &n, &err) != SD_OK)
        return 1;
    for (size_t k = 0; k < n; ++k)
        pts[k] = sd_v3(vv[k].x, vv[k].y, vv[k].z);
    sd_shape_def sd = sd_shape_def_default();
    sd.kind = SD_SHAPE_POLYHEDRON;
    sd.vertices = pts;
    sd.vertex_count = n;
    if (sd_shape_make(&sd, &T->s, T->v, TV, &used, &err) != SD_OK)
        return 1;
    T->s.vstart = 0;
    T->s.vcount = (uint32_t)used;
    return sd_shape_faces(&T->s, T->v, T->p, 2 * TV, &np, T->t, 4 * TV, &nt, &err) != SD_OK;
}

__global__ void overlap_kernel(const sd_shape *shape, const sd_vec3 *verts, const sd_plane *planes,
                               const sd_dtri *dtris, const sd_vec3 *xa, const sd_quat *qa, const sd_vec3 *xb,
                               const sd_quat *qb, sd_overlap_workspace *ws, sd_overlap *out, int n)
{
    int k = (int)(blockIdx.x * blockDim.x + threadIdx.x);
    if (k >= n)
        return;
    sd_convex a, b;
    a.shape = b.shape = shape;
    a.verts = b.verts = verts;
    a.planes = b.planes = planes;
    a.dtris = b.dtris = dtris;
    a.x = xa[k];
    a.q = qa[k];
    b.x = xb[k];
    b.q = qb[k];
    out[k] = sd_overlap_polyhedra(&a, &b, sd_v3_zero(), 0, &ws[k]);
}

#define CK(x)                                                                                                          \
    do {                                                                                                               \
        cudaError_t e_ = (x);                                                                                          \
        if (e_ != cudaSuccess) {                                                                                       \
            fprintf(stderr, "overlap_gpu: %s: %s\n", #x, cudaGetErrorString(e_));                                      \
            return 1;                                                                                                  \
        }                                                                                                              \
    } while (0)

int main(int argc, char **argv)
{
    int n = argc > 1 ? atoi(argv[1]) : 65536;
    static tpl T;
    const char *names[] = {"cube", "dodecahedron", "random32"};
    int presets[] = {SD_POLY_CUBE, SD_POLY_DODECAHEDRON, SD_POLY_RANDOM}, faces[] = {0, 0, 32};
    static sd_overlap_workspace hws;
    for (int s = 0; s < 3; ++s) {
        if (tpl_make(&T, presets[s], faces[s]))
            return fprintf(stderr, "overlap_gpu: template failed\n"), 1;
        std::vector<sd_vec3> xa(n), xb(n);
        std::vector<sd_quat> qa(n), qb(n);
        sd_rng r = sd_rng_seed(99 + s);
        for (int k = 0; k < n; ++k) {
            sd_quat q1 = sd_quat_make(sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1),
                                      sd_rng_range(&r, -1, 1));
            sd_quat q2 = sd_quat_make(sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1),
                                      sd_rng_range(&r, -1, 1));
            sd_vec3 d = sd_v3(sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1));
            xa[k] = sd_v3_zero();
            qa[k] = sd_quat_normalize(q1);
            xb[k] = sd_v3_scale(d, T.s.bound * 1.2);
            qb[k] = sd_quat_normalize(q2);
        }
        sd_shape *dshape;
        sd_vec3 *dverts, *dxa, *dxb;
        sd_plane *dplanes;
        sd_dtri *ddtris;
        sd_quat *dqa, *dqb;
        sd_overlap_workspace *dws;
        sd_overlap *dout;
        CK(cudaMalloc(&dshape, sizeof T.s));
        CK(cudaMalloc(&dverts, sizeof T.v));
        CK(cudaMalloc(&dplanes, sizeof T.p));
        CK(cudaMalloc(&ddtris, sizeof T.t));
        CK(cudaMalloc(&dxa, n * sizeof(sd_vec3)));
        CK(cudaMalloc(&dxb, n * sizeof(sd_vec3)));
        CK(cudaMalloc(&dqa, n * sizeof(sd_quat)));
        CK(cudaMalloc(&dqb, n * sizeof(sd_quat)));
        CK(cudaMalloc(&dws, (size_t)n * sizeof(sd_overlap_workspace)));
        CK(cudaMalloc(&dout, n * sizeof(sd_overlap)));
        CK(cudaMemcpy(dshape, &T.s, sizeof T.s, cudaMemcpyHostToDevice));
        CK(cudaMemcpy(dverts, T.v, sizeof T.v, cudaMemcpyHostToDevice));
        CK(cudaMemcpy(dplanes, T.p, sizeof T.p, cudaMemcpyHostToDevice));
        CK(cudaMemcpy(ddtris, T.t, sizeof T.t, cudaMemcpyHostToDevice));
        CK(cudaMemcpy(dxa, xa.data(), n * sizeof(sd_vec3), cudaMemcpyHostToDevice));
        CK(cudaMemcpy(dxb, xb.data(), n * sizeof(sd_vec3), cudaMemcpyHostToDevice));
        CK(cudaMemcpy(dqa, qa.data(), n * sizeof(sd_quat), cudaMemcpyHostToDevice));
        CK(cudaMemcpy(dqb, qb.data(), n * sizeof(sd_quat), cudaMemcpyHostToDevice));
        int bs = 128, nb = (n + bs - 1) / bs;
        overlap_kernel<<<nb, bs>>>(dshape, dverts, dplanes, ddtris, dxa, dqa, dxb, dqb, dws, dout, n);
        CK(cudaGetLastError());
        CK(cudaDeviceSynchronize());
        cudaEvent_t e0, e1;
        cudaEventCreate(&e0);
        cudaEventCreate(&e1);
        float best = 1e30f;
        for (int rep = 0; rep < 5; ++rep) {
            cudaEventRecord(e0);
            overlap_kernel<<<nb, bs>>>(dshape, dverts, dplanes, ddtris, dxa, dqa, dxb, dqb, dws, dout, n);
            cudaEventRecord(e1);
            CK(cudaEventSynchronize(e1));
            float ms;
            cudaEventElapsedTime(&ms, e0, e1);
            best = ms < best ? ms : best;
        }
        std::vector<sd_overlap> g(n);
        CK(cudaMemcpy(g.data(), dout, n * sizeof(sd_overlap), cudaMemcpyDeviceToHost));
        /* the same pairs on the CPU */
        double worst = 0, worst_n = 0;
        int ok = 0, status_diff = 0;
        for (int k = 0; k < n; ++k) {
            sd_convex a, b;
            a.shape = b.shape = &T.s;
            a.verts = b.verts = T.v;
            a.planes = b.planes = T.p;
            a.dtris = b.dtris = T.t;
            a.x = xa[k];
            a.q = qa[k];
            b.x = xb[k];
            b.q = qb[k];
            sd_overlap c = sd_overlap_polyhedra(&a, &b, sd_v3_zero(), 0, &hws);
            status_diff += c.status != g[k].status;
            if (c.status == SD_OVERLAP_OK && g[k].status == SD_OVERLAP_OK) {
                ++ok;
                double d = fabs(c.volume - g[k].volume) / c.volume;
                worst = d > worst ? d : worst;
                double dn = sd_v3_norm(sd_v3_sub(sd_v3_scale(c.normal, c.area), sd_v3_scale(g[k].normal, g[k].area)));
                dn /= c.area > 1e-12 ? c.area : 1e-12;
                worst_n = dn > worst_n ? dn : worst_n;
            }
        }
        printf("%-13s %d pairs (%d overlapping): GPU %.3f ms = %.3g pairs/s; status differs %d; "
               "max |V_gpu - V_cpu|/V %.3g, max |S_gpu - S_cpu|/|S| %.3g\n",
               names[s], n, ok, best, n / (best * 1e-3), status_diff, worst, worst_n);
        cudaFree(dshape);
        cudaFree(dverts);
        cudaFree(dplanes);
        cudaFree(ddtris);
        cudaFree(dxa);
        cudaFree(dxb);
        cudaFree(dqa);
        cudaFree(dqb);
        cudaFree(dws);
        cudaFree(dout);
    }
    return 0;
}
