/* draw.c — a frame as a PNG (see render.h): orthographic camera, cells
 * painted back to front with back faces culled and Lambert shading, spheres
 * as shaded discs, walls as thin outlines behind them, a colour bar; cairo
 * does the rasterising and the PNG encoding.
 *
 * Camera: the direction c from the scene to the camera is
 * (cos el sin az, -cos el cos az, sin el) for azimuth az and elevation el
 * (front: az = el = 0, the camera on -y looking along +y); screen right
 * r = z x c normalised (x when looking straight down), up u = c x r. The
 * picture fits the particles (and the bounded walls too with fit_walls: a
 * plane's square stands for an infinite plane and is never fitted) with a
 * 4 % margin. A field's colour bar names its unit; a categorical field
 * (shape, material indices) gets a legend of names instead of a scale.
 */
#define _POSIX_C_SOURCE 200809L

#include "render/render.h"

#include "core/alloc.h"
#include "core/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SD_RENDER_PI 3.14159265358979323846

/* ---- defaults, views, colour maps (also without cairo) ------------------- */

sd_render_def sd_render_def_default(void)
{
    sd_render_def d;
    memset(&d, 0, sizeof d);
    d.width = 800;
    d.height = 600;
    d.azimuth = 30.0;
    d.elevation = 25.0;
    d.colormap = SD_CMAP_VIRIDIS;
    d.colorbar = 1;
    return d;
}

int sd_render_view(const char *name, double *az, double *el)
{
    if (!strcmp(name, "front")) {
        *az = 0.0;
        *el = 0.0;
    } else if (!strcmp(name, "top")) {
        *az = 0.0;
        *el = 90.0;
    } else if (!strcmp(name, "iso")) {
        *az = 45.0;
        *el = 35.26438968; /* atan(1/sqrt 2): the cube's diagonal points at the camera */
    } else
        return -1;
    return 0;
}

int sd_render_colormap_of(const char *name)
{
    static const char *names[SD_CMAP_COUNT] = {
#define SD_X_CMAP_NAME(e, name) name,
        SD_RENDER_COLORMAPS(SD_X_CMAP_NAME)
#undef SD_X_CMAP_NAME
    };
    for (int k = 0; k < SD_CMAP_COUNT; ++k)
        if (!strcmp(name, names[k]))
            return k;
    return -1;
}

void sd_render_colormap(int c, double t, double rgb[3])
{
    /* anchors at equal steps of t, linear between them: viridis (perceptually
     * uniform, dark blue to yellow), a diverging blue-grey-red, and grey */
    static const double viridis[9][3] = {{0.267, 0.005, 0.329}, {0.283, 0.141, 0.458}, {0.254, 0.265, 0.530},
                                         {0.207, 0.372, 0.553}, {0.164, 0.471, 0.558}, {0.128, 0.567, 0.551},
                                         {0.135, 0.659, 0.518}, {0.478, 0.821, 0.318}, {0.993, 0.906, 0.144}};
    static const double coolwarm[3][3] = {{0.230, 0.299, 0.754}, {0.865, 0.865, 0.865}, {0.706, 0.016, 0.150}};
    static const double gray[2][3] = {{0.1, 0.1, 0.1}, {0.95, 0.95, 0.95}};
    const double(*a)[3] = c == SD_CMAP_COOLWARM ? coolwarm : c == SD_CMAP_GRAY ? gray : viridis;
    int n = c == SD_CMAP_COOLWARM ? 3 : c == SD_CMAP_GRAY ? 2 : 9;
    if (!(t >= 0.0))
        t = 0.0;
    if (t > 1.0)
        t = 1.0;
    double x = t * (n - 1);
    int k = (int)x;
    if (k >= n - 1)
        k = n - 2;
    double f = x - k;
    for (int i = 0; i < 3; ++i)
        rgb[i] = a[k][i] + f * (a[k + 1][i] - a[k][i]);
}

#ifndef SHAPEDEM_HAVE_CAIRO

int sd_render_available(void) { return 0; }

sd_status sd_render_png(const sd_render_frame *f, const sd_render_def *d, const char *png, sd_error *err)
{
    (void)f;
    (void)d;
    return sd_error_set(err, SD_ERR_INPUT, png, 0, "",
                        "this shapedem was built without rendering (cairo was not found: install "
                        "libcairo2-dev, scripts/deps.sh does it, and build again)");
}

#else

#include <cairo.h>

int sd_render_available(void) { return 1; }

typedef struct sd_cam {
    double r[3], u[3], c[3]; /* screen right, up, toward the camera */
    double scale, ox, oy;    /* pixels per metre; screen offset */
} sd_cam;

static double sd_dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void sd_cam_axes(sd_cam *cam, double az_deg, double el_deg)
{
    double az = az_deg * SD_RENDER_PI / 180.0, el = el_deg * SD_RENDER_PI / 180.0;
    cam->c[0] = cos(el) * sin(az);
    cam->c[1] = -cos(el) * cos(az);
    cam->c[2] = sin(el);
    /* r = z x c; when c is (nearly) z, right is the azimuth's x direction */
    double rx = -cam->c[1], ry = cam->c[0];
    double rl = sqrt(rx * rx + ry * ry);
    if (rl < 1e-9) {
        rx = cos(az);
        ry = sin(az);
        rl = 1.0;
    }
    cam->r[0] = rx / rl;
    cam->r[1] = ry / rl;
    cam->r[2] = 0.0;
    /* u = c x r */
    cam->u[0] = cam->c[1] * cam->r[2] - cam->c[2] * cam->r[1];
    cam->u[1] = cam->c[2] * cam->r[0] - cam->c[0] * cam->r[2];
    cam->u[2] = cam->c[0] * cam->r[1] - cam->c[1] * cam->r[0];
}

static void sd_grow(double *lo, double *hi, double x)
{
    if (x < *lo)
        *lo = x;
    if (x > *hi)
        *hi = x;
}

/* Scale and offset that fit the particles (and the walls with fit_walls,
 * or when there are no particles) into the w x h box at (0, 0). */
static void sd_cam_fit(sd_cam *cam, const sd_render_frame *f, int fit_walls, double w, double h)
{
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (size_t k = 0; k < f->point_count; ++k) {
        sd_grow(&x0, &x1, sd_dot(f->points + 3 * k, cam->r));
        sd_grow(&y0, &y1, sd_dot(f->points + 3 * k, cam->u));
    }
    for (size_t k = 0; k < f->sphere_count; ++k) {
        double sx = sd_dot(f->centres + 3 * k, cam->r), sy = sd_dot(f->centres + 3 * k, cam->u), r = f->radii[k];
        sd_grow(&x0, &x1, sx - r);
        sd_grow(&x0, &x1, sx + r);
        sd_grow(&y0, &y1, sy - r);
        sd_grow(&y0, &y1, sy + r);
    }
    /* the bounded walls (boxes, drums, meshes); a plane's square only when
     * there is nothing else to frame: it is as big as the particles make it
     * and it stays wherever the plane has moved to */
    int nothing = !(x0 <= x1);
    for (int pass = 0; pass < 2; ++pass) {
        int64_t start = 0;
        for (size_t k = 0; (fit_walls || nothing) && k < f->wall_cell_count; ++k) {
            int64_t end = f->wall_ends[k];
            if (pass == 1 || !f->wall_fit || f->wall_fit[k])
                for (int64_t j = start; j < end; ++j) {
                    sd_grow(&x0, &x1, sd_dot(f->wall_points + 3 * f->wall_conn[j], cam->r));
                    sd_grow(&y0, &y1, sd_dot(f->wall_points + 3 * f->wall_conn[j], cam->u));
                }
            start = end;
        }
        if (x0 <= x1)
            break; /* else only planes: frame them after all */
    }
    if (!(x0 <= x1)) { /* nothing to draw */
        x0 = y0 = -1.0;
        x1 = y1 = 1.0;
    }
    double dx = x1 - x0, dy = y1 - y0, ext = fmax(dx, dy);
    if (!(ext > 0.0))
        ext = 1.0;
    if (dx < 1e-9 * ext)
        dx = 1e-9 * ext;
    if (dy < 1e-9 * ext)
        dy = 1e-9 * ext;
    cam->scale = 0.92 * fmin(w / dx, h / dy);
    cam->ox = 0.5 * w - cam->scale * 0.5 * (x0 + x1);
    cam->oy = 0.5 * h + cam->scale * 0.5 * (y0 + y1);
}

static void sd_cam_px(const sd_cam *cam, const double *p, double *x, double *y)
{
    *x = cam->ox + cam->scale * sd_dot(p, cam->r);
    *y = cam->oy - cam->scale * sd_dot(p, cam->u);
}

/* One thing to paint: a cell (k >= 0) or a sphere (-1 - k), at its depth
 * (distance along -c: larger is farther) and shade. */
typedef struct sd_item {
    double body;  /* depth of the particle's centre: particles are painted whole, far first */
    double depth; /* depth of the cell's centroid, within a (non-convex) composite */
    long k;
    double shade;
} sd_item;

static int sd_item_cmp(const void *a, const void *b)
{
    const sd_item *x = a, *y = b;
    if (x->body != y->body)
        return x->body > y->body ? -1 : 1; /* far first */
    if (x->depth != y->depth)
        return x->depth > y->depth ? -1 : 1;
    return x->k < y->k ? -1 : x->k > y->k; /* ties by index: the same pixels every time */
}

/* The colour position of value v: by category for a categorical field
 * (the same colour for an index in every frame), else linear in [lo, hi]. */
static double sd_norm01(const sd_render_frame *f, double lo, double hi, double v)
{
    if (f->categorical)
        return sd_render_category_t(f, v);
    return hi > lo ? (v - lo) / (hi - lo) : 0.5;
}

/* The title over the bar or legend: the field and its unit, "speed (m/s)". */
static void sd_draw_title(cairo_t *cr, const sd_render_frame *f, double x, double y)
{
    char title[96];
    snprintf(title, sizeof title, "%s%s%s%s", f->field, f->unit[0] ? " (" : "", f->unit, f->unit[0] ? ")" : "");
    cairo_move_to(cr, x, y);
    cairo_show_text(cr, title);
}

/* A categorical field's legend: a swatch and the name of each category the
 * frame holds, in index order, as many as fit (then "+ K more"). */
static void sd_draw_legend(cairo_t *cr, const sd_render_def *d, const sd_render_frame *f, int x0)
{
    double fs = fmax(9.0, fmin(13.0, d->height / 40.0)), row = fs + 6.0, top = 0.12 * d->height;
    double x = x0 + 8.0, y = top, bottom = 0.95 * d->height;
    size_t shown = 0, present = 0;
    for (size_t c = 0; c < f->category_count; ++c) {
        double v = (double)f->category_first + (double)c;
        int here = 0;
        for (size_t k = 0; k < f->sphere_count && !here; ++k)
            here = f->sphere_value[k] == v;
        for (size_t k = 0; k < f->cell_count && !here; ++k)
            here = f->cell_value[k] == v;
        if (!here)
            continue;
        present++;
        if (y + 2.0 * row > bottom)
            continue;
        double rgb[3];
        sd_render_colormap(d->colormap, sd_render_category_t(f, v), rgb);
        cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
        cairo_rectangle(cr, x, y, fs, fs);
        cairo_fill(cr);
        cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
        cairo_move_to(cr, x + fs + 5.0, y + fs - 1.0);
        cairo_show_text(cr, f->names[c]);
        y += row;
        shown++;
    }
    if (present > shown) {
        char more[48];
        snprintf(more, sizeof more, "+ %zu more", present - shown);
        cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
        cairo_move_to(cr, x, y + fs - 1.0);
        cairo_show_text(cr, more);
    }
}

static void sd_draw_colorbar(cairo_t *cr, const sd_render_def *d, const sd_render_frame *f, double lo, double hi,
                             int x0)
{
    int h = d->height;
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, fmax(9.0, fmin(13.0, h / 40.0)));
    double top = 0.12 * h, bot = 0.88 * h, bw = 16.0;
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    sd_draw_title(cr, f, x0 + 4.0, top - 10.0);
    if (f->categorical) { /* indices are names, not a scale */
        sd_draw_legend(cr, d, f, x0);
        return;
    }
    double x = x0 + 10.0;
    /* one linear gradient through 33 samples of the map: no seams between steps */
    cairo_pattern_t *g = cairo_pattern_create_linear(0.0, bot, 0.0, top);
    for (int k = 0; k <= 32; ++k) {
        double rgb[3];
        sd_render_colormap(d->colormap, k / 32.0, rgb);
        cairo_pattern_add_color_stop_rgb(g, k / 32.0, rgb[0], rgb[1], rgb[2]);
    }
    cairo_set_source(cr, g);
    cairo_rectangle(cr, x, top, bw, bot - top);
    cairo_fill(cr);
    cairo_pattern_destroy(g);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, x + 0.5, top + 0.5, bw - 1.0, bot - top - 1.0);
    cairo_stroke(cr);
    char buf[64];
    for (int k = 0; k <= 4; ++k) {
        double v = lo + (hi - lo) * k / 4.0, y = bot - (bot - top) * k / 4.0;
        snprintf(buf, sizeof buf, "%.3g", v);
        cairo_move_to(cr, x + bw + 4.0, y + 4.0);
        cairo_show_text(cr, buf);
    }
}

sd_status sd_render_png(const sd_render_frame *f, const sd_render_def *d, const char *png, sd_error *err)
{
    if (d->width < 16 || d->height < 16 || d->width > 16384 || d->height > 16384)
        return sd_error_set(err, SD_ERR_INPUT, png, 0, "--size", "the size must be 16 to 16384 pixels each way");
    int bar = d->colorbar ? (d->width >= 200 ? 90 : d->width / 3) : 0;
    sd_cam cam;
    sd_cam_axes(&cam, d->azimuth, d->elevation);
    sd_cam_fit(&cam, f, d->fit_walls, (double)(d->width - bar), (double)d->height);
    double lo = d->lo, hi = d->hi;
    if (!d->fixed_range)
        sd_render_frame_range(f, &lo, &hi);

    /* visible cells and the spheres, back to front */
    size_t n = f->cell_count + f->sphere_count;
    sd_item *items = sd_malloc((n ? n : 1) * sizeof *items);
    if (!items)
        return sd_error_set(err, SD_ERR_MEMORY, png, 0, "", "out of memory");
    /* light from the camera, raised and to the left */
    double L[3];
    for (int i = 0; i < 3; ++i)
        L[i] = cam.c[i] + 0.45 * cam.u[i] - 0.3 * cam.r[i];
    double ll = sqrt(sd_dot(L, L));
    for (int i = 0; i < 3; ++i)
        L[i] /= ll;
    size_t m = 0;
    int64_t start = 0;
    /* A particle's visible faces never hide one another when it is convex
     * (back faces are culled), so painting particles whole, far to near by
     * their centres, is right wherever particles do not interpenetrate;
     * sorting single triangles across particles is not (a big face's
     * centroid can be nearer than a small particle in front of it). */
    double body = 0.0;
    for (size_t k = 0; k < f->cell_count; ++k) {
        if (k == 0 || f->cell_id[k] != f->cell_id[k - 1]) { /* a new particle: its centre's depth */
            double sum = 0.0;
            size_t cnt = 0;
            int64_t b0 = start;
            for (size_t j = k; j < f->cell_count && f->cell_id[j] == f->cell_id[k]; ++j) {
                for (int64_t q = b0; q < f->ends[j]; ++q, ++cnt)
                    sum += -sd_dot(f->points + 3 * f->conn[q], cam.c);
                b0 = f->ends[j];
            }
            body = cnt ? sum / (double)cnt : 0.0;
        }
        int64_t end = f->ends[k];
        if (end - start >= 3) {
            /* Newell normal (any polygon), centroid depth */
            double nrm[3] = {0, 0, 0}, cen[3] = {0, 0, 0};
            for (int64_t j = start; j < end; ++j) {
                const double *a = f->points + 3 * f->conn[j];
                const double *b = f->points + 3 * f->conn[j + 1 < end ? j + 1 : start];
                nrm[0] += (a[1] - b[1]) * (a[2] + b[2]);
                nrm[1] += (a[2] - b[2]) * (a[0] + b[0]);
                nrm[2] += (a[0] - b[0]) * (a[1] + b[1]);
                for (int i = 0; i < 3; ++i)
                    cen[i] += a[i];
            }
            double nl = sqrt(sd_dot(nrm, nrm));
            if (nl > 0.0 && sd_dot(nrm, cam.c) > 0.0) { /* faces the camera */
                double shade = f->planar ? 1.0 : 0.3 + 0.7 * fmax(0.0, sd_dot(nrm, L) / nl);
                items[m].body = body;
                items[m].depth = -sd_dot(cen, cam.c) / (double)(end - start);
                items[m].k = (long)k;
                items[m].shade = shade;
                ++m;
            }
        }
        start = end;
    }
    for (size_t k = 0; k < f->sphere_count; ++k) {
        items[m].body = items[m].depth = -sd_dot(f->centres + 3 * k, cam.c);
        items[m].k = -1 - (long)k;
        items[m].shade = 1.0;
        ++m;
    }
    qsort(items, m, sizeof *items, sd_item_cmp);

    cairo_surface_t *surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, d->width, d->height);
    cairo_t *cr = cairo_create(surf);
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_paint(cr);
    cairo_rectangle(cr, 0, 0, d->width - bar, d->height);
    cairo_clip(cr);

    /* walls: thin grey outlines behind the particles */
    cairo_set_line_width(cr, 1.0);
    cairo_set_source_rgba(cr, 0.35, 0.35, 0.35, 0.6);
    start = 0;
    for (size_t k = 0; k < f->wall_cell_count; ++k) {
        int64_t end = f->wall_ends[k];
        for (int64_t j = start; j < end; ++j) {
            double x, y;
            sd_cam_px(&cam, f->wall_points + 3 * f->wall_conn[j], &x, &y);
            if (j == start)
                cairo_move_to(cr, x, y);
            else
                cairo_line_to(cr, x, y);
        }
        if (end > start)
            cairo_close_path(cr);
        start = end;
    }
    cairo_stroke(cr);

    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    for (size_t q = 0; q < m; ++q) {
        double rgb[3];
        if (items[q].k >= 0) {
            size_t k = (size_t)items[q].k;
            int64_t s0 = k ? f->ends[k - 1] : 0, s1 = f->ends[k];
            sd_render_colormap(d->colormap, sd_norm01(f, lo, hi, f->cell_value[k]), rgb);
            for (int64_t j = s0; j < s1; ++j) {
                double x, y;
                sd_cam_px(&cam, f->points + 3 * f->conn[j], &x, &y);
                if (j == s0)
                    cairo_move_to(cr, x, y);
                else
                    cairo_line_to(cr, x, y);
            }
            cairo_close_path(cr);
            double sh = items[q].shade;
            cairo_set_source_rgb(cr, rgb[0] * sh, rgb[1] * sh, rgb[2] * sh);
            /* a stroke of the same colour closes the hairline seams that
             * antialiasing leaves between neighbouring triangles */
            cairo_fill_preserve(cr);
            cairo_set_line_width(cr, 0.7);
            cairo_stroke(cr);
            if (f->planar) { /* 2D outlines: a dark rim so touching grains stay apart */
                for (int64_t j = s0; j < s1; ++j) {
                    double x, y;
                    sd_cam_px(&cam, f->points + 3 * f->conn[j], &x, &y);
                    if (j == s0)
                        cairo_move_to(cr, x, y);
                    else
                        cairo_line_to(cr, x, y);
                }
                cairo_close_path(cr);
                cairo_set_source_rgba(cr, 0.0, 0.0, 0.0, 0.5);
                cairo_set_line_width(cr, 0.8);
                cairo_stroke(cr);
            }
        } else {
            size_t k = (size_t)(-1 - items[q].k);
            double x, y, r = cam.scale * f->radii[k];
            sd_cam_px(&cam, f->centres + 3 * k, &x, &y);
            sd_render_colormap(d->colormap, sd_norm01(f, lo, hi, f->sphere_value[k]), rgb);
            /* a sphere lit like the cells: bright toward the light, darker at the rim */
            cairo_pattern_t *pat = cairo_pattern_create_radial(x - 0.3 * r, y - 0.35 * r, 0.05 * r, x, y, r);
            cairo_pattern_add_color_stop_rgb(pat, 0.0, fmin(1.0, rgb[0] * 1.15 + 0.08), fmin(1.0, rgb[1] * 1.15 + 0.08),
                                             fmin(1.0, rgb[2] * 1.15 + 0.08));
            cairo_pattern_add_color_stop_rgb(pat, 1.0, rgb[0] * 0.45, rgb[1] * 0.45, rgb[2] * 0.45);
            if (f->planar) /* discs of a planar run are flat, as its outlines */
                cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
            else
                cairo_set_source(cr, pat);
            cairo_arc(cr, x, y, r, 0.0, 2.0 * SD_RENDER_PI);
            cairo_fill(cr);
            cairo_pattern_destroy(pat);
        }
    }
    sd_free(items);
    cairo_reset_clip(cr);
    if (bar)
        sd_draw_colorbar(cr, d, f, lo, hi, d->width - bar);
    cairo_destroy(cr);

    char tmp[SD_RENDER_PATH_MAX + 16];
    snprintf(tmp, sizeof tmp, "%s.tmp", png);
    cairo_surface_flush(surf);
    cairo_status_t cs = cairo_surface_status(surf);
    if (cs == CAIRO_STATUS_SUCCESS)
        cs = cairo_surface_write_to_png(surf, tmp);
    cairo_surface_destroy(surf);
    if (cs != CAIRO_STATUS_SUCCESS) {
        remove(tmp);
        return sd_error_set(err, SD_ERR_IO, png, 0, "", "cannot write the picture: %s", cairo_status_to_string(cs));
    }
    if (rename(tmp, png) != 0) {
        remove(tmp);
        return sd_error_set(err, SD_ERR_IO, png, 0, "", "cannot write the picture (rename failed)");
    }
    return SD_OK;
}

#endif
