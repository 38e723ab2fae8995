/* api_states.c — every public function in every state (issue 31): each
 * function declared in the headers of include/shapedem/ is called
 *  - with NULL handles and NULL out pointers (an error status, or the
 *    neutral value its header documents: -1, 0, NULL, NaN),
 *  - on a fresh world (created, nothing added), on a world with particles
 *    not prepared, on a prepared one, after steps, after a failed call,
 *    on a 2D and on a grid-solver world, on a loaded scene and an open run,
 *  - and through the destroy paths (a half-built world, a world whose
 *    creation failed).
 * The test passes when nothing crashes (CI runs it under ASan and UBSan)
 * and each answer is the documented one. Every call goes through API(),
 * which records the name; at the end the names declared in the public
 * headers (parsed from $SD_SOURCE_DIR/include/shapedem) are compared with
 * those recorded, so a new public function fails this test until it is
 * called here. Then the bulk field calls by stable id: get/set round trip
 * across rebuilds that reorder the particles, missing ids, wrong sizes,
 * read-only fields and bad values (nothing written on an error).
 */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "test.h"

#include <shapedem/analysis.h>
#include <shapedem/process.h>
#include <shapedem/scene.h>
#include <shapedem/shapedem.h>

/* ---- the record of the functions called ---------------------------------------- */

#define SD_MAX_NAMES 512
static const char *called[SD_MAX_NAMES];
static int ncalled;

static void mark(const char *name)
{
    for (int k = 0; k < ncalled; ++k)
        if (strcmp(called[k], name) == 0)
            return;
    if (ncalled < SD_MAX_NAMES)
        called[ncalled++] = name;
}

/* API(fn)(args): calls fn and records that it was called */
#define API(fn) (mark(#fn), fn)

/* a failed call: an error status with a message */
#define FAILS(expr)                                                                                      \
    do {                                                                                                 \
        memset(&e, 0, sizeof e);                                                                         \
        sd_status s_ = (expr);                                                                           \
        CHECK(s_ != SD_OK);                                                                              \
        CHECK(e.msg[0] != '\0');                                                                         \
    } while (0)

/* ---- the names the headers declare ------------------------------------------- */

/* Reads file into a NUL-terminated buffer (the caller frees it). */
static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = malloc((size_t)n + 1);
    size_t got = b ? fread(b, 1, (size_t)n, f) : 0;
    fclose(f);
    if (b)
        b[got] = '\0';
    return b;
}

/* The functions a header declares: identifiers sd_... followed by '(' at
 * brace and parenthesis depth 0, outside comments and preprocessor lines
 * (macro bodies are not declarations); `extern "C" {` opens no depth. */
static int declared(const char *text, char names[][64], int max)
{
    int n = 0, depth = 0, paren = 0, bol = 1;
    const char *s = text;
    while (*s) {
        if (s[0] == '/' && s[1] == '*') {
            const char *end = strstr(s + 2, "*/");
            s = end ? end + 2 : s + strlen(s);
            continue;
        }
        if (s[0] == '/' && s[1] == '/') {
            while (*s && *s != '\n')
                ++s;
            continue;
        }
        if (bol) {
            const char *t = s;
            while (*t == ' ' || *t == '\t')
                ++t;
            if (*t == '#') { /* a preprocessor line and its continuations */
                while (*t && !(*t == '\n' && t[-1] != '\\'))
                    ++t;
                s = t;
                continue;
            }
        }
        bol = *s == '\n';
        if (*s == '"') { /* a string: `extern "C"` */
            const char *t = strchr(s + 1, '"');
            int extern_c = strncmp(s, "\"C\"", 3) == 0;
            s = t ? t + 1 : s + strlen(s);
            if (extern_c) {
                while (*s == ' ')
                    ++s;
                if (*s == '{')
                    ++s;
            }
            continue;
        }
        if (*s == '{')
            ++depth;
        else if (*s == '}')
            depth = depth > 0 ? depth - 1 : 0; /* the closing brace of extern "C" */
        else if (*s == '(')
            ++paren;
        else if (*s == ')')
            --paren;
        else if ((s == text || !(s[-1] == '_' || (s[-1] >= 'a' && s[-1] <= 'z') || (s[-1] >= '0' && s[-1] <= '9') ||
                                 (s[-1] >= 'A' && s[-1] <= 'Z'))) &&
                 strncmp(s, "sd_", 3) == 0) {
            const char *t = s;
            while (*t == '_' || (*t >= 'a' && *t <= 'z') || (*t >= '0' && *t <= '9'))
                ++t;
            const char *u = t;
            while (*u == ' ')
                ++u;
            if (*u == '(' && depth == 0 && paren == 0 && n < max && t - s < 64) {
                memcpy(names[n], s, (size_t)(t - s));
                names[n][t - s] = '\0';
                ++n;
            }
            s = t;
            continue;
        }
        ++s;
    }
    return n;
}

static void check_coverage(void)
{
    const char *src = getenv("SD_SOURCE_DIR");
    sd_test_require(src != NULL, "SD_SOURCE_DIR is set (ctest sets it)", NULL);
    static const char *headers[] = {"shapedem.h", "scene.h", "process.h", "analysis.h"};
    static char names[SD_MAX_NAMES][64];
    int total = 0;
    for (size_t h = 0; h < sizeof headers / sizeof *headers; ++h) {
        char path[1024];
        snprintf(path, sizeof path, "%s/include/shapedem/%s", src, headers[h]);
        char *text = slurp(path);
        sd_test_require(text != NULL, path, NULL);
        total += declared(text, names + total, SD_MAX_NAMES - total);
        free(text);
    }
    /* the public headers are the four above: a fifth must be listed here */
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/include/shapedem", src);
    int missing = 0;
    for (int k = 0; k < total; ++k) {
        int found = 0;
        for (int j = 0; j < ncalled && !found; ++j)
            found = strcmp(called[j], names[k]) == 0;
        if (!found) {
            printf("FAIL %s is declared in %s but not called by this test\n", names[k], dir);
            ++missing;
        }
    }
    printf("%d public functions declared, %d called here, %d not called\n", total, ncalled, missing);
    CHECK(total >= 120); /* the parser found the declarations */
    CHECK(missing == 0);
}

/* ---- worlds ------------------------------------------------------------------------ */

static sd_world *make_world(int dimension, sd_solver solver, sd_contact_law law)
{
    sd_error e;
    sd_world_def d = API(sd_world_def_default)();
    d.dimension = dimension;
    d.dt = 1e-6;
    d.threads = 1;
    d.solver = solver;
    d.law = law;
    if (dimension == 2)
        d.gravity.z = 0, d.gravity.y = -9.81;
    else
        d.gravity.z = -9.81;
    sd_world *w = NULL;
    sd_test_require(API(sd_world_create)(&d, &w, &e) == SD_OK, "world", &e);
    return w;
}

static int add_glass(sd_world *w, double stiffness)
{
    sd_error e;
    sd_material_def m = API(sd_material_def_default)();
    m.name = "glass";
    m.density = 2500;
    m.youngs_modulus = 1e7;
    m.stiffness = stiffness;
    m.friction = 0.4;
    int mat = API(sd_world_add_material)(w, &m, &e);
    sd_test_require(mat >= 0, "material", &e);
    return mat;
}

/* A box of spheres on a square lattice (shuffled, so that the first
 * rebuild reorders them), a box template and one body of it. */
static void add_particles(sd_world *w, int mat, int dimension, size_t n)
{
    sd_error e;
    sd_sphere_def *s = calloc(n, sizeof *s);
    size_t side = 1;
    while (side * side * (dimension == 2 ? 1 : side) < n)
        ++side;
    for (size_t k = 0; k < n; ++k) {
        size_t j = (k * 7919) % n; /* a scattering permutation of the lattice sites */
        s[k].radius = 0.001;
        s[k].material = mat;
        s[k].position.x = 0.003 * (double)(j % side) + 0.002;
        s[k].position.y = 0.003 * (double)((j / side) % side) + 0.002;
        s[k].position.z = dimension == 2 ? 0 : 0.003 * (double)(j / (side * side)) + 0.002;
    }
    sd_test_require(API(sd_world_add_spheres)(w, n, s, &e) == SD_OK, "spheres", &e);
    free(s);
}

static void add_walls(sd_world *w, int mat, int dimension)
{
    sd_error e;
    if (dimension == 2) {
        CHECK(API(sd_world_add_plane)(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 1, 0), mat, &e) >= 0);
        return;
    }
    CHECK(API(sd_world_add_box)(w, "box", sd_test_v(-0.05, -0.05, 0), sd_test_v(0.05, 0.05, 0.1), SD_BOX_ZMAX, mat,
                                &e) >= 0);
}

/* Every call that takes a world, on w in its present state. Adders are
 * called with bad input (they must refuse it and change nothing); the
 * state-changing calls a test needs are made by the callers. */
static void exercise(sd_world *w, const char *state, int grid)
{
    printf("-- %s\n", state);
    sd_error e;
    size_t np = API(sd_world_particle_count)(w);
    size_t nw = API(sd_world_wall_count)(w);
    long step = API(sd_world_step_count)(w);
    double time = API(sd_world_time)(w);
    (void)time;
    CHECK(API(sd_world_dt)(w) > 0);
    CHECK(API(sd_world_threads)(w) >= 1);
    CHECK(API(sd_world_backend)(w) != NULL);
    CHECK(API(sd_world_backend_note)(w) != NULL);
    CHECK(step >= 0);

    /* materials */
    FAILS(API(sd_world_add_material)(w, NULL, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    CHECK(API(sd_world_find_material)(w, NULL) == -1);
    CHECK(API(sd_world_find_material)(w, "no such material") == -1);
    CHECK(API(sd_world_material_name)(w, 100000) == NULL);
    FAILS(API(sd_world_set_interaction)(w, 0, 0, NULL, &e));
    sd_interaction_def id = API(sd_interaction_def_default)();
    FAILS(sd_world_set_interaction(w, -1, 100000, &id, &e));

    /* particles and shapes: bad input is refused, nothing is added */
    FAILS(API(sd_world_add_spheres)(w, 1, NULL, &e));
    CHECK(sd_world_add_spheres(w, 0, NULL, &e) == SD_OK);
    FAILS(API(sd_world_add_bodies)(w, 1, NULL, &e));
    FAILS(API(sd_world_add_shape)(w, "bad", NULL, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    sd_shape_desc sh = API(sd_shape_desc_default)();
    sh.kind = NULL;
    FAILS(sd_world_add_shape(w, "bad", &sh, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    sh.kind = "polyhedron";
    sh.vertex_count = 4; /* and vertices NULL */
    FAILS(sd_world_add_shape(w, "bad", &sh, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    CHECK(API(sd_world_find_shape)(w, NULL) == -1);
    size_t ns = API(sd_world_shape_count)(w);
    sd_shape_info si;
    CHECK(API(sd_world_get_shape)(w, ns + 5, &si) != SD_OK);
    if (ns > 0) {
        CHECK(sd_world_get_shape(w, 0, &si) == SD_OK);
        CHECK(sd_world_get_shape(w, 0, NULL) != SD_OK);
    }
    FAILS(API(sd_world_add_composite)(w, "bad", NULL, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    sd_composite_desc cd = API(sd_composite_desc_default)();
    FAILS(sd_world_add_composite(w, "bad", &cd, &e) < 0 ? SD_ERR_INPUT : SD_OK); /* no elements */
    sd_composite_element els[64];
    size_t nel = 0;
    FAILS(API(sd_composite_preset)(w, "bad", NULL, els, 64, &nel, &e));
    sd_composite_preset_def pd = API(sd_composite_preset_def_default)();
    FAILS(sd_composite_preset(w, "bad", &pd, els, 64, &nel, &e)); /* preset NULL */
    pd.preset = "no such preset";
    FAILS(sd_composite_preset(w, "bad", &pd, NULL, 0, NULL, &e));
    FAILS(API(sd_world_add_composite_preset)(w, "bad", NULL, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    FAILS(API(sd_world_add_shape2d)(w, "bad", NULL, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    sd_shape2d_def s2 = API(sd_shape2d_def_default)();
    FAILS(sd_world_add_shape2d(w, "bad", &s2, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    CHECK(API(sd_world_add_scaled_shape)(w, -1, 2.0, "bad", &e) < 0);
    CHECK(sd_world_add_scaled_shape(w, 100000, 2.0, NULL, NULL) < 0);

    /* walls */
    FAILS(API(sd_world_add_plane)(w, NULL, sd_test_v(0, 0, 0), sd_test_v(0, 0, 0), 0, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    FAILS(API(sd_world_add_box)(w, NULL, sd_test_v(0, 0, 0), sd_test_v(0, 0, 0), 0, 0, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    sd_wall_motion_def wm = API(sd_wall_motion_def_default)();
    FAILS(API(sd_world_set_wall_motion)(w, -1, &wm, &e));
    FAILS(sd_world_set_wall_motion(w, 0, NULL, &e));
    FAILS(API(sd_world_add_mesh)(w, "bad", NULL, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    sd_mesh_def md = API(sd_mesh_def_default)();
    FAILS(sd_world_add_mesh(w, "bad", &md, &e) < 0 ? SD_ERR_INPUT : SD_OK); /* no triangles */
    sd_mesh_motion_def mm = API(sd_mesh_motion_def_default)();
    FAILS(API(sd_world_set_mesh_motion)(w, (int)nw + 3, &mm, &e));
    FAILS(sd_world_set_mesh_motion(w, 0, NULL, &e));
    FAILS(API(sd_world_set_wall_torque_point)(w, -1, sd_test_v(0, 0, 0), &e));
    sd_mesh_info mi;
    CHECK(API(sd_world_get_mesh)(w, (int)nw + 3, &mi) != SD_OK);
    CHECK(sd_world_get_mesh(w, 0, NULL) != SD_OK);
    sd_wall_info wi;
    CHECK(API(sd_world_get_wall)(w, nw + 3, &wi) != SD_OK);
    CHECK(sd_world_get_wall(w, 0, NULL) != SD_OK);
    if (nw > 0)
        CHECK(sd_world_get_wall(w, 0, &wi) == SD_OK);
    sd_biaxial bx;
    sd_status bs = API(sd_world_biaxial)(w, &bx);
    (void)bs;
    CHECK(sd_world_biaxial(w, NULL) != SD_OK);
    sd_drum_def dd = API(sd_drum_def_default)();
    dd.radius = -1;
    CHECK(API(sd_world_add_drum)(w, &dd, &e) < 0);
    CHECK(sd_world_add_drum(w, NULL, &e) < 0);

    /* pour, outlets, insertions */
    FAILS(API(sd_world_set_pour)(w, NULL, &e));
    sd_pour_def pour = API(sd_pour_def_default)();
    FAILS(sd_world_set_pour(w, &pour, &e)); /* radius 0 */
    FAILS(API(sd_world_set_outlet)(w, NULL, &e));
    sd_outlet_def od = API(sd_outlet_def_default)();
    FAILS(sd_world_set_outlet(w, &od, &e)); /* an empty hole */
    sd_pour_def got;
    CHECK(API(sd_world_get_pour)(w, &got) >= 0);
    CHECK(sd_world_get_pour(w, NULL) == 0);
    CHECK(API(sd_world_add_insertion)(w, NULL, &e) < 0);
    sd_insert_def ins = API(sd_insert_def_default)();
    CHECK(sd_world_add_insertion(w, &ins, &e) < 0); /* no region, no entries */
    sd_size_def fixed = API(sd_size_def_fixed)(0.001);
    CHECK(fixed.a == 0.001);
    size_t ni = API(sd_world_insertion_count)(w);
    sd_insert_info ii;
    CHECK(API(sd_world_get_insertion)(w, ni, &ii) != SD_OK);
    CHECK(sd_world_get_insertion(w, 0, NULL) != SD_OK);
    CHECK(API(sd_world_add_outlet)(w, NULL, &e) < 0);
    sd_region_outlet_def ro = API(sd_region_outlet_def_default)();
    CHECK(sd_world_add_outlet(w, &ro, &e) < 0); /* no region */
    size_t no = API(sd_world_outlet_count)(w);
    sd_outlet_info oi;
    CHECK(API(sd_world_get_outlet)(w, no, &oi) != SD_OK);
    CHECK(sd_world_get_outlet(w, 0, NULL) != SD_OK);
    sd_process_info pi;
    API(sd_world_get_process)(w, &pi);
    sd_world_get_process(w, NULL);

    /* queries */
    sd_particle_state ps;
    CHECK(API(sd_world_get_particle)(w, np, &ps) != SD_OK);
    CHECK(sd_world_get_particle(w, 0, NULL) != SD_OK);
    if (np > 0) {
        CHECK(sd_world_get_particle(w, 0, &ps) == SD_OK);
        CHECK(API(sd_world_find_particle)(w, ps.id) == 0);
    }
    CHECK(sd_world_find_particle(w, UINT64_MAX) == (size_t)-1);
    sd_stats st;
    API(sd_world_stats)(w, &st);
    CHECK(st.step == step);
    sd_world_stats(w, NULL);
    sd_narrow_stats nst[8];
    CHECK(API(sd_world_narrow_stats)(w, nst, 8) < 1000);
    CHECK(sd_world_narrow_stats(w, NULL, 0) < 1000);
    sd_profile pr;
    API(sd_world_profile)(w, &pr);
    sd_world_profile(w, NULL);
    API(sd_world_profile_add)(w, SD_PROFILE_OUTPUT, 0.0);
    sd_world_profile_add(w, (sd_profile_stage)-1, 1.0);
    sd_world_profile_add(w, SD_PROFILE_STAGE_COUNT, 1.0);
    double tc = 0;
    double rec = API(sd_world_recommended_dt)(w, &tc);
    CHECK(rec > 0 || isnan(rec));
    CHECK(sd_world_recommended_dt(w, NULL) == rec || (isnan(rec) && isnan(sd_world_recommended_dt(w, NULL))));

    /* analysis */
    sd_porosity_def pdf = API(sd_porosity_def_default)();
    sd_porosity po;
    FAILS(API(sd_world_porosity)(w, &pdf, &po, NULL, NULL, &e)); /* no region */
    FAILS(sd_world_porosity(w, NULL, &po, NULL, NULL, &e));
    pdf.region.kind = SD_REGION_BOX;
    pdf.region.lo = sd_test_v(0, 0, 0);
    pdf.region.hi = sd_test_v(0.01, 0.01, 0.01);
    pdf.voxel = 0.002;
    FAILS(sd_world_porosity(w, &pdf, NULL, NULL, NULL, &e));
    sd_coordination co;
    sd_status cs = API(sd_world_coordination)(w, NULL, &co, &e);
    (void)cs;
    FAILS(sd_world_coordination(w, NULL, NULL, &e));
    sd_motion_stats ms;
    CHECK(API(sd_world_motion_stats)(w, NULL, &ms, &e) == SD_OK);
    CHECK(ms.particles == np);
    FAILS(sd_world_motion_stats(w, NULL, NULL, &e));
    size_t counts[4];
    double top = 0;
    FAILS(API(sd_world_speed_histogram)(w, NULL, 0, 1.0, counts, &top, &e));
    FAILS(sd_world_speed_histogram(w, NULL, 4, 1.0, NULL, NULL, &e));
    sd_velocity_field_def vf = API(sd_velocity_field_def_default)();
    size_t vc[4];
    sd_v3d vm[4];
    FAILS(API(sd_world_velocity_field)(w, NULL, vc, vm, &e));
    FAILS(sd_world_velocity_field(w, &vf, NULL, NULL, &e));
    sd_bed_height bh;
    FAILS(API(sd_world_bed_height)(w, NULL, 2.0, &bh, &e)); /* fraction outside (0, 1] */
    FAILS(sd_world_bed_height(w, NULL, 0.5, NULL, &e));
    sd_surface_fit sf;
    FAILS(API(sd_world_drum_surface)(w, NULL, 8, NULL, &sf, &e));
    FAILS(API(sd_world_heap_angle)(w, NULL, 8, NULL, &sf, &e));
    sd_v3d centre = {0, 0, 0};
    FAILS(sd_world_heap_angle(w, &centre, 0, NULL, NULL, &e));

    /* bulk fields */
    uint64_t *ids = calloc(np + 1, sizeof *ids);
    double *vals = calloc(4 * (np + 1), sizeof *vals);
    CHECK(API(sd_world_get_ids)(w, ids, np, &e) == SD_OK);
    FAILS(sd_world_get_ids(w, ids, np + 1, &e));
    for (int f = 0; f < SD_FIELD_COUNT; ++f) {
        size_t c = API(sd_field_components)((sd_field)f);
        CHECK(c >= 1 && c <= 4);
        CHECK(API(sd_field_name)((sd_field)f) != NULL);
        CHECK(API(sd_field_unit)((sd_field)f) != NULL);
        CHECK(API(sd_world_get_field)(w, (sd_field)f, NULL, np, vals, np * c, &e) == SD_OK);
        FAILS(sd_world_get_field(w, (sd_field)f, NULL, np, vals, np * c + 1, &e));
        if (API(sd_field_writable)((sd_field)f)) {
            /* the values read back in: the cells solver takes them, the grid's refuses */
            sd_status ss = API(sd_world_set_field)(w, (sd_field)f, NULL, np, vals, np * c, &e);
            CHECK(grid ? ss == SD_ERR_INPUT : ss == SD_OK);
        } else
            FAILS(sd_world_set_field(w, (sd_field)f, NULL, np, vals, np * c, &e));
    }
    FAILS(sd_world_get_field(w, SD_FIELD_COUNT, NULL, np, vals, np, &e));
    FAILS(sd_world_set_field(w, (sd_field)-1, NULL, np, vals, np, &e));
    uint64_t absent = UINT64_MAX;
    FAILS(sd_world_get_field(w, SD_FIELD_RADIUS, &absent, 1, vals, 1, &e));
    free(ids);
    free(vals);
    /* the zero-copy view: the cells solver's arrays, the grid's refused */
    sd_state_view sv;
    sd_status vs = API(sd_world_state_view)(w, &sv, &e);
    CHECK(grid ? vs == SD_ERR_INPUT && sv.n == 0 : vs == SD_OK && sv.n == np);
    CHECK(grid || sv.generation == API(sd_world_generation)(w));
    FAILS(sd_world_state_view(w, NULL, &e));

    /* the checkpoint calls with no file to write or read */
    FAILS(API(sd_checkpoint_write)(w, NULL, &e));
    FAILS(API(sd_checkpoint_restore)(w, NULL, &e));
    FAILS(sd_checkpoint_restore(w, "/nonexistent/dir/ck.h5", &e));

    /* nothing above changed what the world holds */
    CHECK(sd_world_particle_count(w) == np);
    CHECK(sd_world_wall_count(w) == nw);
    CHECK(sd_world_shape_count(w) == ns);
    CHECK(sd_world_step_count(w) == step);
}

/* Every call with NULL handles (and NULL out pointers): an error status
 * with a message, or the neutral value the header gives. */
static void null_handles(void)
{
    printf("-- NULL handles\n");
    sd_error e;
    char buf[64];
    API(sd_error_format)(NULL, buf, sizeof buf);
    CHECK(buf[0] == '\0');
    memset(&e, 0, sizeof e);
    sd_error_format(&e, NULL, 0);
    CHECK(API(sd_status_name)((sd_status)99) != NULL);
    CHECK(API(sd_contact_law_name)((sd_contact_law)99) != NULL || sd_contact_law_name((sd_contact_law)99) == NULL);
    CHECK(API(sd_contact_law_from_name)(NULL) == SD_LAW_COUNT);
    CHECK(API(sd_contact_law_needs)((sd_contact_law)-1) == 0);
    CHECK(API(sd_contact_law_traits)(SD_LAW_COUNT) == 0);
    CHECK(API(sd_backend_kind_from_name)(NULL) == SD_BACKEND_COUNT);
    CHECK(API(sd_backend_kind_name)(SD_BACKEND_COUNT) != NULL || sd_backend_kind_name(SD_BACKEND_COUNT) == NULL);
    CHECK(API(sd_profile_stage_name)(-1) == NULL);
    CHECK(sd_profile_stage_name(SD_PROFILE_STAGE_COUNT) == NULL);
    CHECK(sd_field_name(SD_FIELD_COUNT) == NULL);
    CHECK(sd_field_components((sd_field)-1) == 0);
    CHECK(sd_field_unit(SD_FIELD_COUNT) == NULL);
    CHECK(sd_field_writable(SD_FIELD_COUNT) == 0);
    CHECK(API(sd_memory_in_use)() <= API(sd_memory_peak)());

    /* creation */
    sd_world *w = (sd_world *)&e; /* not NULL: a failed create must set it to NULL */
    FAILS(sd_world_create(NULL, &w, &e));
    CHECK(w == NULL);
    sd_world_def d = sd_world_def_default();
    FAILS(sd_world_create(&d, NULL, &e));
    d.dt = -1;
    w = (sd_world *)&e;
    FAILS(sd_world_create(&d, &w, &e));
    CHECK(w == NULL);
    API(sd_world_destroy)(NULL);
    API(sd_world_destroy)(w); /* the NULL the failed create left */

    /* every call that takes a world, on NULL */
    sd_material_def md = sd_material_def_default();
    md.name = "m";
    md.density = 1000;
    FAILS(sd_world_add_material(NULL, &md, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    CHECK(sd_world_find_material(NULL, "m") == -1);
    CHECK(sd_world_material_name(NULL, 0) == NULL);
    sd_interaction_def id = sd_interaction_def_default();
    FAILS(sd_world_set_interaction(NULL, 0, 0, &id, &e));
    sd_sphere_def sp = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, 0.001, 0};
    FAILS(sd_world_add_spheres(NULL, 1, &sp, &e));
    sd_shape_desc sh = sd_shape_desc_default();
    sh.kind = "sphere";
    sh.size.x = 0.001;
    FAILS(sd_world_add_shape(NULL, "s", &sh, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    CHECK(sd_world_find_shape(NULL, "s") == -1);
    CHECK(sd_world_shape_count(NULL) == 0);
    sd_shape_info si;
    CHECK(sd_world_get_shape(NULL, 0, &si) != SD_OK);
    sd_composite_element el = {0, {0, 0, 0}, {1, 0, 0, 0}};
    sd_composite_desc cd = sd_composite_desc_default();
    cd.elements = &el;
    cd.element_count = 1;
    FAILS(sd_world_add_composite(NULL, "c", &cd, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    sd_composite_preset_def pd = sd_composite_preset_def_default();
    pd.preset = "dumbbell";
    pd.length = 0.004;
    pd.diameter = 0.002;
    sd_composite_element els[64];
    size_t nel = 0;
    FAILS(sd_composite_preset(NULL, "p", &pd, els, 64, &nel, &e));
    FAILS(sd_world_add_composite_preset(NULL, "p", &pd, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    sd_shape2d_def s2 = sd_shape2d_def_default();
    s2.kind = "circle";
    s2.radius = 0.001;
    FAILS(sd_world_add_shape2d(NULL, "c", &s2, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    sd_body_def bd;
    memset(&bd, 0, sizeof bd);
    FAILS(sd_world_add_bodies(NULL, 1, &bd, &e));
    FAILS(sd_world_add_plane(NULL, "p", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), 0, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    FAILS(sd_world_add_box(NULL, "b", sd_test_v(0, 0, 0), sd_test_v(1, 1, 1), 0, 0, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    sd_wall_motion_def wm = sd_wall_motion_def_default();
    FAILS(sd_world_set_wall_motion(NULL, 0, &wm, &e));
    sd_mesh_def mdf = sd_mesh_def_default();
    FAILS(sd_world_add_mesh(NULL, "m", &mdf, &e) < 0 ? SD_ERR_INPUT : SD_OK);
    sd_mesh_motion_def mm = sd_mesh_motion_def_default();
    FAILS(sd_world_set_mesh_motion(NULL, 0, &mm, &e));
    FAILS(sd_world_set_wall_torque_point(NULL, 0, sd_test_v(0, 0, 0), &e));
    sd_mesh_info mi;
    CHECK(sd_world_get_mesh(NULL, 0, &mi) != SD_OK);
    sd_biaxial bx;
    CHECK(sd_world_biaxial(NULL, &bx) != SD_OK);
    CHECK(API(sd_world_biaxial_reference)(NULL) != SD_OK);
    sd_pour_def pour = sd_pour_def_default();
    pour.radius = 0.001;
    FAILS(sd_world_set_pour(NULL, &pour, &e));
    sd_outlet_def od = sd_outlet_def_default();
    od.x1 = od.y1 = 1;
    FAILS(sd_world_set_outlet(NULL, &od, &e));
    sd_pour_def got;
    CHECK(sd_world_get_pour(NULL, &got) == 0);
    FAILS(API(sd_world_prepare)(NULL, &e));
    FAILS(API(sd_world_step)(NULL, 1, &e));
    API(sd_world_request_interrupt)(NULL);
    CHECK(sd_world_particle_count(NULL) == 0);
    CHECK(sd_world_wall_count(NULL) == 0);
    CHECK(sd_world_step_count(NULL) == 0);
    CHECK(isnan(sd_world_time(NULL)));
    CHECK(isnan(sd_world_dt(NULL)));
    CHECK(sd_world_threads(NULL) == 0);
    CHECK(sd_world_backend(NULL) != NULL);
    CHECK(sd_world_backend_note(NULL) != NULL);
    sd_particle_state ps;
    CHECK(sd_world_get_particle(NULL, 0, &ps) != SD_OK);
    CHECK(sd_world_find_particle(NULL, 0) == (size_t)-1);
    sd_stats st;
    st.step = 7;
    sd_world_stats(NULL, &st);
    CHECK(st.step == 0 && st.pairs == 0);
    sd_narrow_stats ns[2];
    CHECK(sd_world_narrow_stats(NULL, ns, 2) == 0);
    sd_profile pr;
    pr.calls[0] = 7;
    sd_world_profile(NULL, &pr);
    CHECK(pr.calls[0] == 0);
    sd_world_profile_add(NULL, SD_PROFILE_OUTPUT, 1.0);
    sd_wall_info wi;
    CHECK(sd_world_get_wall(NULL, 0, &wi) != SD_OK);
    double tc = 1;
    CHECK(isnan(sd_world_recommended_dt(NULL, &tc)));
    CHECK(isnan(tc));
    uint64_t ids[1];
    double vals[4];
    FAILS(sd_world_get_ids(NULL, ids, 0, &e));
    FAILS(sd_world_get_field(NULL, SD_FIELD_POSITION, NULL, 0, vals, 0, &e));
    FAILS(sd_world_set_field(NULL, SD_FIELD_POSITION, NULL, 0, vals, 0, &e));
    sd_state_view sv;
    FAILS(sd_world_state_view(NULL, &sv, &e));
    CHECK(sv.n == 0 && sv.position == NULL);
    CHECK(sd_world_generation(NULL) == 0);

    /* process and analysis */
    sd_insert_def ins = sd_insert_def_default();
    CHECK(sd_world_add_insertion(NULL, &ins, &e) < 0);
    CHECK(sd_world_add_scaled_shape(NULL, 0, 2.0, "s", &e) < 0);
    CHECK(sd_world_insertion_count(NULL) == 0);
    sd_insert_info ii;
    CHECK(sd_world_get_insertion(NULL, 0, &ii) != SD_OK);
    sd_region_outlet_def ro = sd_region_outlet_def_default();
    CHECK(sd_world_add_outlet(NULL, &ro, &e) < 0);
    CHECK(sd_world_outlet_count(NULL) == 0);
    sd_outlet_info oi;
    CHECK(sd_world_get_outlet(NULL, 0, &oi) != SD_OK);
    sd_process_info pi;
    pi.inserted = 7;
    sd_world_get_process(NULL, &pi);
    CHECK(pi.inserted == 0);
    sd_drum_def dd = sd_drum_def_default();
    CHECK(sd_world_add_drum(NULL, &dd, &e) < 0);
    sd_porosity_def pdf = sd_porosity_def_default();
    sd_porosity po;
    FAILS(sd_world_porosity(NULL, &pdf, &po, NULL, NULL, &e));
    sd_coordination co;
    FAILS(sd_world_coordination(NULL, NULL, &co, &e));
    sd_motion_stats ms;
    FAILS(sd_world_motion_stats(NULL, NULL, &ms, &e));
    size_t counts[4];
    FAILS(sd_world_speed_histogram(NULL, NULL, 4, 1.0, counts, NULL, &e));
    sd_velocity_field_def vf = sd_velocity_field_def_default();
    size_t vc[4];
    sd_v3d vm[4];
    FAILS(sd_world_velocity_field(NULL, &vf, vc, vm, &e));
    sd_bed_height bh;
    FAILS(sd_world_bed_height(NULL, NULL, 0.5, &bh, &e));
    sd_surface_fit sf;
    sd_region_def drum;
    memset(&drum, 0, sizeof drum);
    FAILS(sd_world_drum_surface(NULL, &drum, 8, NULL, &sf, &e));
    sd_v3d centre = {0, 0, 0};
    FAILS(sd_world_heap_angle(NULL, &centre, 8, NULL, &sf, &e));

    /* checkpoints */
    FAILS(sd_checkpoint_write(NULL, "unused.h5", &e));
    FAILS(sd_checkpoint_restore(NULL, "unused.h5", &e));
    FAILS(API(sd_checkpoint_print)(NULL, NULL, &e));
    FAILS(sd_checkpoint_print(stdout, "/nonexistent/dir/ck.h5", &e));

    /* scenes and runs */
    sd_scene *sc = (sd_scene *)&e;
    FAILS(API(sd_scene_load)(NULL, &sc, &e));
    CHECK(sc == NULL);
    FAILS(sd_scene_load("/nonexistent/dir/scene.yaml", NULL, &e));
    FAILS(sd_scene_load("/nonexistent/dir/scene.yaml", &sc, &e));
    CHECK(sc == NULL);
    API(sd_scene_free)(NULL);
    w = (sd_world *)&e;
    FAILS(API(sd_scene_build)(NULL, &w, &e));
    CHECK(w == NULL);
    API(sd_scene_set_threads)(NULL, 2);
    API(sd_scene_set_steps)(NULL, 2);
    API(sd_scene_set_backend)(NULL, SD_BACKEND_CPU);
    API(sd_scene_set_device)(NULL, 0);
    CHECK(API(sd_scene_steps)(NULL) == 0);
    sd_scene_info info;
    info.dimension = 7;
    API(sd_scene_get_info)(NULL, &info);
    CHECK(info.dimension == 0);
    CHECK(API(sd_scene_material_name)(NULL, 0) == NULL);
    CHECK(API(sd_scene_shape_name)(NULL, 0) == NULL);
    CHECK(API(sd_scene_shape_warning)(NULL, 0) == NULL);
    CHECK(API(sd_scene_wall_name)(NULL, 0) == NULL);
    CHECK(API(sd_scene_wall_warning)(NULL, 0) == NULL);
    CHECK(API(sd_scene_outlet_warning)(NULL, 0) == NULL);
    CHECK(API(sd_scene_get_pour)(NULL, &got) == 0);
    CHECK(API(sd_scene_get_outlet)(NULL, &od) == 0);
    strcpy(buf, "x");
    API(sd_scene_output_directory)(NULL, buf, sizeof buf);
    CHECK(buf[0] == '\0');
    API(sd_scene_print_keys)(NULL, 0);
    sd_run *run = (sd_run *)&e;
    FAILS(API(sd_run_open)(NULL, NULL, "unused", &run, &e));
    CHECK(run == NULL);
    FAILS(API(sd_run_advance)(NULL, 1, &e));
    FAILS(API(sd_run_checkpoint)(NULL, &e));
    CHECK(API(sd_run_last_checkpoint)(NULL) == NULL);
    CHECK(API(sd_run_steps_to_output)(NULL) == 0);
    sd_run_progress rp;
    rp.done = 7;
    API(sd_run_get_progress)(NULL, &rp);
    CHECK(rp.done == 0);
    CHECK(API(sd_run_stop_note)(NULL) == NULL);
    CHECK(API(sd_run_directory)(NULL) == NULL);
    CHECK(API(sd_run_close)(NULL, &e) == SD_OK); /* closing nothing, like free(NULL) */
}

/* A temporary directory for the scene, the run and the checkpoints. */
static char tmpdir[256];

static void scene_and_run(void)
{
    printf("-- scene and run\n");
    sd_error e;
    char path[512], out[512], ck[512];
    snprintf(path, sizeof path, "%s/scene.yaml", tmpdir);
    snprintf(out, sizeof out, "%s/out", tmpdir);
    snprintf(ck, sizeof ck, "%s/ck.h5", tmpdir);
    FILE *f = fopen(path, "w");
    sd_test_require(f != NULL, "write the scene", NULL);
    fputs("simulation: {dt: 1.0e-6, steps: 20, gravity: [0, 0, -9.81], threads: 1}\n"
          "materials:\n  - {name: glass, density: 2500, youngs_modulus: 1.0e7}\n"
          "particles:\n  - generator: list\n    material: glass\n    spheres:\n"
          "      - {position: [0, 0, 0.002], radius: 0.001}\n"
          "      - {position: [0.0025, 0, 0.002], radius: 0.001}\n"
          "walls:\n  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: glass}\n"
          "output: {every: 10, formats: [csv]}\n",
          f);
    fclose(f);
    sd_scene *sc = NULL;
    sd_test_require(sd_scene_load(path, &sc, &e) == SD_OK, "scene", &e);
    sd_scene_set_threads(sc, 1);
    sd_scene_set_steps(sc, 20);
    sd_scene_set_backend(sc, SD_BACKEND_CPU);
    sd_scene_set_device(sc, 0);
    CHECK(sd_scene_steps(sc) == 20);
    sd_scene_info info;
    sd_scene_get_info(sc, &info);
    CHECK(info.material_count == 1 && info.wall_count == 1);
    sd_scene_get_info(sc, NULL);
    CHECK(sd_scene_material_name(sc, 0) != NULL);
    CHECK(sd_scene_material_name(sc, 5) == NULL);
    CHECK(sd_scene_shape_name(sc, 5) == NULL);
    CHECK(sd_scene_shape_warning(sc, 5) == NULL);
    CHECK(sd_scene_wall_name(sc, 0) != NULL);
    CHECK(sd_scene_wall_name(sc, 5) == NULL);
    CHECK(sd_scene_wall_warning(sc, 5) == NULL);
    CHECK(sd_scene_outlet_warning(sc, 5) == NULL);
    sd_pour_def pour;
    CHECK(sd_scene_get_pour(sc, &pour) == 0);
    CHECK(sd_scene_get_pour(sc, NULL) == 0);
    sd_outlet_def od;
    CHECK(sd_scene_get_outlet(sc, &od) == 0);
    CHECK(sd_scene_get_outlet(sc, NULL) == 0);
    char buf[256];
    sd_scene_output_directory(sc, buf, sizeof buf);
    sd_scene_output_directory(sc, NULL, 0);
    FILE *keys = tmpfile();
    if (keys) {
        sd_scene_print_keys(keys, 1);
        CHECK(ftell(keys) > 0);
        fclose(keys);
    }
    FAILS(sd_scene_build(sc, NULL, &e));
    sd_world *w = NULL;
    sd_test_require(sd_scene_build(sc, &w, &e) == SD_OK, "build", &e);
    exercise(w, "a world built from a scene", 0);
    sd_run *run = (sd_run *)&e;
    FAILS(sd_run_open(sc, NULL, out, &run, &e));
    CHECK(run == NULL);
    FAILS(sd_run_open(NULL, w, out, &run, &e));
    FAILS(sd_run_open(sc, w, out, NULL, &e));
    sd_test_require(sd_run_open(sc, w, out, &run, &e) == SD_OK, "run", &e);
    CHECK(sd_run_directory(run) != NULL);
    CHECK(sd_run_steps_to_output(run) > 0);
    CHECK(sd_run_advance(run, 10, &e) == SD_OK);
    CHECK(sd_run_advance(run, -1, &e) == SD_OK); /* a negative count runs nothing */
    CHECK(sd_run_checkpoint(run, &e) == SD_OK);
    CHECK(sd_run_last_checkpoint(run) != NULL);
    sd_run_progress rp;
    sd_run_get_progress(run, &rp);
    CHECK(rp.done == 10);
    sd_run_get_progress(run, NULL);
    (void)sd_run_stop_note(run);
    exercise(w, "a world in an open run", 0);
    CHECK(sd_run_close(run, &e) == SD_OK);
    /* checkpoints of the world: write, print, restore into a fresh build */
    CHECK(sd_checkpoint_write(w, ck, &e) == SD_OK);
    FAILS(sd_checkpoint_write(w, "", &e));
    FILE *sink = tmpfile();
    if (sink) {
        CHECK(sd_checkpoint_print(sink, ck, &e) == SD_OK);
        fclose(sink);
    }
    FAILS(sd_checkpoint_print(NULL, ck, &e));
    sd_world *w2 = NULL;
    sd_test_require(sd_scene_build(sc, &w2, &e) == SD_OK, "build 2", &e);
    CHECK(sd_checkpoint_restore(w2, ck, &e) == SD_OK);
    CHECK(sd_world_step_count(w2) == sd_world_step_count(w));
    exercise(w2, "a world restored from a checkpoint", 0);
    sd_world_destroy(w2);
    sd_world_destroy(w);
    sd_scene_free(sc);
}

/* The states of a world's life, each exercised. */
static void world_states(void)
{
    sd_error e;
    /* 3D cells: fresh, with particles, prepared, after steps */
    sd_world *w = make_world(3, SD_SOLVER_CELLS, SD_LAW_HERTZ_MINDLIN);
    exercise(w, "fresh world", 0);
    double tc = 0;
    CHECK(isinf(sd_world_recommended_dt(w, &tc))); /* no particle: no contact can form */
    int mat = add_glass(w, 0);
    exercise(w, "a material, nothing else", 0);
    add_walls(w, mat, 3);
    add_particles(w, mat, 3, 27);
    /* the crash: the recommended step before any prepare or step */
    double rec = sd_world_recommended_dt(w, &tc);
    CHECK(rec > 0 && isfinite(rec) && tc > 0 && isfinite(tc));
    exercise(w, "particles, not prepared", 0);
    CHECK(sd_world_prepare(w, &e) == SD_OK);
    double tc_prepared = 0;
    CHECK(sd_world_recommended_dt(w, &tc_prepared) == rec); /* the same mixed table before and after */
    CHECK(tc_prepared == tc);
    exercise(w, "prepared", 0);
    CHECK(sd_world_step(w, 3, &e) == SD_OK);
    exercise(w, "after 3 steps", 0);
    CHECK(sd_world_biaxial_reference(w) != SD_OK); /* no four plane walls */
    /* a material added after the prepare: the report mixes its own table */
    sd_material_def m2 = sd_material_def_default();
    m2.name = "steel";
    m2.density = 7800;
    m2.youngs_modulus = 2e8;
    CHECK(sd_world_add_material(w, &m2, &e) == 1);
    CHECK(sd_world_recommended_dt(w, &tc) > 0);
    exercise(w, "a material added after steps", 0);
    CHECK(sd_world_step(w, 1, &e) == SD_OK);
    /* an interrupt asked for between calls stops the next after its first
     * step, with a message, and is then cleared */
    long at = sd_world_step_count(w);
    sd_world_request_interrupt(w);
    memset(&e, 0, sizeof e);
    CHECK(sd_world_step(w, 5, &e) == SD_ERR_INTERRUPTED && e.msg[0] && sd_world_step_count(w) == at + 1);
    CHECK(sd_world_step(w, 2, &e) == SD_OK && sd_world_step_count(w) == at + 3);
    exercise(w, "after an interrupted step", 0);
    sd_world_destroy(w);

    /* a failed call: the linear law with no stiffness fails at prepare */
    w = make_world(3, SD_SOLVER_CELLS, SD_LAW_LINEAR);
    mat = add_glass(w, 0);
    add_particles(w, mat, 3, 8);
    FAILS(sd_world_step(w, 1, &e));
    exercise(w, "after a failed step", 0);
    FAILS(sd_world_prepare(w, &e));
    exercise(w, "after a failed prepare", 0);
    sd_world_destroy(w);

    /* a half-built world destroyed: shapes, a composite, a mesh and a
     * motion, no particle, never prepared */
    w = make_world(3, SD_SOLVER_CELLS, SD_LAW_HERTZ_MINDLIN);
    mat = add_glass(w, 0);
    sd_shape_desc sh = sd_shape_desc_default();
    sh.kind = "box";
    sh.size = sd_test_v(0.002, 0.003, 0.004);
    int brick = sd_world_add_shape(w, "brick", &sh, &e);
    CHECK(brick >= 0);
    sd_composite_preset_def pd = sd_composite_preset_def_default();
    pd.preset = "dumbbell";
    pd.length = 0.004;
    pd.diameter = 0.002;
    pd.width = 0.001;
    int bell = sd_world_add_composite_preset(w, "bell", &pd, &e);
    if (bell < 0)
        printf("composite preset: %s\n", e.msg);
    CHECK(bell >= 0);
    static const sd_v3d verts[4] = {{0, 0, 0}, {0.1, 0, 0}, {0.1, 0.1, 0}, {0, 0.1, 0}};
    static const uint32_t tris[2][3] = {{0, 1, 2}, {0, 2, 3}};
    sd_mesh_def md = sd_mesh_def_default();
    md.vertices = verts;
    md.vertex_count = 4;
    md.triangles = tris;
    md.triangle_count = 2;
    md.material = mat;
    int mesh = sd_world_add_mesh(w, "floor", &md, &e);
    CHECK(mesh >= 0);
    sd_mesh_motion_def mm = sd_mesh_motion_def_default();
    mm.kind = SD_MESH_ROTATE;
    mm.axis = sd_test_v(0, 0, 1);
    mm.rpm = 10;
    CHECK(sd_world_set_mesh_motion(w, mesh, &mm, &e) == SD_OK);
    CHECK(sd_world_set_wall_torque_point(w, mesh, sd_test_v(0, 0, 0), &e) == SD_OK);
    sd_mesh_info mi;
    CHECK(sd_world_get_mesh(w, mesh, &mi) == SD_OK);
    exercise(w, "half built: shapes and a mesh, no particle", 0);
    sd_body_def bd;
    memset(&bd, 0, sizeof bd);
    bd.shape = brick;
    bd.material = mat;
    bd.position = sd_test_v(0.05, 0.05, 0.01);
    CHECK(sd_world_add_bodies(w, 1, &bd, &e) == SD_OK);
    exercise(w, "half built: one body", 0);
    sd_world_destroy(w);

    /* the planar mode */
    w = make_world(2, SD_SOLVER_CELLS, SD_LAW_HERTZ_MINDLIN);
    exercise(w, "fresh 2D world", 0);
    mat = add_glass(w, 0);
    add_walls(w, mat, 2);
    add_particles(w, mat, 2, 16);
    CHECK(sd_world_recommended_dt(w, &tc) > 0);
    exercise(w, "2D, not prepared", 0);
    CHECK(sd_world_step(w, 2, &e) == SD_OK);
    exercise(w, "2D after 2 steps", 0);
    sd_world_destroy(w);

    /* the grid solver */
    w = make_world(3, SD_SOLVER_GRID, SD_LAW_LINEAR);
    exercise(w, "fresh grid world", 1);
    mat = add_glass(w, 50000);
    add_walls(w, mat, 3);
    add_particles(w, mat, 3, 8);
    exercise(w, "grid, not prepared", 1);
    if (sd_world_step(w, 2, &e) == SD_OK)
        exercise(w, "grid after 2 steps", 1);
    else
        exercise(w, "grid after a failed step", 1);
    sd_world_destroy(w);
}

/* storage index of each id */
static void indices(const sd_world *w, const uint64_t *ids, size_t n, size_t *idx)
{
    for (size_t k = 0; k < n; ++k)
        idx[k] = sd_world_find_particle(w, ids[k]);
}

static int moved(const size_t *a, const size_t *b, size_t n)
{
    size_t m = 0;
    for (size_t k = 0; k < n; ++k)
        m += a[k] != b[k];
    return (int)m;
}

/* The bulk calls by stable id: round trip across rebuilds that reorder
 * the particles, subsets, and each refusal writing nothing. */
static void bulk_fields(void)
{
    printf("-- bulk fields by id\n");
    sd_error e;
    enum { N = 64 };
    sd_world *w = make_world(3, SD_SOLVER_CELLS, SD_LAW_HERTZ_MINDLIN);
    int mat = add_glass(w, 0);
    add_walls(w, mat, 3);
    add_particles(w, mat, 3, N);
    uint64_t ids[N];
    size_t before[N], after[N];
    CHECK(sd_world_get_ids(w, ids, N, &e) == SD_OK);
    int increasing = 1;
    for (size_t k = 1; k < N; ++k)
        increasing &= ids[k] > ids[k - 1];
    CHECK(increasing);
    indices(w, ids, N, before);
    CHECK(sd_world_prepare(w, &e) == SD_OK); /* the first rebuild sorts the particles by cell */
    indices(w, ids, N, after);
    int reordered = moved(before, after, N);
    printf("prepare moved %d of %d particles in storage\n", reordered, N);
    CHECK(reordered > 0);

    /* every field in id order is what get_particle says of each id */
    double P[3 * N], V[3 * N], Q[4 * N], M[N];
    CHECK(sd_world_get_field(w, SD_FIELD_POSITION, NULL, N, P, 3 * N, &e) == SD_OK);
    CHECK(sd_world_get_field(w, SD_FIELD_MASS, NULL, N, M, N, &e) == SD_OK);
    int same = 1;
    for (size_t k = 0; k < N; ++k) {
        sd_particle_state ps;
        CHECK(sd_world_get_particle(w, sd_world_find_particle(w, ids[k]), &ps) == SD_OK);
        same &= ps.id == ids[k] && ps.position.x == P[3 * k] && ps.position.y == P[3 * k + 1] &&
                ps.position.z == P[3 * k + 2] && ps.mass == M[k];
    }
    CHECK(same);
    /* explicit ids, in reverse */
    uint64_t rev[N];
    double Pr[3 * N];
    for (size_t k = 0; k < N; ++k)
        rev[k] = ids[N - 1 - k];
    CHECK(sd_world_get_field(w, SD_FIELD_POSITION, rev, N, Pr, 3 * N, &e) == SD_OK);
    same = 1;
    for (size_t k = 0; k < N; ++k)
        for (int c = 0; c < 3; ++c)
            same &= Pr[3 * k + c] == P[3 * (N - 1 - k) + c];
    CHECK(same);

    /* set: positions exchanged between particles (so the next rebuild
     * reorders them), velocities and turned orientations of each id */
    double P2[3 * N];
    for (size_t k = 0; k < N; ++k) {
        size_t j = (k * 37 + 11) % N; /* 37 is prime to 64: a permutation */
        memcpy(P2 + 3 * k, P + 3 * j, 3 * sizeof(double));
        V[3 * k] = 0.001 * (double)k;
        V[3 * k + 1] = -0.002 * (double)k;
        V[3 * k + 2] = 0.0005;
        double a = 0.01 * (double)k;
        Q[4 * k] = cos(a / 2);
        Q[4 * k + 1] = sin(a / 2) * 0.6;
        Q[4 * k + 2] = 0;
        Q[4 * k + 3] = sin(a / 2) * 0.8;
    }
    CHECK(sd_world_set_field(w, SD_FIELD_POSITION, NULL, N, P2, 3 * N, &e) == SD_OK);
    CHECK(sd_world_set_field(w, SD_FIELD_VELOCITY, ids, N, V, 3 * N, &e) == SD_OK);
    CHECK(sd_world_set_field(w, SD_FIELD_ORIENTATION, NULL, N, Q, 4 * N, &e) == SD_OK);
    indices(w, ids, N, before);
    CHECK(sd_world_prepare(w, &e) == SD_OK); /* new pair lists: the particles sorted again */
    indices(w, ids, N, after);
    reordered = moved(before, after, N);
    printf("the rebuild after the set moved %d of %d particles in storage\n", reordered, N);
    CHECK(reordered > 0);
    double G[4 * N];
    CHECK(sd_world_get_field(w, SD_FIELD_POSITION, NULL, N, G, 3 * N, &e) == SD_OK);
    CHECK(memcmp(G, P2, sizeof P2) == 0);
    CHECK(sd_world_get_field(w, SD_FIELD_VELOCITY, ids, N, G, 3 * N, &e) == SD_OK);
    CHECK(memcmp(G, V, sizeof V) == 0);
    CHECK(sd_world_get_field(w, SD_FIELD_ORIENTATION, NULL, N, G, 4 * N, &e) == SD_OK);
    CHECK(memcmp(G, Q, sizeof Q) == 0);

    /* a subset, an id twice (the last values win), the others untouched */
    uint64_t sub[3] = {ids[5], ids[2], ids[5]};
    double W[9] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    CHECK(sd_world_set_field(w, SD_FIELD_ANGULAR_VELOCITY, sub, 3, W, 9, &e) == SD_OK);
    double Wall[3 * N];
    CHECK(sd_world_get_field(w, SD_FIELD_ANGULAR_VELOCITY, NULL, N, Wall, 3 * N, &e) == SD_OK);
    CHECK(Wall[15] == 7 && Wall[16] == 8 && Wall[17] == 9);
    CHECK(Wall[6] == 4 && Wall[7] == 5 && Wall[8] == 6);
    CHECK(Wall[0] == 0 && Wall[3 * N - 1] == 0);

    /* refusals: each leaves the caller's array and the world as they were */
    double sentinel[3 * N], keep[3 * N];
    for (size_t k = 0; k < 3 * N; ++k)
        sentinel[k] = -12345.0;
    memcpy(keep, sentinel, sizeof keep);
    FAILS(sd_world_get_field(w, SD_FIELD_POSITION, NULL, N, sentinel, 3 * N - 1, &e)); /* one short */
    FAILS(sd_world_get_field(w, SD_FIELD_POSITION, NULL, N - 1, sentinel, 3 * (N - 1), &e)); /* not all */
    FAILS(sd_world_get_field(w, SD_FIELD_POSITION, NULL, N, NULL, 3 * N, &e));
    uint64_t with_absent[3] = {ids[0], ids[N - 1] + 1000, ids[1]};
    FAILS(sd_world_get_field(w, SD_FIELD_POSITION, with_absent, 3, sentinel, 9, &e));
    printf("missing id: %s\n", e.msg);
    CHECK(strstr(e.msg, "ids[1]") != NULL);
    CHECK(memcmp(sentinel, keep, sizeof keep) == 0);
    FAILS(sd_world_get_ids(w, ids, N - 1, &e));

    double Pbefore[3 * N], Pafter[3 * N];
    CHECK(sd_world_get_field(w, SD_FIELD_POSITION, NULL, N, Pbefore, 3 * N, &e) == SD_OK);
    double bad[3 * N];
    memcpy(bad, Pbefore, sizeof bad);
    for (size_t k = 0; k < 3 * N; ++k)
        bad[k] += 0.0001;
    FAILS(sd_world_set_field(w, SD_FIELD_POSITION, with_absent, 3, bad, 9, &e)); /* an id missing */
    FAILS(sd_world_set_field(w, SD_FIELD_POSITION, NULL, N, bad, 3 * N + 3, &e)); /* wrong size */
    FAILS(sd_world_set_field(w, SD_FIELD_FORCE, NULL, N, bad, 3 * N, &e));        /* read-only */
    CHECK(strstr(e.msg, "read-only") != NULL);
    FAILS(sd_world_set_field(w, SD_FIELD_MASS, NULL, N, bad, N, &e));
    bad[3 * N - 1] = NAN; /* the last value: everything before it would be written by a careless setter */
    FAILS(sd_world_set_field(w, SD_FIELD_POSITION, NULL, N, bad, 3 * N, &e));
    double Qbad[4 * N];
    memcpy(Qbad, Q, sizeof Qbad);
    Qbad[4 * N - 4] = 2; /* the last orientation is not a unit quaternion */
    FAILS(sd_world_set_field(w, SD_FIELD_ORIENTATION, NULL, N, Qbad, 4 * N, &e));
    printf("non-unit orientation: %s\n", e.msg);
    CHECK(sd_world_get_field(w, SD_FIELD_POSITION, NULL, N, Pafter, 3 * N, &e) == SD_OK);
    CHECK(memcmp(Pbefore, Pafter, sizeof Pafter) == 0);
    CHECK(sd_world_get_field(w, SD_FIELD_ORIENTATION, NULL, N, G, 4 * N, &e) == SD_OK);
    CHECK(memcmp(G, Q, sizeof Q) == 0);

    /* the world steps on from the state set */
    CHECK(sd_world_step(w, 20, &e) == SD_OK);
    CHECK(sd_world_get_field(w, SD_FIELD_POSITION, NULL, N, Pafter, 3 * N, &e) == SD_OK);
    CHECK(memcmp(Pbefore, Pafter, sizeof Pafter) != 0);
    sd_world_destroy(w);

    /* 2D: the plane is kept */
    w = make_world(2, SD_SOLVER_CELLS, SD_LAW_HERTZ_MINDLIN);
    mat = add_glass(w, 0);
    add_particles(w, mat, 2, 4);
    double p2[12] = {0, 0, 0, 0.01, 0, 0, 0.02, 0, 0, 0.03, 0, 0.001};
    FAILS(sd_world_set_field(w, SD_FIELD_POSITION, NULL, 4, p2, 12, &e)); /* z != 0 */
    double w2[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 1, 1};
    FAILS(sd_world_set_field(w, SD_FIELD_ANGULAR_VELOCITY, NULL, 4, w2, 12, &e)); /* about y */
    w2[10] = 0;
    CHECK(sd_world_set_field(w, SD_FIELD_ANGULAR_VELOCITY, NULL, 4, w2, 12, &e) == SD_OK);
    double q2[16] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0};
    FAILS(sd_world_set_field(w, SD_FIELD_ORIENTATION, NULL, 4, q2, 16, &e)); /* about x */
    sd_world_destroy(w);
}

int main(void)
{
    snprintf(tmpdir, sizeof tmpdir, "%s/sd-api-states-XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    sd_test_require(mkdtemp(tmpdir) != NULL, "a temporary directory", NULL);
    null_handles();
    world_states();
    scene_and_run();
    bulk_fields();
    check_coverage();
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    if (system(cmd) != 0)
        printf("note: could not remove %s\n", tmpdir);
    return sd_test_summary();
}
