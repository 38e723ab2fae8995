/* output.c — the run output module: directory safety, VTK frames that
 * decode back to the world's state, frames.pvd, stats.csv and summary.txt.
 *
 * The .vtu/.vtp files are checked by a small reader here (header attributes,
 * the appended raw block with UInt64 little-endian headers), not by VTK, so
 * the suite needs no VTK installation.
 */
#define _POSIX_C_SOURCE 200809L

#include "io/output.h"

#include <dirent.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int failures;

#define CHECK(cond)                                                                                \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);               \
            ++failures;                                                                            \
        }                                                                                          \
    } while (0)

#define CHECK_OK(status, err)                                                                      \
    do {                                                                                           \
        sd_status s_ = (status);                                                                   \
        if (s_ != SD_OK) {                                                                         \
            char buf_[1024];                                                                       \
            sd_error_format(&(err), buf_, sizeof buf_);                                            \
            fprintf(stderr, "%s:%d: %s returned %d: %s\n", __FILE__, __LINE__, #status, (int)s_,   \
                    buf_);                                                                         \
            ++failures;                                                                            \
        }                                                                                          \
    } while (0)

/* ---- small file helpers ---------------------------------------------------- */

static char *path_join(char *buf, size_t size, const char *dir, const char *name)
{
    snprintf(buf, size, "%s/%s", dir, name);
    return buf;
}

/* Whole file in malloc'd memory (NUL-terminated), size in *n; NULL if absent. */
static char *read_all(const char *path, size_t *n)
{
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return NULL;
    fseek(fp, 0, SEEK_END);
    long len = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    char *buf = malloc((size_t)len + 1);
    size_t got = fread(buf, 1, (size_t)len, fp);
    fclose(fp);
    buf[got] = '\0';
    if (n)
        *n = got;
    return buf;
}

static int file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

static void write_text(const char *path, const char *text)
{
    FILE *fp = fopen(path, "w");
    if (fp) {
        fputs(text, fp);
        fclose(fp);
    }
}

static int count_matching(const char *dir, const char *prefix, const char *suffix)
{
    DIR *d = opendir(dir);
    int n = 0;
    if (!d)
        return -1;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        size_t len = strlen(e->d_name), a = strlen(prefix), b = strlen(suffix);
        if (len >= a + b && strncmp(e->d_name, prefix, a) == 0 &&
            strcmp(e->d_name + len - b, suffix) == 0)
            ++n;
    }
    closedir(d);
    return n;
}

static void remove_tree(const char *path)
{
    struct stat st;
    if (lstat(path, &st) != 0)
        return;
    if (S_ISDIR(st.st_mode)) {
        DIR *d = opendir(path);
        if (d) {
            struct dirent *e;
            while ((e = readdir(d)) != NULL) {
                if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
                    continue;
                char child[4096];
                remove_tree(path_join(child, sizeof child, path, e->d_name));
            }
            closedir(d);
        }
        rmdir(path);
    } else {
        unlink(path);
    }
}

/* ---- a minimal VTK XML appended-data reader ---------------------------------- */

/* Value of attribute attr in the tag around position at (the tag that
 * contains it), copied to out; returns 1 if found. */
static int tag_attr(const char *doc, const char *at, const char *attr, char *out, size_t size)
{
    const char *start = at;
    while (start > doc && *start != '<')
        --start;
    const char *end = strchr(at, '>');
    if (!end)
        return 0;
    char key[64];
    snprintf(key, sizeof key, " %s=\"", attr);
    const char *p = strstr(start, key);
    if (!p || p > end)
        return 0;
    p += strlen(key);
    const char *q = strchr(p, '"');
    if (!q || q > end || (size_t)(q - p) >= size)
        return 0;
    memcpy(out, p, (size_t)(q - p));
    out[q - p] = '\0';
    return 1;
}

static long first_tag_long(const char *doc, const char *tag, const char *attr)
{
    const char *p = strstr(doc, tag);
    char v[64];
    if (!p || !tag_attr(doc, p + 1, attr, v, sizeof v))
        return -1;
    return atol(v);
}

static uint64_t le_u64(const unsigned char *p)
{
    uint64_t v = 0;
    for (int k = 7; k >= 0; --k)
        v = (v << 8) | p[k];
    return v;
}

static double le_f64(const unsigned char *p)
{
    uint64_t u = le_u64(p);
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

typedef struct vtk_file {
    char *doc;
    size_t size;
    const unsigned char *data; /* byte after the '_' */
    size_t data_size;          /* bytes up to the closing newline */
} vtk_file;

static int vtk_load(vtk_file *f, const char *path)
{
    f->doc = read_all(path, &f->size);
    if (!f->doc)
        return 0;
    const char *ap = strstr(f->doc, "<AppendedData encoding=\"raw\">");
    if (!ap)
        return 0;
    const char *us = strchr(ap, '_');
    if (!us)
        return 0;
    f->data = (const unsigned char *)us + 1;
    const char *tail = "\n  </AppendedData>\n</VTKFile>\n";
    size_t tl = strlen(tail);
    if (f->size < tl || memcmp(f->doc + f->size - tl, tail, tl) != 0)
        return 0;
    f->data_size = (size_t)((f->doc + f->size - tl) - (const char *)f->data);
    return 1;
}

/* The block of the DataArray named name: values and byte count. */
static const unsigned char *vtk_array(const vtk_file *f, const char *name, uint64_t *bytes,
                                      int *components)
{
    char key[96];
    snprintf(key, sizeof key, "Name=\"%s\"", name);
    const char *p = strstr(f->doc, key);
    char v[64];
    if (!p || !tag_attr(f->doc, p, "offset", v, sizeof v))
        return NULL;
    uint64_t off = strtoull(v, NULL, 10);
    *components = tag_attr(f->doc, p, "NumberOfComponents", v, sizeof v) ? atoi(v) : 1;
    if (off + 8 > f->data_size)
        return NULL;
    *bytes = le_u64(f->data + off);
    if (off + 8 + *bytes > f->data_size)
        return NULL;
    return f->data + off + 8;
}

/* Every declared array's block lies inside the appended data and the blocks
 * tile it exactly, in declaration order. */
static int vtk_blocks_tile(const vtk_file *f)
{
    uint64_t expect = 0;
    const char *p = f->doc;
    const char *stop = (const char *)f->data;
    while ((p = strstr(p, "<DataArray")) != NULL && p < stop) {
        char v[64];
        if (!tag_attr(f->doc, p + 1, "offset", v, sizeof v))
            return 0;
        uint64_t off = strtoull(v, NULL, 10);
        if (off != expect || off + 8 > f->data_size)
            return 0;
        expect = off + 8 + le_u64(f->data + off);
        ++p;
    }
    return expect == f->data_size;
}

/* Checks the frame against the world's current state, particle by particle. */
static void check_particle_frame(const char *path, const sd_world *w)
{
    size_t n = sd_world_particle_count(w);
    printf("  checking %s: header, block layout, ids and positions of %zu particles\n", path, n);
    vtk_file f;
    memset(&f, 0, sizeof f);
    CHECK(vtk_load(&f, path));
    if (!f.data) {
        free(f.doc);
        return;
    }
    CHECK(strstr(f.doc, "type=\"UnstructuredGrid\"") != NULL);
    CHECK(strstr(f.doc, "byte_order=\"LittleEndian\"") != NULL);
    CHECK(strstr(f.doc, "header_type=\"UInt64\"") != NULL);
    CHECK(first_tag_long(f.doc, "<Piece", "NumberOfPoints") == (long)n);
    CHECK(first_tag_long(f.doc, "<Piece", "NumberOfCells") == (long)n);
    CHECK(vtk_blocks_tile(&f));

    uint64_t bytes = 0;
    int comps = 0;
    const unsigned char *ids = vtk_array(&f, "id", &bytes, &comps);
    CHECK(ids != NULL && bytes == 8 * n && comps == 1);
    const unsigned char *pos = vtk_array(&f, "position", &bytes, &comps);
    CHECK(pos != NULL && bytes == 24 * n && comps == 3);
    const unsigned char *rad = vtk_array(&f, "radius", &bytes, &comps);
    CHECK(rad != NULL && bytes == 8 * n);
    const unsigned char *ori = vtk_array(&f, "orientation", &bytes, &comps);
    CHECK(ori != NULL && bytes == 32 * n && comps == 4);
    const unsigned char *mat = vtk_array(&f, "material", &bytes, &comps);
    CHECK(mat != NULL && bytes == 4 * n);
    const unsigned char *types = vtk_array(&f, "types", &bytes, &comps);
    CHECK(types != NULL && bytes == n);
    const unsigned char *offs = vtk_array(&f, "offsets", &bytes, &comps);
    CHECK(offs != NULL && bytes == 8 * n);
    if (ids && pos && rad && ori && types && offs) {
        int bad = 0;
        for (size_t i = 0; i < n; ++i) {
            sd_particle_state p;
            if (sd_world_get_particle(w, i, &p) != SD_OK) {
                ++bad;
                continue;
            }
            bad += le_u64(ids + 8 * i) != p.id;
            bad += le_f64(pos + 24 * i) != p.position.x;
            bad += le_f64(pos + 24 * i + 8) != p.position.y;
            bad += le_f64(pos + 24 * i + 16) != p.position.z;
            bad += le_f64(rad + 8 * i) != p.radius;
            bad += le_f64(ori + 32 * i) != p.quat[0];
            bad += types[i] != 1;               /* VTK_VERTEX */
            bad += le_u64(offs + 8 * i) != i + 1;
        }
        CHECK(bad == 0);
    }
    free(f.doc);
}

static void check_wall_frame(const char *path, long polys)
{
    printf("  checking %s: PolyData with %ld quads\n", path, polys);
    vtk_file f;
    memset(&f, 0, sizeof f);
    CHECK(vtk_load(&f, path));
    if (!f.data) {
        free(f.doc);
        return;
    }
    CHECK(strstr(f.doc, "type=\"PolyData\"") != NULL);
    CHECK(first_tag_long(f.doc, "<Piece", "NumberOfPolys") == polys);
    CHECK(first_tag_long(f.doc, "<Piece", "NumberOfPoints") == 4 * polys);
    CHECK(vtk_blocks_tile(&f));
    uint64_t bytes = 0;
    int comps = 0;
    const unsigned char *wall = vtk_array(&f, "wall", &bytes, &comps);
    CHECK(wall != NULL && bytes == 4 * (uint64_t)polys);
    const unsigned char *force = vtk_array(&f, "force", &bytes, &comps);
    CHECK(force != NULL && bytes == 24 * (uint64_t)polys && comps == 3);
    free(f.doc);
}

/* Number of comma-separated fields in one line. */
static int csv_fields(const char *line, const char *end)
{
    int n = 1;
    for (const char *p = line; p < end; ++p)
        n += *p == ',';
    return n;
}

/* ---- the world ---------------------------------------------------------------- */

static sd_world *make_world(size_t nspheres, int with_walls)
{
    sd_error err;
    sd_world_def d = sd_world_def_default();
    d.dt = 1e-5;
    sd_world *w = NULL;
    CHECK_OK(sd_world_create(&d, &w, &err), err);
    if (!w)
        return NULL;
    sd_material_def m = sd_material_def_default();
    m.youngs_modulus = 1e7; /* Pa; the default law (Hertz-Mindlin) needs it */
    int mat = sd_world_add_material(w, &m, &err);
    CHECK(mat >= 0);
    sd_sphere_def s[8];
    memset(s, 0, sizeof s);
    for (size_t i = 0; i < nspheres && i < 8; ++i) {
        s[i].position.x = 0.25 + 0.5 * (double)(i & 1);
        s[i].position.y = 0.25 + 0.5 * (double)((i >> 1) & 1);
        s[i].position.z = 0.25 + 0.5 * (double)((i >> 2) & 1);
        s[i].velocity.x = 0.1 * (double)i;
        s[i].angular_velocity.z = 1.0;
        s[i].radius = 0.05 + 0.001 * (double)i;
        s[i].material = mat;
    }
    if (nspheres)
        CHECK_OK(sd_world_add_spheres(w, nspheres, s, &err), err);
    if (with_walls) {
        sd_v3d p = {0.0, 0.0, 0.0}, n = {0.0, 0.0, 1.0};
        CHECK(sd_world_add_plane(w, "floor", p, n, mat, &err) == 0);
        sd_v3d lo = {0.0, 0.0, 0.0}, hi = {1.0, 1.0, 1.5};
        /* not an identifier: its stats columns are named wall1_* */
        CHECK(sd_world_add_box(w, "bin box", lo, hi, SD_BOX_ZMAX, mat, &err) == 1);
    }
    return w;
}

/* ---- the tests ------------------------------------------------------------------ */

static void test_foreign_directory(const char *root)
{
    printf("checking: a non-empty directory without the marker is refused and left untouched\n");
    char dir[1024], mine[1100], marker[1100];
    path_join(dir, sizeof dir, root, "foreign");
    mkdir(dir, 0777);
    path_join(mine, sizeof mine, dir, "particles_000000.vtu"); /* even under one of our names */
    write_text(mine, "precious user data\n");

    sd_output_def def = {.directory = dir, .vtk = 1, .csv = 1, .scene = "scene.yaml"};
    sd_output *o = NULL;
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_status s = sd_output_open(&def, NULL, &o, &err);
    CHECK(s == SD_ERR_IO);
    CHECK(o == NULL);
    CHECK(strstr(err.msg, "did not write") != NULL);
    char *text = read_all(mine, NULL);
    CHECK(text && strcmp(text, "precious user data\n") == 0);
    free(text);
    CHECK(!file_exists(path_join(marker, sizeof marker, dir, ".shapedem-output")));
    CHECK(count_matching(dir, "", "") == 3); /* ".", ".." and the user's file */
}

static void test_run(const char *root)
{
    char dir[1024], path[1200];
    snprintf(dir, sizeof dir, "%s/run/nested/out", root);
    printf("checking: open makes %s (mkdir -p) with the marker\n", dir);
    sd_world *w = make_world(8, 1);
    if (!w)
        return;
    sd_output_def def = {.directory = dir, .vtk = 1, .csv = 1, .scene = "scene.yaml"};
    sd_output *o = NULL;
    sd_error err;
    CHECK_OK(sd_output_open(&def, w, &o, &err), err);
    if (!o) {
        sd_world_destroy(w);
        return;
    }
    CHECK(file_exists(path_join(path, sizeof path, dir, ".shapedem-output")));

    const int frames = 3;
    for (int f = 0; f < frames; ++f) {
        CHECK_OK(sd_output_frame(o, w, &err), err);
        CHECK_OK(sd_output_stats(o, w, &err), err);
        snprintf(path, sizeof path, "%s/particles_%06d.vtu", dir, f);
        check_particle_frame(path, w);
        CHECK_OK(sd_world_step(w, 5, &err), err);
    }
    CHECK_OK(sd_output_stats(o, w, &err), err); /* one more row than frames */
    snprintf(path, sizeof path, "%s/walls_%06d.vtp", dir, frames - 1);
    check_wall_frame(path, 1 + 5); /* the plane's square + the box without its top */

    printf("checking: frames.pvd lists every frame\n");
    char *pvd = read_all(path_join(path, sizeof path, dir, "frames.pvd"), NULL);
    CHECK(pvd != NULL);
    if (pvd) {
        CHECK(strstr(pvd, "type=\"Collection\"") != NULL);
        int sets = 0;
        for (const char *p = pvd; (p = strstr(p, "<DataSet")) != NULL; ++p)
            ++sets;
        CHECK(sets == 2 * frames);
        for (int f = 0; f < frames; ++f) {
            char name[64];
            snprintf(name, sizeof name, "file=\"particles_%06d.vtu\"", f);
            CHECK(strstr(pvd, name) != NULL);
            snprintf(name, sizeof name, "file=\"walls_%06d.vtp\"", f);
            CHECK(strstr(pvd, name) != NULL);
        }
        free(pvd);
    }

    printf("checking: stats.csv has a header and one row per call, all with 12 + 6 x walls columns\n");
    char *csv = read_all(path_join(path, sizeof path, dir, "stats.csv"), NULL);
    CHECK(csv != NULL);
    if (csv) {
        CHECK(strncmp(csv, "step,time,kinetic_translational,", 32) == 0);
        CHECK(strstr(csv, ",floor_fx,floor_fy,floor_fz,floor_tx,floor_ty,floor_tz,"
                          "wall1_fx,wall1_fy,wall1_fz,wall1_tx,wall1_ty,wall1_tz\n") != NULL);
        int lines = 0, bad = 0;
        const int want = 12 + 6 * 2; /* per wall: force and torque */
        for (const char *p = csv; *p;) {
            const char *e = strchr(p, '\n');
            if (!e) {
                ++bad; /* a row without its newline */
                break;
            }
            bad += csv_fields(p, e) != want;
            ++lines;
            p = e + 1;
        }
        CHECK(bad == 0);
        CHECK(lines == 1 + frames + 1);
        free(csv);
    }

    printf("checking: summary.txt is written on close\n");
    sd_run_summary sum = {15, 0.5, 240.0, 1, 1 << 20, 1 << 22, NULL, NULL, 0};
    CHECK_OK(sd_output_close(o, w, &sum, &err), err);
    char *summary = read_all(path_join(path, sizeof path, dir, "summary.txt"), NULL);
    CHECK(summary && strstr(summary, "particles: 8\n") && strstr(summary, "steps_run: 15\n") &&
          strstr(summary, "peak_memory_MiB: 1.000\n") && strstr(summary, "scene: scene.yaml\n"));
    free(summary);

    printf("checking: no temporary file remains\n");
    CHECK(count_matching(dir, "", ".tmp") == 0);

    printf("checking: a second run replaces our files only, and writes an empty frame\n");
    char user[1200];
    write_text(path_join(user, sizeof user, dir, "notes.txt"), "keep me\n");
    sd_world *empty = make_world(0, 0);
    o = NULL;
    CHECK_OK(sd_output_open(&def, empty, &o, &err), err);
    CHECK(file_exists(user));
    CHECK(count_matching(dir, "particles_", ".vtu") == 0);
    CHECK(count_matching(dir, "walls_", ".vtp") == 0);
    CHECK(!file_exists(path_join(path, sizeof path, dir, "stats.csv")));
    CHECK(!file_exists(path_join(path, sizeof path, dir, "summary.txt")));
    if (o && empty) {
        CHECK_OK(sd_output_frame(o, empty, &err), err);
        check_particle_frame(path_join(path, sizeof path, dir, "particles_000000.vtu"), empty);
        check_wall_frame(path_join(path, sizeof path, dir, "walls_000000.vtp"), 0);
        CHECK_OK(sd_output_stats(o, empty, &err), err);
        CHECK_OK(sd_output_close(o, empty, NULL, &err), err);
    }
    CHECK(count_matching(dir, "", ".tmp") == 0);
    if (empty)
        sd_world_destroy(empty);
    sd_world_destroy(w);
}

int main(void)
{
    char root[] = "/tmp/shapedem-test-output-XXXXXX";
    if (!mkdtemp(root)) {
        perror("mkdtemp");
        return 1;
    }
    test_foreign_directory(root);
    test_run(root);
    remove_tree(root);
    if (failures) {
        fprintf(stderr, "test_output: %d check(s) failed\n", failures);
        return 1;
    }
    printf("test_output: all checks passed\n");
    return 0;
}
