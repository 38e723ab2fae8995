/* poly_law.cu — compile-only proof that the volume laws and their pair
 * evaluation (contact/law_volume.h, contact/pair_poly.h, geom/halfspace.h)
 * are single source (DESIGN.md rule 1): they compile as CUDA C++ with nvcc
 * and as C++ with the host compiler, and run one pair per thread with a
 * per-thread overlap workspace, as the CUDA backend will. */
#include "contact/law_volume.h"
#include "contact/pair_poly.h"
#include "geom/halfspace.h"

#if defined(__CUDACC__)
#define SD_KERNEL __global__
#else
#define SD_KERNEL static
#endif

/* One polyhedron pair and one polyhedron-wall pair per thread. ws holds one
 * workspace per thread (global memory: ~30 KB each, too large for the stack). */
SD_KERNEL void sd_check_poly(const sd_pair_params *prm, const sd_body *a, const sd_body *b, const sd_convex *ca,
                             const sd_convex *cb, sd_vec3 *ds, sd_vec3 *x0, uint8_t *x0_ok, sd_overlap_workspace *ws,
                             sd_pair_result *out, int n, sd_real dt)
{
#if defined(__CUDACC__)
    int k = (int)(blockIdx.x * blockDim.x + threadIdx.x);
#else
    int k = 0;
#endif
    if (k >= n)
        return;
    sd_narrow_count ns;
    out[k] = sd_pair_poly(prm, &a[k], &b[k], &ca[k], &cb[k], SD_R(0.01), SD_R(0.01), &ds[k], &x0[k], &x0_ok[k], &ws[k],
                          dt, &ns);
    sd_vec3 point;
    sd_pair_result wr = sd_pair_poly_wall(prm, &a[k], &ca[k], sd_v3_zero(), sd_v3(0, 0, 1), SD_R(0.01), &ds[k], dt, &point);
    out[k].f = sd_v3_add(out[k].f, wr.f);
}

#if !defined(__CUDACC__)
void sd_poly_law_keep(void);
void sd_poly_law_keep(void) { (void)&sd_check_poly; }
#endif
