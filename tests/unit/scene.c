/* scene.c — the scene module: parsing with values and defaults, the
 * four generators, building a world, the key table and its docs, and a
 * table of bad scenes that must each fail with SD_ERR_INPUT at the right
 * line and key.
 *
 * Scenes are written to a fresh directory under /tmp (mkdtemp), with a CSV
 * file beside them when a case needs one.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "core/alloc.h"
#include "io/scene.h"
#include "io/scene_keys.h"
#include "test.h"

static char dir[64];
static char scene_path[128];
static char csv_path[128];

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    sd_test_require(f != NULL, path, NULL);
    fputs(text, f);
    fclose(f);
}

/* Writes the scene (and csv, if any) and loads it. */
static sd_status load(const char *yaml, const char *csv, sd_scene **s, sd_error *err)
{
    write_file(scene_path, yaml);
    remove(csv_path);
    if (csv)
        write_file(csv_path, csv);
    return sd_scene_load(scene_path, s, err);
}

static void print_err(const char *what, const sd_error *err)
{
    char buf[1200];
    sd_error_format(err, buf, sizeof buf);
    printf("  %s: %s\n", what, buf);
}

static int near(double a, double b) { return fabs(a - b) <= 1e-12 * (fabs(a) + fabs(b) + 1e-300); }

/* ---- a good scene: values and defaults --------------------------------- */

static const char *good_scene =
    "simulation:\n"
    "  dt: 1.0e-6\n"
    "  duration: 0.00100005\n"
    "  seed: 42\n"
    "materials:\n"
    "  - name: glass\n"
    "    density: 2500\n"
    "    youngs_modulus: 1e7\n"
    "    restitution: 0.9\n"
    "  - name: steel\n"
    "    density: 7800\n"
    "    youngs_modulus: 2.0e8\n"
    "    poisson_ratio: 0.25\n"
    "    friction: 0.3\n"
    "    rolling_friction: 0.01\n"
    "    stiffness: 1000\n"
    "interactions:\n"
    "  - between: [glass, steel]\n"
    "    friction: 0.2\n"
    "    contact_law: hertz_mindlin\n"
    "particles:\n"
    "  - generator: lattice\n"
    "    material: glass\n"
    "    radius: 0.001\n"
    "    origin: [0.002, 0.003, 0.004]\n"
    "    spacing: [0.0025, 0.003, 0.0035]\n"
    "    count: [3, 4, 5]\n"
    "    velocity: [0.1, 0, 0]\n"
    "  - generator: list\n"
    "    material: steel\n"
    "    spheres:\n"
    "      - {position: [0.05, 0.05, 0.05], radius: 0.002}\n"
    "      - position: [0.06, 0.05, 0.05]\n"
    "        radius: 0.0015\n"
    "        velocity: [0, 0, -1]\n"
    "        angular_velocity: [0, 10, 0]\n"
    "        material: glass\n"
    "  - generator: csv\n"
    "    material: glass\n"
    "    file: spheres.csv\n"
    "    velocity: [0, 0.5, 0]\n"
    "  - generator: random\n"
    "    material: glass\n"
    "    radius: {min: 0.0005, max: 0.0008}\n"
    "    box: {min: [0.1, 0.1, 0.1], max: [0.12, 0.12, 0.12]}\n"
    "    number: 200\n"
    "    velocity_jitter: 0.01\n"
    "walls:\n"
    "  - type: plane\n"
    "    point: [0, 0, 0]\n"
    "    normal: [0, 0, 2]\n"
    "    material: steel\n"
    "  - name: bin\n"
    "    type: box\n"
    "    min: [-1, -1, -1]\n"
    "    max: [1, 1, 1]\n"
    "    open: [zmax, xmin]\n"
    "    material: steel\n"
    "output:\n"
    "  every: 7\n";

static const char *good_csv =
    "x, y, z, radius, vx\n"
    "0.08, 0.08, 0.08, 0.001, 1.5\n"
    "# a comment line\n"
    "\n"
    "0.083,0.08,0.08,0.001,0\n";

static void test_good_scene(void)
{
    printf("good scene: values and defaults\n");
    sd_scene *s;
    sd_error err;
    sd_status st = load(good_scene, good_csv, &s, &err);
    if (st != SD_OK)
        print_err("load", &err);
    sd_test_require(st == SD_OK, "load the good scene", &err);

    CHECK(s->world.dimension == 3);
    CHECK(near(s->world.dt, 1e-6));
    CHECK(s->steps == 1001); /* ceil(1000.05 - 1e-9) */
    CHECK(s->dt_line == 2);
    CHECK(s->simulation_line == 1);
    CHECK(s->world.gravity.x == 0.0 && s->world.gravity.y == 0.0 && near(s->world.gravity.z, -9.81));
    CHECK(s->world.seed == 42);
    CHECK(s->world.threads == 0);
    CHECK(s->world.law == SD_LAW_HERTZ_MINDLIN);
    CHECK(s->world.skin == 0.0);

    CHECK(s->material_count == 2);
    const sd_material_def *g = &s->materials[0].def, *m = &s->materials[1].def;
    CHECK(!strcmp(s->materials[0].name, "glass") && !strcmp(g->name, "glass"));
    CHECK(s->materials[0].line == 6 && s->materials[1].line == 10);
    CHECK(g->density == 2500.0 && g->youngs_modulus == 1e7 && g->restitution == 0.9);
    CHECK(near(g->poisson_ratio, 0.3) && near(g->friction, 0.5) && g->rolling_friction == 0.0);
    CHECK(g->stiffness == 0.0 && near(g->tangential_stiffness_ratio, 2.0 / 7.0));
    CHECK(m->density == 7800.0 && m->poisson_ratio == 0.25 && m->friction == 0.3);
    CHECK(m->rolling_friction == 0.01 && m->stiffness == 1000.0 && near(m->restitution, 0.5));

    CHECK(s->interaction_count == 1);
    const sd_scene_interaction *in = &s->interactions[0];
    CHECK(in->mat_a == 0 && in->mat_b == 1 && in->line == 18);
    CHECK(in->def.friction == 0.2 && in->def.restitution < 0.0 && in->def.stiffness < 0.0);
    CHECK(in->def.rolling_friction < 0.0 && in->def.law == SD_LAW_HERTZ_MINDLIN);

    CHECK(s->generator_count == 4);
    const sd_scene_generator *lat = &s->generators[0];
    CHECK(lat->kind == SD_GEN_LATTICE && lat->line == 22 && lat->material == 0);
    CHECK(lat->radius_min == 0.001 && lat->radius_max == 0.001);
    CHECK(lat->count[0] == 3 && lat->count[1] == 4 && lat->count[2] == 5);
    CHECK(lat->spacing.y == 0.003 && lat->origin.z == 0.004 && lat->velocity.x == 0.1);
    CHECK(lat->velocity_jitter == 0.0);
    const sd_scene_generator *lst = &s->generators[1];
    CHECK(lst->kind == SD_GEN_LIST && lst->list_count == 2);
    CHECK(lst->list[0].material == 1 && lst->list[1].material == 0);
    CHECK(lst->list_lines[0] == 32 && lst->list_lines[1] == 33);
    CHECK(lst->list[1].velocity.z == -1.0 && lst->list[1].angular_velocity.y == 10.0);
    CHECK(lst->list[0].radius == 0.002 && lst->list[1].radius == 0.0015);
    const sd_scene_generator *csv = &s->generators[2];
    CHECK(csv->kind == SD_GEN_CSV && csv->list_count == 2);
    CHECK(!strcmp(csv->file, csv_path));
    CHECK(csv->list_lines[0] == 2 && csv->list_lines[1] == 5);
    CHECK(csv->list[0].velocity.x == 1.5 && csv->list[0].velocity.y == 0.5);
    CHECK(csv->list[1].position.x == 0.083 && csv->list[1].radius == 0.001);
    const sd_scene_generator *rnd = &s->generators[3];
    CHECK(rnd->kind == SD_GEN_RANDOM && rnd->number == 200);
    CHECK(rnd->radius_min == 0.0005 && rnd->radius_max == 0.0008 && rnd->velocity_jitter == 0.01);
    CHECK(rnd->box_lo.x == 0.1 && rnd->box_hi.z == 0.12);

    CHECK(s->wall_count == 2);
    CHECK(!strcmp(s->walls[0].name, "wall0") && s->walls[0].kind == 0);
    CHECK(s->walls[0].normal.z == 1.0 && s->walls[0].normal.x == 0.0 && s->walls[0].material == 1);
    CHECK(!strcmp(s->walls[1].name, "bin") && s->walls[1].kind == 1);
    CHECK(s->walls[1].open_faces == (SD_BOX_ZMAX | SD_BOX_XMIN));
    CHECK(s->walls[1].lo.x == -1.0 && s->walls[1].hi.y == 1.0);

    CHECK(s->output.directory[0] == '\0');
    CHECK(s->output.every == 7 && s->output.stats_every == 1);
    CHECK(s->output.formats == (SD_OUT_VTK | SD_OUT_CSV));

    /* Generated spheres, in id order. */
    sd_scene_spheres sp;
    st = sd_scene_generate(s, &sp, &err);
    sd_test_require(st == SD_OK, "generate", &err);
    CHECK(sp.count == 60 + 2 + 2 + 200);
    int lattice_ok = 1;
    for (int k = 0; k < 60; ++k) {
        int ix = k % 3, iy = (k / 3) % 4, iz = k / 12;
        const sd_sphere_def *d = &sp.defs[k];
        lattice_ok &= near(d->position.x, 0.002 + ix * 0.0025) && near(d->position.y, 0.003 + iy * 0.003) &&
                      near(d->position.z, 0.004 + iz * 0.0035) && d->radius == 0.001 &&
                      d->velocity.x == 0.1 && d->material == 0 && sp.gen[k] == 0 && sp.line[k] == 22;
    }
    CHECK(lattice_ok);
    CHECK(sp.defs[60].position.x == 0.05 && sp.gen[60] == 1 && sp.entry[61] == 1 && sp.line[61] == 33);
    CHECK(sp.defs[62].position.x == 0.08 && sp.line[63] == 5 && sp.gen[63] == 2);
    int random_ok = 1;
    for (size_t k = 64; k < sp.count; ++k) {
        const sd_sphere_def *d = &sp.defs[k];
        random_ok &= d->radius >= 0.0005 && d->radius <= 0.0008;
        random_ok &= d->position.x - d->radius >= 0.1 && d->position.x + d->radius <= 0.12;
        random_ok &= d->position.y - d->radius >= 0.1 && d->position.y + d->radius <= 0.12;
        random_ok &= d->position.z - d->radius >= 0.1 && d->position.z + d->radius <= 0.12;
        random_ok &= fabs(d->velocity.x) <= 0.01 && fabs(d->velocity.z) <= 0.01;
        for (size_t q = 64; q < k; ++q) {
            double dx = d->position.x - sp.defs[q].position.x, dy = d->position.y - sp.defs[q].position.y,
                   dz = d->position.z - sp.defs[q].position.z;
            random_ok &= sqrt(dx * dx + dy * dy + dz * dz) >= d->radius + sp.defs[q].radius;
        }
    }
    CHECK(random_ok);

    /* The world gets the same spheres with ids in generation order. */
    sd_world *w;
    st = sd_scene_build(s, &w, &err);
    if (st != SD_OK)
        print_err("build", &err);
    CHECK(st == SD_OK);
    if (st == SD_OK) {
        CHECK(sd_world_particle_count(w) == sp.count);
        CHECK(sd_world_wall_count(w) == 2);
        CHECK(sd_world_find_material(w, "steel") == 1);
        int ids_ok = 1;
        for (size_t k = 0; k < sp.count; ++k) {
            sd_particle_state ps;
            size_t idx = sd_world_find_particle(w, (uint64_t)k);
            ids_ok &= idx != (size_t)-1 && sd_world_get_particle(w, idx, &ps) == SD_OK;
            ids_ok &= ps.position.x == sp.defs[k].position.x && ps.radius == sp.defs[k].radius &&
                      ps.material == sp.defs[k].material;
        }
        CHECK(ids_ok);
        sd_world_destroy(w);
    }
    sd_scene_spheres_free(&sp);
    sd_scene_free(s);
}

/* ---- the random generator: deterministic, seeded, fast ------------------ */

static const char *random_scene =
    "simulation: {dt: 1e-6, steps: 1, seed: %d}\n"
    "materials: [{name: a, density: 1000, youngs_modulus: 1e7}]\n"
    "particles:\n"
    "  - {generator: random, material: a, radius: {min: %g, max: %g}, number: %d,\n"
    "     box: {min: [0, 0, 0], max: [1, 1, 1]}}\n";

static void gen_random(int seed, double rmin, double rmax, int n, sd_scene_spheres *sp)
{
    char text[1024];
    sd_scene *s;
    sd_error err;
    snprintf(text, sizeof text, random_scene, seed, rmin, rmax, n);
    sd_test_require(load(text, NULL, &s, &err) == SD_OK, "load random scene", &err);
    sd_test_require(sd_scene_generate(s, sp, &err) == SD_OK, "generate random", &err);
    sd_scene_free(s);
}

static void test_random(void)
{
    printf("random generator\n");
    sd_scene_spheres a, b, c;
    gen_random(5, 0.01, 0.02, 3000, &a);
    gen_random(5, 0.01, 0.02, 3000, &b);
    gen_random(6, 0.01, 0.02, 3000, &c);
    CHECK(a.count == 3000 && b.count == 3000 && c.count == 3000);
    CHECK(memcmp(a.defs, b.defs, a.count * sizeof *a.defs) == 0);
    CHECK(memcmp(a.defs, c.defs, a.count * sizeof *a.defs) != 0);
    size_t i, j;
    CHECK(sd_scene_find_overlap(a.count, a.defs, 0.0, &i, &j) == 0);
    /* The grid search agrees with brute force on a pair made to overlap. */
    a.defs[2500].position = a.defs[1200].position;
    a.defs[2500].position.x += 0.5 * a.defs[1200].radius;
    CHECK(sd_scene_find_overlap(a.count, a.defs, 1e-6, &i, &j) == 1);
    size_t bi = 0, bj = 0;
    int found = 0;
    for (size_t q = 0; q < a.count && !found; ++q)
        for (size_t p = 0; p < q && !found; ++p) {
            double dx = a.defs[p].position.x - a.defs[q].position.x,
                   dy = a.defs[p].position.y - a.defs[q].position.y,
                   dz = a.defs[p].position.z - a.defs[q].position.z;
            if (a.defs[p].radius + a.defs[q].radius - sqrt(dx * dx + dy * dy + dz * dz) >
                1e-6 * fmin(a.defs[p].radius, a.defs[q].radius)) {
                bi = p;
                bj = q;
                found = 1;
            }
        }
    CHECK(found && i == bi && j == bj);
    sd_scene_spheres_free(&a);
    sd_scene_spheres_free(&b);
    sd_scene_spheres_free(&c);

    /* 1e5 spheres: the cell grid keeps this well under a second (printed,
     * not asserted: tests never check a time). */
    clock_t t0 = clock();
    gen_random(1, 0.003, 0.004, 100000, &a);
    double secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
    printf("  100000 random spheres placed in %.3f s\n", secs);
    CHECK(a.count == 100000);
    CHECK(sd_scene_find_overlap(a.count, a.defs, 0.0, &i, &j) == 0);
    sd_scene_spheres_free(&a);
}

/* ---- the example scene in the docs, and the docs themselves ------------- */

static void test_example_and_docs(void)
{
    printf("documented example and docs/scene-format.md\n");
    sd_scene *s;
    sd_error err;
    sd_world *w;
    sd_status st = load(sd_scene_example, NULL, &s, &err);
    if (st != SD_OK)
        print_err("example", &err);
    CHECK(st == SD_OK);
    if (st == SD_OK) {
        st = sd_scene_build(s, &w, &err);
        if (st != SD_OK)
            print_err("example build", &err);
        CHECK(st == SD_OK);
        if (st == SD_OK)
            sd_world_destroy(w);
        sd_scene_free(s);
    }

    /* Every key of the table appears in both help forms. */
    char *text = NULL, *md = NULL;
    size_t tn = 0, mn = 0;
    FILE *f = open_memstream(&text, &tn);
    sd_scene_print_keys(f, 0);
    fclose(f);
    f = open_memstream(&md, &mn);
    sd_scene_print_keys(f, 1);
    fclose(f);
    int all = 1;
    for (size_t k = 0; k < sd_scene_key_count; ++k) {
        char tick[80];
        snprintf(tick, sizeof tick, "`%s`", sd_scene_keys[k].key);
        all &= strstr(text, sd_scene_keys[k].key) != NULL && strstr(md, tick) != NULL;
    }
    CHECK(all);
    CHECK(strstr(md, sd_scene_example) != NULL);

    /* docs/scene-format.md is exactly what the table prints: regenerate it
     * with `shapedem help scene --markdown > docs/scene-format.md`. */
    const char *src = getenv("SD_SOURCE_DIR");
    if (src) {
        char path[512];
        snprintf(path, sizeof path, "%s/docs/scene-format.md", src);
        FILE *d = fopen(path, "rb");
        CHECK(d != NULL);
        if (d) {
            char *doc = malloc(mn + 2);
            size_t got = fread(doc, 1, mn + 1, d);
            fclose(d);
            int same = got == mn && memcmp(doc, md, mn) == 0;
            if (!same)
                printf("  docs/scene-format.md is stale: run `shapedem help scene --markdown > "
                       "docs/scene-format.md`\n");
            CHECK(same);
            free(doc);
        }
    }
    free(text);
    free(md);
}

/* ---- bad scenes --------------------------------------------------------- */

typedef struct bad_case {
    const char *name;
    const char *yaml;
    const char *csv;  /* written as spheres.csv beside the scene, or NULL */
    int line;
    const char *key;
    const char *msg;  /* a part of the message */
    int csv_file;     /* 1: the error names the CSV file */
} bad_case;

/* A small good scene, line by line, that the cases below vary. */
#define SIM "simulation:\n  dt: 1.0e-6\n  steps: 10\n"                           /* 1-3 */
#define MAT "materials:\n  - name: glass\n    density: 2500\n    youngs_modulus: 1.0e7\n" /* 4-7 */
#define PARTS                                                                                      \
    "particles:\n  - generator: list\n    material: glass\n    spheres:\n"                          \
    "      - {position: [0, 0, 0.01], radius: 0.001}\n"                                             \
    "      - {position: [0.003, 0, 0.01], radius: 0.001}\n" /* 8-13 */

static const bad_case bad_cases[] = {
    {"good scene as a control", SIM MAT PARTS, NULL, 0, "", "", 0},
    {"unknown top-level key", "simulaton:\n  dt: 1\n", NULL, 1, "simulaton", "did you mean 'simulation'", 0},
    {"unknown material key", SIM "materials:\n  - name: glass\n    densty: 2500\n" PARTS, NULL, 6,
     "materials[0].densty", "unknown key", 0},
    {"string for a number", SIM "materials:\n  - name: glass\n    density: abc\n" PARTS, NULL, 6,
     "materials[0].density", "expected a number > 0, got abc", 0},
    {"quoted number", SIM "materials:\n  - name: glass\n    density: \"2500\"\n" PARTS, NULL, 6,
     "materials[0].density", "expected a number", 0},
    {"zero density", SIM "materials:\n  - name: glass\n    density: 0\n" PARTS, NULL, 6,
     "materials[0].density", "expected a number > 0, got 0", 0},
    {"restitution 0", SIM MAT "    restitution: 0\n" PARTS, NULL, 8, "materials[0].restitution",
     "in (0, 1]", 0},
    {"restitution 1.5", SIM MAT "    restitution: 1.5\n" PARTS, NULL, 8, "materials[0].restitution",
     "got 1.5", 0},
    {"poisson ratio 0.5", SIM MAT "    poisson_ratio: 0.5\n" PARTS, NULL, 8,
     "materials[0].poisson_ratio", "in (-1, 0.5)", 0},
    {"negative radius", SIM MAT "particles:\n  - generator: list\n    material: glass\n    spheres:\n"
                                "      - {position: [0, 0, 0.01], radius: -0.001}\n",
     NULL, 12, "particles[0].spheres[0].radius", "expected a number > 0, got -0.001", 0},
    {"missing dt", "simulation:\n  steps: 10\n" MAT PARTS, NULL, 1, "simulation.dt", "missing", 0},
    {"steps and duration", SIM "  duration: 0.1\n" MAT PARTS, NULL, 4, "simulation.duration",
     "not both", 0},
    {"no run length", "simulation:\n  dt: 1e-6\n" MAT PARTS, NULL, 1, "simulation.steps",
     "steps or duration", 0},
    {"steps not an integer", "simulation:\n  dt: 1e-6\n  steps: 2.5\n" MAT PARTS, NULL, 3,
     "simulation.steps", "expected an integer >= 0, got 2.5", 0},
    {"duplicate key", "simulation:\n  dt: 1e-6\n  dt: 2e-6\n  steps: 1\n" MAT PARTS, NULL, 3,
     "simulation.dt", "duplicate key", 0},
    {"planar mode", SIM "  dimension: 2\n" MAT PARTS, NULL, 4, "simulation.dimension",
     "planar mode not available yet", 0},
    {"gravity of length 2", SIM "  gravity: [0, -9.81]\n" MAT PARTS, NULL, 4, "simulation.gravity",
     "expected a list of 3 numbers", 0},
    {"unknown contact law", SIM "  contact_law: hooke\n" MAT PARTS, NULL, 4,
     "simulation.contact_law", "expected one of hertz_mindlin, linear", 0},
    {"duplicate material", SIM MAT "  - name: glass\n    density: 1000\n" PARTS, NULL, 8,
     "materials[1].name", "duplicate material name", 0},
    {"unknown material", SIM MAT "particles:\n  - generator: list\n    material: glas\n    spheres:\n"
                                 "      - {position: [0, 0, 0.01], radius: 0.001}\n",
     NULL, 10, "particles[0].material", "unknown material 'glas'", 0},
    {"unknown material in interaction", SIM MAT "interactions:\n  - between: [glass, wood]\n" PARTS,
     NULL, 9, "interactions[0].between", "unknown material 'wood'", 0},
    {"hertz without youngs modulus", SIM "materials:\n  - name: glass\n    density: 2500\n" PARTS, NULL,
     5, "materials[0].youngs_modulus", "hertz_mindlin", 0},
    {"linear without stiffness", SIM "  contact_law: linear\n" MAT PARTS, NULL, 6,
     "materials[0].stiffness", "linear", 0},
    {"YAML syntax error", "simulation:\n  dt: [1e-6\n  steps: 10\n" MAT, NULL, 3, "", "invalid YAML", 0},
    {"empty file", "", NULL, 1, "", "empty", 0},
    {"generator key of another kind", SIM MAT
     "particles:\n  - generator: random\n    material: glass\n    radius: 0.001\n"
     "    origin: [0, 0, 0]\n    box: {min: [0, 0, 0], max: [1, 1, 1]}\n    number: 5\n",
     NULL, 12, "particles[0].origin", "does not apply to a random generator", 0},
    {"unknown generator", SIM MAT "particles:\n  - generator: cloud\n    material: glass\n", NULL, 9,
     "particles[0].generator", "expected one of lattice, random, list, csv", 0},
    {"lattice spacing too small", SIM MAT
     "particles:\n  - generator: lattice\n    material: glass\n    radius: {min: 0.001, max: 0.002}\n"
     "    origin: [0, 0, 0]\n    spacing: 0.003\n    count: [2, 2, 2]\n",
     NULL, 13, "particles[0].spacing", "2 x the largest radius", 0},
    {"lattice count zero", SIM MAT
     "particles:\n  - generator: lattice\n    material: glass\n    radius: 0.001\n"
     "    origin: [0, 0, 0]\n    spacing: 0.003\n    count: [2, 0, 2]\n",
     NULL, 14, "particles[0].count", "expected an integer >= 1 for y, got 0", 0},
    {"radius min above max", SIM MAT
     "particles:\n  - generator: random\n    material: glass\n    radius:\n      min: 0.002\n"
     "      max: 0.001\n    box: {min: [0, 0, 0], max: [1, 1, 1]}\n    number: 5\n",
     NULL, 13, "particles[0].radius.max", "expected max >= min", 0},
    {"list entry without radius", SIM MAT
     "particles:\n  - generator: list\n    material: glass\n    spheres:\n"
     "      - {position: [0, 0, 0.01]}\n",
     NULL, 12, "particles[0].spheres[0].radius", "missing required key 'radius'", 0},
    {"wall normal zero", SIM MAT PARTS "walls:\n  - type: plane\n    point: [0, 0, 0]\n"
                                       "    normal: [0, 0, 0]\n    material: glass\n",
     NULL, 17, "walls[0].normal", "non-zero", 0},
    {"box max below min", SIM MAT PARTS "walls:\n  - type: box\n    min: [0, 0, 0]\n"
                                        "    max: [1, -1, 1]\n    material: glass\n",
     NULL, 17, "walls[0].max", "max > min", 0},
    {"unknown box face", SIM MAT PARTS "walls:\n  - type: box\n    min: [0, 0, 0]\n"
                                       "    max: [1, 1, 1]\n    open: [top]\n    material: glass\n",
     NULL, 18, "walls[0].open", "expected one of xmin", 0},
    {"unknown output format", SIM MAT PARTS "output:\n  formats: [vtk, pdf]\n", NULL, 15,
     "output.formats", "got pdf", 0},
    {"csv bad row", SIM MAT "particles:\n  - generator: csv\n    material: glass\n    file: spheres.csv\n",
     "x,y,z,radius\n0,0,0,0.001\n0.01,0,zero,0.001\n", 3, "particles[0].file",
     "column z: expected a number, got 'zero'", 1},
    {"csv missing column", SIM MAT "particles:\n  - generator: csv\n    material: glass\n    file: spheres.csv\n",
     "x,y,radius\n0,0,0.001\n", 1, "particles[0].file", "no 'z' column", 1},
    {"csv missing file", SIM MAT "particles:\n  - generator: csv\n    material: glass\n    file: nothere.csv\n",
     NULL, 11, "particles[0].file", "cannot open the CSV file", 0},
    {"random box too full", SIM MAT
     "particles:\n  - generator: random\n    material: glass\n    radius: 0.1\n"
     "    box: {min: [0, 0, 0], max: [1, 1, 1]}\n    number: 1000\n",
     NULL, 9, "particles[0].number", "placed only", 0},
    {"overlap at start", SIM MAT
     "particles:\n  - generator: list\n    material: glass\n    spheres:\n"
     "      - {position: [0, 0, 0.01], radius: 0.001}\n"
     "      - {position: [0.0015, 0, 0.01], radius: 0.001}\n",
     NULL, 13, "particles[0].spheres[1]", "overlap at the start", 0},
    {"overlap between generators", SIM MAT PARTS
     "  - generator: lattice\n    material: glass\n    radius: 0.001\n    origin: [0.003, 0.001, 0.01]\n"
     "    spacing: 0.002\n    count: [1, 1, 1]\n",
     NULL, 14, "particles[1]", "from particles[0].spheres[1] (line 13)", 0},
    {"particle below a plane", SIM MAT PARTS "walls:\n  - type: plane\n    point: [0, 0, 0.0105]\n"
                                             "    normal: [0, 0, 1]\n    material: glass\n",
     NULL, 12, "particles[0].spheres[0]", "behind plane 'wall0'", 0},
    {"particle through a box face", SIM MAT PARTS "walls:\n  - type: box\n    min: [-0.002, -0.002, 0]\n"
                                                  "    max: [0.0035, 0.002, 0.02]\n    material: glass\n",
     NULL, 13, "particles[0].spheres[1]", "closed xmax face", 0},
    {"time step above the stability limit", "simulation:\n  dt: 1.0e-3\n  steps: 10\n" MAT PARTS, NULL,
     2, "simulation.dt", "time step above the stability limit", 0},
};

static void test_bad_scenes(void)
{
    printf("bad scenes\n");
    size_t n = sizeof bad_cases / sizeof bad_cases[0];
    for (size_t c = 0; c < n; ++c) {
        const bad_case *b = &bad_cases[c];
        sd_scene *s = NULL;
        sd_world *w = NULL;
        sd_error err;
        sd_status st = load(b->yaml, b->csv, &s, &err);
        if (st == SD_OK) {
            st = sd_scene_build(s, &w, &err);
            CHECK((st == SD_OK) == (w != NULL));
            sd_world_destroy(w);
            sd_scene_free(s);
        } else {
            CHECK(s == NULL);
        }
        char buf[1200];
        sd_error_format(&err, buf, sizeof buf);
        int ok;
        if (b->line == 0) {
            ok = st == SD_OK;
        } else {
            const char *want_file = b->csv_file ? csv_path : scene_path;
            ok = st == SD_ERR_INPUT && err.line == b->line && !strcmp(err.key, b->key) &&
                 !strcmp(err.file, want_file) && strstr(err.msg, b->msg) != NULL &&
                 !strchr(buf, '\n');
        }
        printf("  %s %-40s %s\n", ok ? "ok  " : "FAIL", b->name, st == SD_OK ? "(loaded and built)" : buf);
        if (!ok && b->line)
            printf("       expected line %d key '%s' message containing '%s'\n", b->line, b->key, b->msg);
        CHECK(ok);
    }
    /* A scene file that is not there. */
    sd_scene *s;
    sd_error err;
    CHECK(sd_scene_load("/nonexistent/scene.yaml", &s, &err) != SD_OK && s == NULL);
    CHECK(!strcmp(err.file, "/nonexistent/scene.yaml") && strstr(err.msg, "cannot open"));
}

/* Every allocation of load and build may fail: the result is then
 * SD_ERR_MEMORY (never a crash, never a half-made scene or world); the
 * sanitizer build also proves nothing leaks on these paths. */
static void test_out_of_memory(void)
{
    printf("out of memory at each allocation\n");
    write_file(scene_path, good_scene);
    int ok = 1, failures_seen = 0;
    for (long n = 1; n <= 400; ++n) {
        sd_scene *s = NULL;
        sd_world *w = NULL;
        sd_error err;
        write_file(csv_path, good_csv);
        sd_alloc_fail_after(n);
        sd_status st = sd_scene_load(scene_path, &s, &err);
        if (st == SD_OK) {
            st = sd_scene_build(s, &w, &err);
            ok &= (st == SD_OK) == (w != NULL);
        } else {
            ok &= s == NULL;
        }
        sd_alloc_fail_after(0);
        ok &= st == SD_OK || st == SD_ERR_MEMORY;
        failures_seen += st == SD_ERR_MEMORY;
        sd_world_destroy(w);
        sd_scene_free(s);
        if (st == SD_OK)
            break; /* n is past the last allocation */
    }
    CHECK(ok);
    CHECK(failures_seen > 5);
}

int main(void)
{
    snprintf(dir, sizeof dir, "/tmp/sd_test_scene_XXXXXX");
    sd_test_require(mkdtemp(dir) != NULL, "mkdtemp", NULL);
    snprintf(scene_path, sizeof scene_path, "%s/scene.yaml", dir);
    snprintf(csv_path, sizeof csv_path, "%s/spheres.csv", dir);

    test_good_scene();
    test_out_of_memory();
    test_random();
    test_example_and_docs();
    test_bad_scenes();

    remove(scene_path);
    remove(csv_path);
    rmdir(dir);
    return sd_test_summary();
}
