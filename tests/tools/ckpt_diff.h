/* ckpt_diff.h — compares two world states (sd_snapshot, as read from
 * checkpoints) dataset by dataset: the bits of every value, and for
 * floating-point fields the largest difference relative to the field's
 * scale. The comparison of bench/gpu/run's CPU-vs-GPU equality cases
 * (tests/tools/ckpt_diff.c is its command; unit.ckpt_diff tests it).
 *
 * Invariant: two states compare equal with tolerance 0 exactly when every
 * dataset has the same name, type, shape and bytes and the headers (step,
 * time, scene hash, dimension, solver) agree; any single flipped bit is a
 * difference. With a tolerance tol > 0, an f64 field passes when
 * max |a - b| <= tol * max(|a|, |b|) over the field (its scale: a velocity
 * component near zero is judged against the field's largest velocity, not
 * its own magnitude); integer and byte datasets must still be identical.
 */
#ifndef SD_TOOLS_CKPT_DIFF_H
#define SD_TOOLS_CKPT_DIFF_H

#include "world/snapshot.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct sd_ckdiff_result {
    size_t datasets;       /* names in either state */
    size_t differ;         /* datasets with any differing bit (or missing, or reshaped) */
    size_t beyond;         /* datasets beyond the tolerance (all non-f64 differences count) */
    int header_differs;    /* step, time, scene hash, dimension or solver */
    double max_rel;        /* largest f64 difference over its field's scale */
    char worst[64];        /* the dataset of max_rel */
} sd_ckdiff_result;

/* One dataset: counts differing values, the largest |a - b| and the field's
 * scale max(|a|, |b|). Returns the number of differing values (bytes for
 * non-f64 items). */
static size_t sd_ckdiff_item(const sd_snap_item *a, const sd_snap_item *b, double *max_abs, double *scale)
{
    size_t n = a->count * a->comps, differ = 0;
    *max_abs = 0.0;
    *scale = 0.0;
    if (a->type == SD_ST_F64) {
        const unsigned char *pa = (const unsigned char *)a->data, *pb = (const unsigned char *)b->data;
        for (size_t i = 0; i < n; i++) {
            double x, y;
            memcpy(&x, pa + 8 * i, 8);
            memcpy(&y, pb + 8 * i, 8);
            if (fabs(x) > *scale)
                *scale = fabs(x);
            if (fabs(y) > *scale)
                *scale = fabs(y);
            if (memcmp(pa + 8 * i, pb + 8 * i, 8) != 0) {
                differ++;
                double d = fabs(x - y);
                if (d != d) /* a NaN on one side only */
                    d = (double)INFINITY;
                if (d > *max_abs)
                    *max_abs = d;
            }
        }
        return differ;
    }
    size_t bytes = n * sd_state_type_size(a->type);
    const unsigned char *pa = (const unsigned char *)a->data, *pb = (const unsigned char *)b->data;
    for (size_t i = 0; i < bytes; i++)
        differ += pa[i] != pb[i];
    return differ;
}

/* Compares a and b; prints one line per dataset (all when verbose, else
 * the differing ones) and the headers' differences to out (NULL: silent). */
static void sd_ckdiff_compare(const sd_snapshot *a, const sd_snapshot *b, double tol, int verbose, FILE *out,
                              sd_ckdiff_result *res)
{
    memset(res, 0, sizeof *res);
    if (a->step != b->step || memcmp(&a->time, &b->time, sizeof a->time) != 0 || a->scene_hash != b->scene_hash ||
        a->dimension != b->dimension || strcmp(a->solver, b->solver) != 0) {
        res->header_differs = 1;
        if (out)
            fprintf(out, "header: step %ld / %ld, time %.17g / %.17g, scene hash %016llx / %016llx, dimension %d / %d, "
                         "solver %s / %s\n",
                    a->step, b->step, a->time, b->time, (unsigned long long)a->scene_hash,
                    (unsigned long long)b->scene_hash, a->dimension, b->dimension, a->solver, b->solver);
    }
    /* both item lists are sorted by name: merge them */
    size_t i = 0, j = 0;
    while (i < a->n || j < b->n) {
        int c = i == a->n ? 1 : j == b->n ? -1 : strcmp(a->items[i].name, b->items[j].name);
        res->datasets++;
        if (c != 0) {
            const sd_snap_item *only = c < 0 ? &a->items[i] : &b->items[j];
            res->differ++;
            res->beyond++;
            if (out)
                fprintf(out, "%-28s only in %s\n", only->name, c < 0 ? "the first" : "the second");
            if (c < 0)
                i++;
            else
                j++;
            continue;
        }
        const sd_snap_item *x = &a->items[i++], *y = &b->items[j++];
        if (x->type != y->type || x->comps != y->comps || x->count != y->count) {
            res->differ++;
            res->beyond++;
            if (out)
                fprintf(out, "%-28s shape differs: %s %zu x %zu / %s %zu x %zu\n", x->name, sd_state_type_name(x->type),
                        x->count, x->comps, sd_state_type_name(y->type), y->count, y->comps);
            continue;
        }
        double max_abs, scale;
        size_t nd = sd_ckdiff_item(x, y, &max_abs, &scale);
        double rel = nd == 0 ? 0.0 : scale > 0.0 ? max_abs / scale : (double)INFINITY;
        int beyond = nd != 0 && (x->type != SD_ST_F64 || !(rel <= tol));
        if (nd) {
            res->differ++;
            res->beyond += (size_t)beyond;
            double r = x->type == SD_ST_F64 ? rel : (double)INFINITY; /* integers: any difference */
            if (r > res->max_rel || !res->worst[0]) {
                res->max_rel = r > res->max_rel ? r : res->max_rel;
                snprintf(res->worst, sizeof res->worst, "%s", x->name);
            }
        }
        if (out && (verbose || nd)) {
            if (!nd)
                fprintf(out, "%-28s %-5s %8zu x %-2zu identical\n", x->name, sd_state_type_name(x->type), x->count,
                        x->comps);
            else if (x->type == SD_ST_F64)
                fprintf(out, "%-28s %-5s %8zu x %-2zu %zu values differ, max |diff| %.3g, relative to the field %.3g%s\n",
                        x->name, sd_state_type_name(x->type), x->count, x->comps, nd, max_abs, rel,
                        beyond ? " (beyond tolerance)" : "");
            else
                fprintf(out, "%-28s %-5s %8zu x %-2zu %zu bytes differ\n", x->name, sd_state_type_name(x->type),
                        x->count, x->comps, nd);
        }
    }
}

#endif
