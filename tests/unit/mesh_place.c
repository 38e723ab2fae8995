/* mesh_place.c — placing a mesh wall in a scene (io/scene_mesh.c,
 * docs/mesh-walls.md): world = position + R (scale x_file), with R from
 * `rotation: [rx, ry, rz]` (degrees, rx about x first, then ry about y,
 * then rz about z, fixed axes) or from the quaternion `orientation`.
 * Checked on the vertices the world holds (sd_world_get_mesh):
 *  - rotation [90, 0, 0] is orientation [cos 45, sin 45, 0, 0];
 *  - rotation [30, 45, 60] with scale and position is Rz Ry Rx worked out
 *    here with matrices;
 *  - [0, 0, 90] turns the file's x axis onto y;
 *  - both keys at once are refused (SD_ERR_INPUT, the message naming the
 *    key and the other key's line).
 */
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include <shapedem/scene.h>
#include <string.h>

#define PI 3.14159265358979323846

static char dir[256];

/* Loads a scene with one mesh wall (a triangle) placed by `place`, and
 * copies its world vertices into v (9 numbers). */
static sd_status sd_place(const char *place, double v[9], sd_error *err)
{
    char path[400];
    snprintf(path, sizeof path, "%s/place.yaml", dir);
    FILE *f = fopen(path, "w");
    sd_test_require(f != NULL, path, NULL);
    fprintf(f,
            "simulation: {dt: 1.0e-5, steps: 1, gravity: [0, 0, -9.81]}\n"
            "materials: [{name: m, density: 2500, youngs_modulus: 1.0e7}]\n"
            "particles: [{generator: list, material: m, spheres: [{position: [5, 5, 5], radius: 0.001}]}]\n"
            "walls:\n"
            "  - type: mesh\n"
            "    file: tri.obj\n"
            "    material: m\n"
            "%s",
            place);
    fclose(f);
    sd_scene *s;
    sd_status st = sd_scene_load(path, &s, err);
    if (st != SD_OK)
        return st;
    sd_world *w;
    sd_test_require(sd_scene_build(s, &w, err) == SD_OK, "build", err);
    sd_mesh_info mi;
    CHECK(sd_world_get_mesh(w, 0, &mi) == SD_OK);
    CHECK(mi.vertex_count == 3);
    memcpy(v, mi.vertices, 9 * sizeof *v);
    sd_world_destroy(w);
    sd_scene_free(s);
    return SD_OK;
}

static void sd_rot(int axis, double deg, double R[3][3])
{
    double c = cos(deg * PI / 180.0), s = sin(deg * PI / 180.0);
    memset(R, 0, 9 * sizeof(double));
    int a = (axis + 1) % 3, b = (axis + 2) % 3;
    R[axis][axis] = 1;
    R[a][a] = c;
    R[a][b] = -s;
    R[b][a] = s;
    R[b][b] = c;
}

static void sd_mul(double A[3][3], double B[3][3], double C[3][3])
{
    double T[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            T[i][j] = A[i][0] * B[0][j] + A[i][1] * B[1][j] + A[i][2] * B[2][j];
    memcpy(C, T, sizeof T);
}

int main(void)
{
    snprintf(dir, sizeof dir, "%s/sd_mesh_place_XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    sd_test_require(mkdtemp(dir) != NULL, "mkdtemp", NULL);
    char path[400];
    snprintf(path, sizeof path, "%s/tri.obj", dir);
    FILE *f = fopen(path, "w");
    sd_test_require(f != NULL, path, NULL);
    const double file[9] = {1, 0, 0, 0, 2, 0, 0, 0, 3}; /* one triangle, file units */
    fprintf(f, "v 1 0 0\nv 0 2 0\nv 0 0 3\nf 1 2 3\n");
    fclose(f);

    sd_error err;
    double a[9], b[9];
    CHECK(sd_place("    rotation: [90, 0, 0]\n", a, &err) == SD_OK);
    CHECK(sd_place("    orientation: [0.7071067811865476, 0.7071067811865476, 0, 0]\n", b, &err) == SD_OK);
    double d = 0;
    for (int k = 0; k < 9; ++k)
        d = fmax(d, fabs(a[k] - b[k]));
    CHECK_NEAR("rotation [90,0,0] vs orientation quaternion", d, 0.0, 1e-14);
    CHECK_NEAR("rotation [90,0,0]: file y (0,2,0) goes to z", a[5], 2.0, 1e-15);

    CHECK(sd_place("    rotation: [0, 0, 90]\n", a, &err) == SD_OK);
    CHECK_NEAR("rotation [0,0,90]: file x (1,0,0) goes to y", a[1], 1.0, 1e-15);
    CHECK_NEAR("rotation [0,0,90]: ... and leaves x", a[0], 0.0, 1e-15);

    CHECK(sd_place("    scale: 0.001\n    rotation: [30, 45, 60]\n    position: [0.1, -0.2, 0.3]\n", a, &err) ==
          SD_OK);
    double Rx[3][3], Ry[3][3], Rz[3][3], R[3][3];
    sd_rot(0, 30, Rx);
    sd_rot(1, 45, Ry);
    sd_rot(2, 60, Rz);
    sd_mul(Ry, Rx, R);
    sd_mul(Rz, R, R);
    const double pos[3] = {0.1, -0.2, 0.3};
    d = 0;
    for (int v = 0; v < 3; ++v)
        for (int i = 0; i < 3; ++i) {
            double e = pos[i];
            for (int j = 0; j < 3; ++j)
                e += R[i][j] * 0.001 * file[3 * v + j];
            d = fmax(d, fabs(a[3 * v + i] - e));
        }
    CHECK_NEAR("rotation [30,45,60], scale, position vs Rz Ry Rx by hand", d, 0.0, 1e-14);

    memset(&err, 0, sizeof err);
    sd_status st = sd_place("    rotation: [90, 0, 0]\n    orientation: identity\n", a, &err);
    printf("both keys: status %d, %s:%d key '%s': %s\n", (int)st, err.file, err.line, err.key, err.msg);
    CHECK(st == SD_ERR_INPUT);
    CHECK(strstr(err.key, "rotation") != NULL);
    CHECK(strstr(err.msg, "line 9") != NULL);
    return sd_test_summary();
}
