/* contacts.c — coordination numbers from the cells solver's contact list
 * (shapedem/analysis.h; seed 004 §4.2 reports their time average in the
 * rotating drum).
 *
 * A particle pair is in contact when one of its pair entries had an
 * overlap > 0 at the last force evaluation. Composites contribute one
 * entry per element pair, and a periodic contact is held once, with the
 * ghost's owner as the second body; so the entries in contact are reduced
 * to distinct (owned i, owner of j) pairs (sorted, then unique) before
 * counting. Wall contacts alike: distinct (particle, wall, feature). A
 * region keeps the particles whose centre lies in it, with every contact
 * they have (a contact with a particle outside counts for the one
 * inside).
 *
 * Invariant: reads only; the counts are integers in a fixed order, the
 * same for any thread count.
 */
#include <stdlib.h>
#include <string.h>

#include "analysis/analysis.h"
#include "core/alloc.h"
#include "world/solver.h"

typedef struct sd_an_pair {
    uint32_t a, b, c; /* particle, particle (or wall), feature */
} sd_an_pair;

static int sd_an_pair_cmp(const void *x, const void *y)
{
    const sd_an_pair *p = x, *q = y;
    if (p->a != q->a)
        return p->a < q->a ? -1 : 1;
    if (p->b != q->b)
        return p->b < q->b ? -1 : 1;
    return p->c < q->c ? -1 : p->c > q->c;
}

/* Sorts and drops repeats; the count left. */
static size_t sd_an_unique(sd_an_pair *v, size_t n)
{
    if (n == 0)
        return 0;
    qsort(v, n, sizeof *v, sd_an_pair_cmp);
    size_t m = 1;
    for (size_t k = 1; k < n; ++k)
        if (sd_an_pair_cmp(&v[k], &v[m - 1]) != 0)
            v[m++] = v[k];
    return m;
}

sd_status sd_world_coordination(const sd_world *w, const sd_region_def *region, sd_coordination *out,
                                sd_error *err)
{
    if (!w || !out)
        return sd_error_null(err, "sd_world_coordination", !w ? "world" : "out");
    memset(out, 0, sizeof *out);
    sd_an_region reg;
    sd_status st = sd_an_region_make(region, w->dim2, &reg, err);
    if (st != SD_OK)
        return st;
    if (w->solver != &sd_solver_cells)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "type",
                            "coordination reads the contact list of the cells solver; the %s solver keeps none",
                            w->solver->name);
    const size_t n = w->p.n;
    if (n == 0)
        return SD_OK;
    const sd_pair_list *l = &w->pairs;
    const sd_wall_pair_list *wl = &w->wpairs;
    size_t cap = l->n + wl->n;
    sd_an_pair *v = sd_calloc(cap ? cap : 1, sizeof *v);
    uint32_t *z = sd_calloc(n, sizeof *z), *zw = sd_calloc(n, sizeof *zw);
    if (!v || !z || !zw) {
        sd_free(v);
        sd_free(z);
        sd_free(zw);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (coordination)");
    }
    size_t m = 0;
    for (size_t e = 0; e < l->n; ++e) {
        if (!(l->delta[e] > 0))
            continue;
        uint32_t i = l->i[e], j = l->j[e];
        if (j >= n) /* a periodic image: its owner */
            j = w->ghost_owner[j - n];
        if (i >= n || j >= n || i == j)
            continue;
        v[m].a = i < j ? i : j;
        v[m].b = i < j ? j : i;
        v[m].c = 0;
        m++;
    }
    m = sd_an_unique(v, m);
    for (size_t k = 0; k < m; ++k) {
        z[v[k].a]++;
        z[v[k].b]++;
        out->contacts += sd_an_region_has(&reg, w->p.x[v[k].a]) || sd_an_region_has(&reg, w->p.x[v[k].b]);
    }
    m = 0;
    for (size_t e = 0; e < wl->n; ++e) {
        if (!(wl->delta[e] > 0) || wl->i[e] >= n)
            continue;
        v[m].a = wl->i[e];
        v[m].b = wl->wall[e];
        v[m].c = wl->sub[e];
        m++;
    }
    m = sd_an_unique(v, m);
    for (size_t k = 0; k < m; ++k)
        zw[v[k].a]++;
    long zsum = 0;
    for (size_t k = 0; k < n; ++k) {
        if (!sd_an_region_has(&reg, w->p.x[k]))
            continue;
        out->particles++;
        out->histogram[z[k] < SD_COORDINATION_MAX ? z[k] : SD_COORDINATION_MAX]++;
        out->rattlers += z[k] == 0 && zw[k] == 0;
        out->wall_contacts += (long)zw[k];
        zsum += (long)z[k];
    }
    if (out->particles > 0) {
        out->mean = (double)zsum / (double)out->particles;
        out->mean_with_walls = (double)(zsum + out->wall_contacts) / (double)out->particles;
    }
    sd_free(v);
    sd_free(z);
    sd_free(zw);
    return SD_OK;
}
