/* servo.c — moving walls: prescribed motion (loading) and servo control
 * (confining pressure), and the biaxial state read from the four walls of
 * a 2D box (seed 002 §3.2).
 *
 * Invariants: walls move only between steps, at the same time as the
 * particles drift (velocity Verlet: positions at t + dt), with the
 * velocity decided from the wall force of the last evaluation; the sums
 * over wall contacts run serially in pair order, so the result is the same
 * bits for any thread count (DESIGN.md rule 4). A wall that moved more than
 * half the skin since the last rebuild forces a rebuild (world/rebuild.c), so the
 * particle-wall candidate list stays complete.
 */
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "dynamics/servo.h"
#include "world/mesh.h"
#include "world/world.h"

#define SD_COOKIE 0x5D5D

sd_wall_motion_def sd_wall_motion_def_default(void)
{
    sd_wall_motion_def d;
    memset(&d, 0, sizeof d);
    d.move_end = -1; /* never ends */
    d.servo_end = -1;
    d.cookie = SD_COOKIE;
    return d;
}

static int sd_finite3(sd_v3d v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

static sd_real sd_wall_span(const sd_world *w, size_t k);

sd_status sd_world_set_wall_motion(sd_world *w, int wall, const sd_wall_motion_def *d, sd_error *err)
{
    if (!w)
        return sd_error_null(err, "sd_world_set_wall_motion", "world");
    if (!d || d->cookie != SD_COOKIE)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "motion",
                            "wall motion def not made by sd_wall_motion_def_default");
    if (wall < 0 || (size_t)wall >= w->wall_count)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "motion", "unknown wall index %d", wall);
    sd_wall *wl = &w->walls[wall];
    if (!sd_finite3(d->velocity) || !isfinite(d->move_start) || !isfinite(d->move_end) || !isfinite(d->servo_start) ||
        !isfinite(d->servo_end))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "velocity", "wall '%s': velocity and times must be finite",
                            wl->name);
    if (w->dim2 && d->velocity.z != 0)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "velocity", "wall '%s': dimension 2 needs a velocity with z = 0",
                            wl->name);
    if (!(d->servo_stress >= 0) || !(d->servo_gain >= 0) || !(d->servo_max_speed >= 0) || !isfinite(d->servo_stress) ||
        !isfinite(d->servo_gain) || !isfinite(d->servo_max_speed))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "servo_stress",
                            "wall '%s': servo stress, gain and maximum speed must be finite and >= 0", wl->name);
    if (d->servo_stress > 0 && wl->kind != SD_WALL_PLANE)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "servo_stress",
                            "wall '%s': only plane walls can be servo-controlled", wl->name);
    if (d->servo_stress > 0 && !(sd_wall_span(w, (size_t)wall) > 0))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "servo_stress",
                            "wall '%s': a servo wall needs %s of opposite plane walls across it (their distance "
                            "is its contact %s); add them before setting the motion",
                            wl->name, w->dim2 ? "a pair" : "two pairs", w->dim2 ? "length" : "area");
    wl->motion = *d;
    wl->moving = 1;
    wl->velocity = sd_v3_zero();
    wl->servo_i = SD_R(0.0);
    w->walls_moving = 1;
    return SD_OK;
}

static int sd_window_open(double t, double start, double end)
{
    return t >= start && (end <= start || t < end);
}

/* Contact length (2D) or area (3D) of plane wall k: the distance between
 * each pair of opposite plane walls perpendicular to it. Returns 0 when the
 * walls that bound it are missing. */
static sd_real sd_wall_span(const sd_world *w, size_t k)
{
    const sd_wall *a = &w->walls[k];
    sd_real area = SD_R(1.0); /* 2D: per unit thickness (1 m) */
    int found = 0;
    for (size_t i = 0; i < w->wall_count; ++i) {
        const sd_wall *b = &w->walls[i];
        if (i == k || b->kind != SD_WALL_PLANE || sd_fabs(sd_v3_dot(a->normal, b->normal)) > SD_R(1e-9))
            continue;
        for (size_t j = i + 1; j < w->wall_count; ++j) {
            const sd_wall *c = &w->walls[j];
            if (j == k || c->kind != SD_WALL_PLANE || sd_v3_dot(b->normal, c->normal) > SD_R(-1.0) + SD_R(1e-9))
                continue;
            area *= sd_v3_dot(sd_v3_sub(c->point, b->point), b->normal);
            ++found;
        }
    }
    return found == (w->dim2 ? 1 : 2) ? area : SD_R(0.0);
}

/* Normal stiffness of one wall contact (N/m): k_n of a law with a constant
 * one (the law table's SD_LAW_IS_LINEAR), else the tangent stiffness
 * 2 Y* sqrt(R* delta) of Hertz (an estimate for the volume laws). */
static sd_real sd_contact_stiffness(const sd_pair_params *prm, sd_real r, sd_real delta)
{
    if (sd_law_traits(prm->law) & SD_LAW_IS_LINEAR)
        return prm->kn;
    return SD_R(2.0) * prm->y_star * sd_sqrt(r * delta);
}

/* A decomposed run (w->comm): each rank holds the wall pairs of its own
 * particles, so a servo wall's force and contact stiffness are the sums
 * of every rank's; they are taken over the ranks in the order of the wall
 * pairs' keys (the comm's wall_sums), the same bits on any rank count,
 * and every rank moves the wall alike. Other walls keep their own totals. */
static sd_status sd_walls_servo_sums(sd_world *w, sd_error *err)
{
    int any = 0;
    for (size_t k = 0; k < w->wall_count; ++k)
        any |= w->walls[k].moving && w->walls[k].motion.servo_stress > 0;
    if (!any)
        return SD_OK;
    const sd_wall_pair_list *l = &w->wpairs;
    size_t nm = w->material_count, n = 0;
    sd_wall_pair_key *key = sd_malloc((l->n ? l->n : 1) * sizeof *key);
    double *v = sd_malloc((l->n ? l->n : 1) * 4 * sizeof *v);
    double *out = sd_malloc((w->wall_count ? w->wall_count : 1) * 4 * sizeof *out);
    sd_status st = key && v && out ? SD_OK : SD_ERR_MEMORY;
    for (size_t e = 0; st == SD_OK && e < l->n; ++e) {
        const sd_wall *wl = &w->walls[l->wall[e]];
        if (l->delta[e] <= 0 || !(wl->moving && wl->motion.servo_stress > 0))
            continue;
        uint32_t i = l->i[e];
        const sd_pair_params *prm = &w->mix[(size_t)w->p.material[i] * nm + (size_t)wl->material];
        key[n] = l->key[e];
        v[4 * n] = -(double)l->f[e].x; /* the wall feels the opposite of the particle's force */
        v[4 * n + 1] = -(double)l->f[e].y;
        v[4 * n + 2] = -(double)l->f[e].z;
        v[4 * n + 3] = (double)sd_contact_stiffness(prm, w->p.radius[i], l->delta[e]);
        ++n;
    }
    /* collective: every rank takes part, even one without memory */
    sd_status cst = w->comm->wall_sums(w->comm_ctx, st == SD_OK ? n : 0, key, v, w->wall_count, out, err);
    if (st == SD_OK && cst == SD_OK)
        for (size_t k = 0; k < w->wall_count; ++k) {
            sd_wall *wl = &w->walls[k];
            if (!(wl->moving && wl->motion.servo_stress > 0))
                continue;
            wl->force = sd_v3((sd_real)out[4 * k], (sd_real)out[4 * k + 1], (sd_real)out[4 * k + 2]);
            wl->stiffness = (sd_real)out[4 * k + 3];
        }
    sd_free(key);
    sd_free(v);
    sd_free(out);
    if (st != SD_OK)
        return sd_error_set(err, st, "", 0, "", "out of memory summing the servo walls' forces over the ranks");
    return cst;
}

sd_status sd_world_walls_drift(sd_world *w, double t, sd_error *err)
{
    if (!w->walls_moving)
        return SD_OK;
    /* mesh walls: pose and velocity are functions of time (world/mesh.c) */
    sd_world_meshes_pose(w, t + (double)w->dt);
    sd_world_drums_spin(w, t + (double)w->dt); /* a drum's spin-up, as a mesh's ramp */
    const sd_wall_pair_list *l = &w->wpairs;
    size_t nm = w->material_count;
    for (size_t k = 0; k < w->wall_count; ++k)
        w->walls[k].stiffness = SD_R(0.0);
    /* in gather order (particle by particle, wall by wall): the sums do
     * not depend on the kind segments of the list. A world changed since
     * its last rebuild (dirty: particles inserted or removed) has stale
     * gather lists (a removal compacts the wall pairs under them: entries
     * past the list's end), which its next step rebuilds after this drift:
     * then the list's own order, which a restore of that state reads too
     * (world/snapshot.c saves no gather lists for a dirty world) */
    for (size_t g = 0; g < l->n; ++g) {
        size_t e = w->dirty ? g : l->gidx[g];
        if (l->delta[e] <= 0)
            continue;
        sd_wall *wl = &w->walls[l->wall[e]];
        uint32_t i = l->i[e];
        const sd_pair_params *prm = &w->mix[(size_t)w->p.material[i] * nm + (size_t)wl->material];
        wl->stiffness += sd_contact_stiffness(prm, w->p.radius[i], l->delta[e]);
    }
    if (w->comm) {
        sd_status sst = sd_walls_servo_sums(w, err);
        if (sst != SD_OK)
            return sst;
    }
    sd_real dt = w->dt;
    for (size_t k = 0; k < w->wall_count; ++k) {
        sd_wall *wl = &w->walls[k];
        if (!wl->moving)
            continue;
        const sd_wall_motion_def *m = &wl->motion;
        sd_vec3 v = sd_v3_zero();
        int servo = m->servo_stress > 0 && sd_window_open(t, m->servo_start, m->servo_end);
        if (!servo)
            wl->servo_i = SD_R(0.0); /* the integral starts afresh with each servo window */
        if (servo) {
            sd_real area = sd_wall_span(w, k);
            if (!(area > 0))
                return sd_error_set(err, SD_ERR_INPUT, "", 0, "servo_stress",
                                    "wall '%s': a servo wall needs %s pair%s of opposite plane walls across it "
                                    "to measure its contact %s",
                                    wl->name, w->dim2 ? "one" : "two", w->dim2 ? "" : "s", w->dim2 ? "length" : "area");
            sd_real stress = -sd_v3_dot(wl->force, wl->normal) / area;
            sd_real gain = m->servo_gain > 0 ? (sd_real)m->servo_gain : sd_servo_auto_gain(area, wl->stiffness, dt);
            /* without a cap the wall may move a tenth of the skin per step */
            sd_real vmax = m->servo_max_speed > 0 ? (sd_real)m->servo_max_speed : SD_R(0.1) * w->skin / dt;
            v = sd_v3_scale(wl->normal, sd_servo_speed(stress, (sd_real)m->servo_stress, gain, vmax, &wl->servo_i));
        } else if (sd_window_open(t, m->move_start, m->move_end)) {
            v = sd_v3((sd_real)m->velocity.x, (sd_real)m->velocity.y, (sd_real)m->velocity.z);
            /* the strains of the biaxial output count from the start of loading */
            if (w->biaxial_ref.z == 0 && sd_v3_norm2(v) > 0)
                (void)sd_world_biaxial_reference(w);
        }
        wl->velocity = v;
        wl->point = sd_v3_madd(wl->point, dt, v);
        if (wl->kind == SD_WALL_BOX) {
            wl->lo = sd_v3_madd(wl->lo, dt, v);
            wl->hi = sd_v3_madd(wl->hi, dt, v);
        }
    }
    return SD_OK;
}

int sd_world_walls_moved(const sd_world *w)
{
    if (!w->walls_moving)
        return 0;
    sd_real lim2 = sd_sq(SD_R(0.5) * w->skin);
    for (size_t k = 0; k < w->wall_count; ++k)
        if (w->walls[k].kind != SD_WALL_MESH && sd_v3_norm2(sd_v3_sub(w->walls[k].point, w->walls[k].point_ref)) > lim2)
            return 1;
    return sd_world_meshes_moved(w, SD_R(0.5) * w->skin);
}

void sd_world_walls_mark(sd_world *w)
{
    for (size_t k = 0; k < w->wall_count; ++k)
        w->walls[k].point_ref = w->walls[k].point;
    sd_world_meshes_mark(w);
}

/* ---- biaxial box -------------------------------------------------------------- */

/* Indices of the plane walls with normals +x, -x, +y, -y, or 0 when one is
 * missing. */
static int sd_biaxial_walls(const sd_world *w, int idx[4])
{
    const sd_real tol = SD_R(1.0) - SD_R(1e-9);
    idx[0] = idx[1] = idx[2] = idx[3] = -1;
    for (size_t k = 0; k < w->wall_count; ++k) {
        const sd_wall *wl = &w->walls[k];
        if (wl->kind != SD_WALL_PLANE)
            continue;
        if (wl->normal.x > tol && idx[0] < 0)
            idx[0] = (int)k;
        else if (wl->normal.x < -tol && idx[1] < 0)
            idx[1] = (int)k;
        else if (wl->normal.y > tol && idx[2] < 0)
            idx[2] = (int)k;
        else if (wl->normal.y < -tol && idx[3] < 0)
            idx[3] = (int)k;
    }
    return idx[0] >= 0 && idx[1] >= 0 && idx[2] >= 0 && idx[3] >= 0;
}

sd_status sd_world_biaxial_reference(sd_world *w)
{
    int idx[4];
    if (!w || !w->dim2 || !sd_biaxial_walls(w, idx))
        return SD_ERR_INPUT;
    w->biaxial_ref = sd_v3(w->walls[idx[1]].point.x - w->walls[idx[0]].point.x,
                           w->walls[idx[3]].point.y - w->walls[idx[2]].point.y, SD_R(1.0));
    return SD_OK;
}

sd_status sd_world_biaxial(const sd_world *w, sd_biaxial *out)
{
    int idx[4];
    if (!out)
        return SD_ERR_INPUT;
    memset(out, 0, sizeof *out);
    if (!w || !w->dim2 || !sd_biaxial_walls(w, idx))
        return SD_ERR_INPUT;
    const sd_wall *xl = &w->walls[idx[0]], *xr = &w->walls[idx[1]], *yb = &w->walls[idx[2]], *yt = &w->walls[idx[3]];
    double width = (double)(xr->point.x - xl->point.x), height = (double)(yt->point.y - yb->point.y);
    out->width = width;
    out->height = height;
    /* compression positive: the particles push each wall against its normal */
    double fx = -0.5 * (double)(sd_v3_dot(xl->force, xl->normal) + sd_v3_dot(xr->force, xr->normal));
    double fy = -0.5 * (double)(sd_v3_dot(yb->force, yb->normal) + sd_v3_dot(yt->force, yt->normal));
    out->sigma_xx = height > 0 ? fx / height : 0;
    out->sigma_yy = width > 0 ? fy / width : 0;
    double sum = out->sigma_xx + out->sigma_yy;
    out->stress_ratio = sum != 0 ? (out->sigma_yy - out->sigma_xx) / sum : 0;
    out->has_reference = w->biaxial_ref.z != 0;
    out->width0 = out->has_reference ? (double)w->biaxial_ref.x : width;
    out->height0 = out->has_reference ? (double)w->biaxial_ref.y : height;
    out->strain_axial = (out->height0 - height) / out->height0;
    out->strain_lateral = (out->width0 - width) / out->width0;
    out->strain_volumetric = 1.0 - width * height / (out->width0 * out->height0);
    return SD_OK;
}
