/* info_cmd.c — `shapedem info CHECKPOINT.h5 [--csv]`: what a checkpoint
 * holds (io/checkpoint.c's summary), or with --csv its particles as CSV on
 * stdout (io/ckpt_particles.h), so that a checkpoint, a failed-NNNNNN.h5
 * included, can be looked at without HDF5 tools.
 *
 * Invariant: bad input (no file, a file that is not a checkpoint, a
 * damaged one, an unknown option) is one line on stderr naming it, exit
 * status 2, and nothing on stdout.
 */
#include "cli/commands.h"
#include "io/ckpt_particles.h"

#include <shapedem/scene.h>

#include <stdio.h>
#include <string.h>

static int sd_info_usage(FILE *f)
{
    fprintf(f, "usage: shapedem info CHECKPOINT.h5 [--csv]\n"
               "\n"
               "  what a checkpoint holds: step, time, particles, pairs, walls and its datasets\n"
               "  --csv  instead, its particles as CSV on stdout, one row each in storage order:\n"
               "         id,x,y,z,vx,vy,vz,wx,wy,wz,qw,qx,qy,qz,radius,shape,material,fx,fy,fz\n"
               "         (SI units; shape empty for a plain sphere, radius the bounding radius of a\n"
               "         shaped particle; every value to 17 digits, the checkpoint's bits)\n");
    return f == stdout ? 0 : 2;
}

int sd_cmd_info(int argc, char **argv)
{
    const char *path = NULL;
    int csv = 0;
    for (int k = 2; k < argc; ++k) {
        const char *a = argv[k];
        if (!strcmp(a, "--help") || !strcmp(a, "-h"))
            return sd_info_usage(stdout);
        if (!strcmp(a, "--csv") || (!strcmp(a, "--particles") && k + 1 < argc && !strcmp(argv[k + 1], "csv"))) {
            k += a[2] == 'p';
            csv = 1;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "shapedem: info: unknown option '%s' (see 'shapedem info --help')\n", a);
            return 2;
        } else if (!path) {
            path = a;
        } else {
            fprintf(stderr, "shapedem: info: unexpected argument '%s' (see 'shapedem info --help')\n", a);
            return 2;
        }
    }
    if (!path) {
        fprintf(stderr, "shapedem: info needs a checkpoint file (see 'shapedem info --help')\n");
        return 2;
    }
    sd_error err;
    memset(&err, 0, sizeof err);
    if (!csv) {
        if (sd_checkpoint_print(stdout, path, &err) != SD_OK)
            return sd_cli_fail_input(&err);
        return 0;
    }
    sd_ckpt_particles p;
    sd_status s = sd_ckpt_particles_read(path, &p, &err);
    if (s == SD_OK)
        s = sd_ckpt_particles_print_csv(stdout, &p, &err);
    sd_ckpt_particles_free(&p);
    if (s != SD_OK) {
        int rc = sd_cli_fail_input(&err);
        return s == SD_ERR_IO ? 1 : rc;
    }
    return 0;
}
