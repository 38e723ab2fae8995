/* dump.c — LAMMPS-style dump text of the particles (see dump.h).
 *
 * One block per frame, in the layout of LAMMPS's `dump custom` (LAMMPS
 * documentation, "dump" command): the step (TIMESTEP; the time is the step
 * times the run's time step, summary.txt's time_step_s), the particle
 * count, three lines of box bounds and one line per particle. LAMMPS's
 * column names are used where LAMMPS has the quantity (id, type, x, vx,
 * fx, omegax, radius, quatw..quatk of its ellipsoid and body styles), so
 * readers map them to their own properties; `type` is the material index
 * + 1 (LAMMPS types count from 1) and `shape` the template index, -1 for a
 * plain sphere. Positions are those of the particle frames: periodic
 * images wrapped into the box (world/rebuild.h).
 */
#include "io/dump.h"

#include "core/alloc.h"
#include "core/error.h"
#include "world/rebuild.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

sd_status sd_dump_particle(const sd_world *w, uint64_t id, sd_particle_state *p, sd_error *err)
{
    size_t i = sd_world_find_particle(w, id);
    if (i == (size_t)-1 || sd_world_get_particle(w, i, p) != SD_OK)
        return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "cannot read particle id %llu of the world",
                            (unsigned long long)id);
    sd_world_wrap_periodic(w, &p->position);
    return SD_OK;
}

/* The box bounds: periodic axes from the box, the others the particles'
 * extent with their radii (0 0 for an empty world). */
static sd_status sd_dump_bounds(const sd_world *w, const uint64_t *ids, size_t n, const sd_dump_box *box, double lo[3],
                                double hi[3], sd_error *err)
{
    for (int k = 0; k < 3; ++k)
        lo[k] = hi[k] = 0.0;
    for (size_t i = 0; i < n; ++i) {
        sd_particle_state p;
        sd_status s = sd_dump_particle(w, ids[i], &p, err);
        if (s != SD_OK)
            return s;
        const double x[3] = {p.position.x, p.position.y, p.position.z};
        for (int k = 0; k < 3; ++k) {
            double a = x[k] - p.radius, b = x[k] + p.radius;
            lo[k] = (i == 0 || a < lo[k]) ? a : lo[k];
            hi[k] = (i == 0 || b > hi[k]) ? b : hi[k];
        }
    }
    const double dlo[3] = {box->domain_lo.x, box->domain_lo.y, box->domain_lo.z};
    const double dhi[3] = {box->domain_hi.x, box->domain_hi.y, box->domain_hi.z};
    for (int k = 0; k < 3; ++k)
        if (box->periodic & (1u << k)) {
            lo[k] = dlo[k];
            hi[k] = dhi[k];
        }
    return SD_OK;
}

sd_status sd_dump_write(FILE *fp, const sd_world *w, const sd_dump_box *box, sd_error *err)
{
    size_t n = sd_world_particle_count(w);
    uint64_t *ids = sd_malloc((n ? n : 1) * sizeof *ids);
    if (!ids)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    sd_status s = sd_world_get_ids(w, ids, n, err);
    double lo[3], hi[3];
    if (s == SD_OK)
        s = sd_dump_bounds(w, ids, n, box, lo, hi, err);
    if (s == SD_OK) {
        fprintf(fp, "ITEM: TIMESTEP\n%ld\nITEM: NUMBER OF ATOMS\n%zu\nITEM: BOX BOUNDS", sd_world_step_count(w), n);
        for (int k = 0; k < 3; ++k)
            fputs(box->periodic & (1u << k) ? " pp" : " ss", fp);
        fputc('\n', fp);
        for (int k = 0; k < 3; ++k)
            fprintf(fp, "%.17g %.17g\n", lo[k], hi[k]);
        fputs("ITEM: ATOMS " SD_DUMP_COLUMNS "\n", fp);
    }
    for (size_t i = 0; s == SD_OK && i < n; ++i) {
        sd_particle_state p;
        s = sd_dump_particle(w, ids[i], &p, err);
        if (s != SD_OK)
            break;
        fprintf(fp,
                "%llu %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g "
                "%.17g %.17g %.17g %d\n",
                (unsigned long long)p.id, p.material + 1, p.position.x, p.position.y, p.position.z, p.velocity.x,
                p.velocity.y, p.velocity.z, p.force.x, p.force.y, p.force.z, p.angular_velocity.x, p.angular_velocity.y,
                p.angular_velocity.z, p.radius, p.quat[0], p.quat[1], p.quat[2], p.quat[3], p.shape);
    }
    sd_free(ids);
    if (s == SD_OK && ferror(fp))
        s = sd_error_set(err, SD_ERR_IO, "", 0, "", "write failed: %s", strerror(errno ? errno : EIO));
    return s;
}

/* ---- a restart's blocks --------------------------------------------------- */

/* The line at *at (up to its '\n', which must be there) into line[len];
 * *at moves past it. 0 at the end or for a line cut short. */
static int sd_dump_line(const char *text, size_t n, size_t *at, const char **line, size_t *len)
{
    if (*at >= n)
        return 0;
    const char *a = text + *at, *e = memchr(a, '\n', n - *at);
    if (!e)
        return 0;
    *line = a;
    *len = (size_t)(e - a);
    *at = (size_t)(e - text) + 1;
    return 1;
}

/* The next line is exactly `want`. */
static int sd_dump_expect(const char *text, size_t n, size_t *at, const char *want)
{
    const char *l;
    size_t len;
    return sd_dump_line(text, n, at, &l, &len) && len == strlen(want) && memcmp(l, want, len) == 0;
}

/* The next line is one non-negative integer, into *v. */
static int sd_dump_count(const char *text, size_t n, size_t *at, long *v)
{
    const char *l;
    size_t len;
    if (!sd_dump_line(text, n, at, &l, &len) || len == 0 || len > 20)
        return 0;
    char num[24];
    memcpy(num, l, len);
    num[len] = '\0';
    char *end;
    errno = 0;
    *v = strtol(num, &end, 10);
    return *end == '\0' && errno == 0 && *v >= 0;
}

/* A block at *at, whole and in our layout: its step in *step, *at past it. */
static int sd_dump_block(const char *text, size_t n, size_t *at, long *step)
{
    long count;
    if (!sd_dump_expect(text, n, at, "ITEM: TIMESTEP") || !sd_dump_count(text, n, at, step) ||
        !sd_dump_expect(text, n, at, "ITEM: NUMBER OF ATOMS") || !sd_dump_count(text, n, at, &count))
        return 0;
    const char *l;
    size_t len;
    if (!sd_dump_line(text, n, at, &l, &len) || len < 16 || memcmp(l, "ITEM: BOX BOUNDS", 16) != 0)
        return 0;
    for (int k = 0; k < 3; ++k)
        if (!sd_dump_line(text, n, at, &l, &len))
            return 0;
    if (!sd_dump_expect(text, n, at, "ITEM: ATOMS " SD_DUMP_COLUMNS))
        return 0;
    for (long i = 0; i < count; ++i)
        if (!sd_dump_line(text, n, at, &l, &len))
            return 0;
    return 1;
}

long sd_dump_keep(const char *text, size_t n, long step, void *blocks)
{
    size_t keep = 0;
    long *count = blocks;
    *count = 0;
    for (;;) {
        size_t at = keep;
        long s;
        if (!text || !sd_dump_block(text, n, &at, &s) || s >= step)
            return (long)keep;
        keep = at;
        ++*count;
    }
}
