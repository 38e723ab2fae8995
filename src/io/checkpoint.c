/* checkpoint.c — HDF5 checkpoints (io/checkpoint.h, docs/checkpoints.md):
 * a snapshot (world/snapshot.h) to an in-memory HDF5 image and back, the
 * atomic file write, and the public calls of shapedem/scene.h.
 *
 * One writer for every file: the items of a snapshot, each one dataset
 * with its attributes, and the root's attributes. A serial write takes
 * every item's rows whole; a collective one (mpi/ckpt.c) the runs of rows
 * each MPI process holds. The build compiles this file twice where a
 * parallel HDF5 is found (CMakeLists.txt): against the serial library for
 * libshapedem and shapedem, and with SHAPEDEM_HDF5_MPIIO against the MPI
 * one for shapedem-mpi, which then writes through MPI-IO.
 *
 * Invariant: the reader never trusts a size it read: every dataset is
 * checked for its type, rank, and bytes no more than the image holds
 * before anything is allocated, and the checksum of the data read is
 * compared with the one the writer stored before the snapshot is handed
 * out. HDF5's own error printing is off (the message is ours).
 */
#define _POSIX_C_SOURCE 200809L

#include "io/checkpoint.h"

#include <errno.h>
#include <fcntl.h>
#include <unistd.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hdf5.h>
#ifdef SHAPEDEM_HDF5_MPIIO
#include <mpi.h>
#endif

#include <shapedem/scene.h>

#include "core/alloc.h"
#include "core/error.h"
#include "io/fsutil.h"

#define SD_CKPT_FORMAT "shapedem checkpoint"
#define SD_CKPT_MAX_ITEMS 4096

/* HDF5 prints its error stack unless told not to; SD_HDF5_DEBUG=1 in the
 * environment keeps it (to see why HDF5 refused a file). */
void sd_h5_quiet(void)
{
    /* Before the library's first call (it is this): no HDF5 clean-up at
     * exit. A file whose H5Fclose failed (disk full: the closing flush
     * cannot write) stays in HDF5's table half destroyed, and libhdf5
     * 1.10's exit handler closing it again segfaulted after the run had
     * reported the error (probe 3 finding 4). Every file shapedem opens is
     * closed on every other path, so the handler has nothing else to do. */
    static int once;
    if (!once) {
        once = 1;
        (void)H5dont_atexit(); /* fails harmlessly when the library is running already */
    }
    const char *d = getenv("SD_HDF5_DEBUG");
    if (!d || !*d || *d == '0')
        H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
}

/* The file type of each state type (little-endian, as h5py reads it). */
static hid_t sd_h5_type(sd_state_type t)
{
    switch (t) {
    case SD_ST_F64:
        return H5T_IEEE_F64LE;
    case SD_ST_I64:
        return H5T_STD_I64LE;
    case SD_ST_U64:
        return H5T_STD_U64LE;
    case SD_ST_I32:
        return H5T_STD_I32LE;
    case SD_ST_U32:
        return H5T_STD_U32LE;
    case SD_ST_U16:
        return H5T_STD_U16LE;
    case SD_ST_U8:
    case SD_ST_BYTES:
    case SD_ST_TYPE_COUNT:
        return H5T_STD_U8LE;
    }
    return H5T_STD_U8LE;
}

/* The memory type to read or write with (the machine's order). */
static hid_t sd_h5_native(sd_state_type t)
{
    switch (t) {
    case SD_ST_F64:
        return H5T_NATIVE_DOUBLE;
    case SD_ST_I64:
        return H5T_NATIVE_INT64;
    case SD_ST_U64:
        return H5T_NATIVE_UINT64;
    case SD_ST_I32:
        return H5T_NATIVE_INT32;
    case SD_ST_U32:
        return H5T_NATIVE_UINT32;
    case SD_ST_U16:
        return H5T_NATIVE_UINT16;
    case SD_ST_U8:
    case SD_ST_BYTES:
    case SD_ST_TYPE_COUNT:
        return H5T_NATIVE_UINT8;
    }
    return H5T_NATIVE_UINT8;
}

/* ---- attributes ---------------------------------------------------------------- */

static int sd_h5_attr_write(hid_t obj, const char *name, hid_t ftype, hid_t mtype, const void *v)
{
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t a = sp < 0 ? -1 : H5Acreate2(obj, name, ftype, sp, H5P_DEFAULT, H5P_DEFAULT);
    int ok = a >= 0 && H5Awrite(a, mtype, v) >= 0;
    if (a >= 0)
        H5Aclose(a);
    if (sp >= 0)
        H5Sclose(sp);
    return ok;
}

static int sd_h5_attr_str_write(hid_t obj, const char *name, const char *s)
{
    hid_t t = H5Tcopy(H5T_C_S1);
    if (t < 0)
        return 0;
    int ok = H5Tset_size(t, strlen(s) + 1) >= 0 && H5Tset_strpad(t, H5T_STR_NULLTERM) >= 0 &&
             sd_h5_attr_write(obj, name, t, t, s);
    H5Tclose(t);
    return ok;
}

/* A scalar numeric attribute of the given class and size (the caller's
 * memory type converts); 0 when absent or of another kind. */
static int sd_h5_attr_read(hid_t obj, const char *name, H5T_class_t cls, hid_t mtype, void *v)
{
    if (H5Aexists(obj, name) <= 0)
        return 0;
    hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
    if (a < 0)
        return 0;
    hid_t sp = H5Aget_space(a), t = H5Aget_type(a);
    int ok = sp >= 0 && t >= 0 && H5Sget_simple_extent_type(sp) == H5S_SCALAR && H5Tget_class(t) == cls &&
             H5Tget_size(t) == H5Tget_size(mtype) && H5Aread(a, mtype, v) >= 0;
    if (t >= 0)
        H5Tclose(t);
    if (sp >= 0)
        H5Sclose(sp);
    H5Aclose(a);
    return ok;
}

static int sd_h5_attr_str_read(hid_t obj, const char *name, char *buf, size_t size)
{
    if (H5Aexists(obj, name) <= 0)
        return 0;
    hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
    if (a < 0)
        return 0;
    hid_t sp = H5Aget_space(a), t = H5Aget_type(a);
    int ok = 0;
    if (sp >= 0 && t >= 0 && H5Sget_simple_extent_type(sp) == H5S_SCALAR && H5Tget_class(t) == H5T_STRING &&
        H5Tis_variable_str(t) == 0) {
        size_t n = H5Tget_size(t);
        if (n > 0 && n < size) {
            hid_t mt = H5Tcopy(H5T_C_S1);
            if (mt >= 0 && H5Tset_size(mt, n) >= 0 && H5Aread(a, mt, buf) >= 0) {
                buf[n] = '\0';
                ok = 1;
            }
            if (mt >= 0)
                H5Tclose(mt);
        }
    }
    if (t >= 0)
        H5Tclose(t);
    if (sp >= 0)
        H5Sclose(sp);
    H5Aclose(a);
    return ok;
}

/* ---- writing ----------------------------------------------------------------- */

static unsigned sd_ckpt_counter; /* names of in-memory files (HDF5 keeps them apart by name) */

static hid_t sd_h5_core_fapl(void)
{
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    if (fapl < 0)
        return -1;
    /* the image in memory, nothing written back */
    if (H5Pset_fapl_core(fapl, 1 << 16, 0) < 0) {
        H5Pclose(fapl);
        return -1;
    }
    return fapl;
}

/* One dataset /group/name for an item: (rows,) or (rows, values). part
 * NULL: the item's rows are the whole dataset; else this process writes
 * part's runs of it (io/checkpoint.h), with the transfer list dxpl
 * (collective: every process calls this for every item, in one order). */
static int sd_h5_write_item(hid_t file, const sd_snap_item *it, const sd_ckpt_part *part, hid_t dxpl)
{
    char group[64];
    const char *slash = strchr(it->name, '/');
    if (!slash || slash == it->name || strchr(slash + 1, '/') || !slash[1])
        return 0;
    size_t gl = (size_t)(slash - it->name);
    memcpy(group, it->name, gl);
    group[gl] = '\0';
    hid_t g = H5Lexists(file, group, H5P_DEFAULT) > 0 ? H5Gopen2(file, group, H5P_DEFAULT)
                                                      : H5Gcreate2(file, group, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0)
        return 0;
    size_t rows = part ? part->rows : it->count;
    int rank = it->comps == 1 ? 1 : 2;
    hsize_t dims[2] = {(hsize_t)rows, (hsize_t)it->comps};
    hid_t sp = H5Screate_simple(rank, dims, NULL);
    hid_t d = sp < 0 ? -1 : H5Dcreate2(g, slash + 1, sd_h5_type(it->type), sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    int ok = d >= 0;
    if (ok && rows > 0 && it->comps > 0) {
        if (!part)
            ok = H5Dwrite(d, sd_h5_native(it->type), H5S_ALL, H5S_ALL, dxpl, it->data) >= 0;
        else {
            /* this process's runs of the file's rows, from its rows in turn
             * (none selected on both sides when it writes nothing) */
            hsize_t mdims[2] = {(hsize_t)(it->count ? it->count : 1), (hsize_t)it->comps};
            hid_t ms = H5Screate_simple(rank, mdims, NULL);
            ok = ms >= 0 && H5Sselect_none(sp) >= 0 && (it->count > 0 || H5Sselect_none(ms) >= 0);
            for (size_t k = 0; ok && k < part->nseg; ++k) {
                hsize_t start[2] = {(hsize_t)part->seg[2 * k], 0}, cnt[2] = {(hsize_t)part->seg[2 * k + 1],
                                                                             (hsize_t)it->comps};
                if (cnt[0] > 0)
                    ok = H5Sselect_hyperslab(sp, H5S_SELECT_OR, start, NULL, cnt, NULL) >= 0;
            }
            ok = ok && H5Dwrite(d, sd_h5_native(it->type), ms, sp, dxpl, it->data) >= 0;
            if (ms >= 0)
                H5Sclose(ms);
        }
    }
    int type = (int)it->type;
    if (d >= 0) /* the attributes whatever happened above: collective calls */
        ok = sd_h5_attr_write(d, "type", H5T_STD_I32LE, H5T_NATIVE_INT, &type) &&
             sd_h5_attr_str_write(d, "type_name", sd_state_type_name(it->type)) && ok;
    if (d >= 0)
        H5Dclose(d);
    if (sp >= 0)
        H5Sclose(sp);
    H5Gclose(g);
    return ok;
}

/* ---- the header: a checksum of the whole file, checked before HDF5 reads
 * a byte. HDF5's metadata checksums do not cover everything (a flipped
 * byte in a dense link table made libhdf5 1.10.8 free a pointer it never
 * allocated: tests/fuzz/open), so a damaged file must never reach it.
 * Layout of the first SD_CKPT_HEADER bytes (an HDF5 user block):
 *   0..7   "SDCKPT01"
 *   8..15  uint64 LE, the file's size in bytes
 *   16..23 uint64 LE, FNV-1a 64 of bytes SD_CKPT_HEADER .. size - 1
 *   24..   zeros */
#define SD_CKPT_HEADER 512
#define SD_CKPT_MAGIC "SDCKPT01"

static void sd_put_u64(unsigned char *b, uint64_t v)
{
    for (int k = 0; k < 8; ++k)
        b[k] = (unsigned char)(v >> (8 * k));
}

static uint64_t sd_get_u64(const unsigned char *b)
{
    uint64_t v = 0;
    for (int k = 7; k >= 0; --k)
        v = (v << 8) | b[k];
    return v;
}

/* Writes the header into a closed HDF5 file made with the user block. */
static sd_status sd_ckpt_seal(const char *path, sd_error *err)
{
    FILE *fp = fopen(path, "r+b");
    if (!fp)
        return sd_error_set(err, SD_ERR_IO, path, 0, "", "cannot reopen the checkpoint: %s", strerror(errno));
    uint64_t h = SD_FNV_BASIS, size = 0;
    unsigned char buf[1 << 16];
    int ok = fseek(fp, SD_CKPT_HEADER, SEEK_SET) == 0;
    size_t got;
    while (ok && (got = fread(buf, 1, sizeof buf, fp)) > 0) {
        h = sd_fnv1a(h, buf, got);
        size += got;
    }
    ok = ok && !ferror(fp) && size > 0;
    unsigned char head[SD_CKPT_HEADER];
    memset(head, 0, sizeof head);
    memcpy(head, SD_CKPT_MAGIC, 8);
    sd_put_u64(head + 8, size + SD_CKPT_HEADER);
    sd_put_u64(head + 16, h);
    ok = ok && fseek(fp, 0, SEEK_SET) == 0 && fwrite(head, 1, sizeof head, fp) == sizeof head;
    if (fclose(fp) != 0)
        ok = 0;
    if (!ok)
        return sd_error_set(err, SD_ERR_IO, path, 0, "", "cannot write the checkpoint's header");
    return SD_OK;
}

/* The header's checks: SD_OK when the bytes are the file that was written. */
int sd_checkpoint_is_file(const char *path)
{
    unsigned char head[8];
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    size_t got = fread(head, 1, sizeof head, f);
    fclose(f);
    return got == sizeof head && memcmp(head, SD_CKPT_MAGIC, 8) == 0;
}

static sd_status sd_ckpt_check_header(const unsigned char *b, size_t size, sd_error *err)
{
    if (size < SD_CKPT_HEADER || memcmp(b, SD_CKPT_MAGIC, 8) != 0) {
        if (size >= 8 && memcmp(b, "\x89HDF\r\n\x1a\n", 8) == 0)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "an HDF5 file without a shapedem checkpoint header "
                                "(not a checkpoint, or one of an older format)");
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "not a shapedem checkpoint (no SDCKPT01 header%s)",
                            size < SD_CKPT_HEADER ? "; the file is truncated or damaged" : "");
    }
    uint64_t want = sd_get_u64(b + 8);
    if (want != (uint64_t)size)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "the file is truncated or damaged: it has %zu bytes, its "
                            "header says %llu", size, (unsigned long long)want);
    uint64_t h = sd_fnv1a(SD_FNV_BASIS, b + SD_CKPT_HEADER, size - SD_CKPT_HEADER);
    if (h != sd_get_u64(b + 16))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "the file is damaged: its checksum is %016llx, its header "
                            "says %016llx", (unsigned long long)h, (unsigned long long)sd_get_u64(b + 16));
    return SD_OK;
}

/* Writes the snapshot as an HDF5 file at path (truncated when there),
 * closed on return; sealed (sd_ckpt_seal) when parts is NULL. HDF5 writes
 * the file itself: an image taken from an open in-memory file has a
 * superblock whose checksum a reader refuses. With parts (a build with
 * SHAPEDEM_HDF5_MPIIO), every MPI process writes its parts of each item
 * through MPI-IO, collectively; the caller seals the file. */
static sd_status sd_h5_write_path(const sd_snapshot *s, const sd_ckpt_part *parts, const char *path, sd_error *err)
{
    sd_h5_quiet();
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    /* the newer object formats: their metadata carry checksums */
    if (fapl >= 0 && H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_LATEST) < 0) {
        H5Pclose(fapl);
        fapl = -1;
    }
    hid_t dxpl = H5P_DEFAULT;
#ifdef SHAPEDEM_HDF5_MPIIO
    if (parts && fapl >= 0) {
        /* one file for every process; the datasets' rows written in one
         * collective MPI-IO call per dataset */
        dxpl = H5Pcreate(H5P_DATASET_XFER);
        if (H5Pset_fapl_mpio(fapl, MPI_COMM_WORLD, MPI_INFO_NULL) < 0 || dxpl < 0 ||
            H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE) < 0) {
            H5Pclose(fapl);
            fapl = -1;
        }
    }
#endif
    /* the first SD_CKPT_HEADER bytes are an HDF5 user block: our header
     * (sd_ckpt_seal), which h5py and HDF5 skip */
    hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
    if (fcpl >= 0 && H5Pset_userblock(fcpl, SD_CKPT_HEADER) < 0) {
        H5Pclose(fcpl);
        fcpl = -1;
    }
    hid_t f = fapl < 0 || fcpl < 0 ? -1 : H5Fcreate(path, H5F_ACC_TRUNC, fcpl, fapl);
    if (fapl >= 0)
        H5Pclose(fapl);
    if (fcpl >= 0)
        H5Pclose(fcpl);
    if (f < 0) {
        if (dxpl != H5P_DEFAULT && dxpl >= 0)
            H5Pclose(dxpl);
        return sd_error_set(err, SD_ERR_IO, path, 0, "", "HDF5 cannot create the checkpoint file");
    }
    uint32_t version = s->version;
    int64_t step = s->step;
    int32_t dim = s->dimension;
    int ok = sd_h5_attr_str_write(f, "format", SD_CKPT_FORMAT) &&
             sd_h5_attr_write(f, "version", H5T_STD_U32LE, H5T_NATIVE_UINT32, &version) &&
             sd_h5_attr_write(f, "scene_hash", H5T_STD_U64LE, H5T_NATIVE_UINT64, &s->scene_hash) &&
             sd_h5_attr_write(f, "checksum", H5T_STD_U64LE, H5T_NATIVE_UINT64, &s->checksum) &&
             sd_h5_attr_write(f, "step", H5T_STD_I64LE, H5T_NATIVE_INT64, &step) &&
             sd_h5_attr_write(f, "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &s->time) &&
             sd_h5_attr_write(f, "dimension", H5T_STD_I32LE, H5T_NATIVE_INT32, &dim) &&
             sd_h5_attr_str_write(f, "solver", s->solver) && sd_h5_attr_str_write(f, "writer", s->writer);
    const char *bad = NULL;
    /* collectively every item is visited whatever failed before (a
     * process leaving the sequence would leave the others waiting) */
    for (size_t k = 0; (ok || parts) && k < s->n; ++k)
        if (!sd_h5_write_item(f, &s->items[k], parts ? &parts[k] : NULL, dxpl) && !bad) {
            ok = 0;
            bad = s->items[k].name;
        }
    if (dxpl != H5P_DEFAULT)
        H5Pclose(dxpl);
    if (!ok && !parts) {
        /* a write failed (a full disk): the file is dropped, so its blocks
         * are freed first, which leaves the closing flush of the metadata
         * room to succeed and HDF5 a clean state (sd_h5_quiet) */
        void *fd = NULL;
        if (H5Fget_vfd_handle(f, H5P_DEFAULT, &fd) >= 0 && fd)
            (void)!ftruncate(*(int *)fd, 0);
    }
    if (H5Fclose(f) < 0)
        ok = 0;
    if (!ok)
        return sd_error_set(err, SD_ERR_IO, path, 0, bad ? bad : "", "HDF5 could not write the checkpoint%s%s "
                            "(disk full?)", bad ? ": dataset " : "", bad ? bad : "");
    return parts ? SD_OK : sd_ckpt_seal(path, err);
}

sd_status sd_checkpoint_encode(const sd_snapshot *s, void **buf, size_t *size, sd_error *err)
{
    *buf = NULL;
    *size = 0;
    const char *tmp = getenv("TMPDIR");
    char path[4096];
    snprintf(path, sizeof path, "%s/shapedem-checkpoint-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    int fd = mkstemp(path);
    if (fd < 0)
        return sd_error_set(err, SD_ERR_IO, path, 0, "", "cannot make a temporary file: %s", strerror(errno));
    close(fd);
    sd_status st = sd_h5_write_path(s, NULL, path, err);
    if (st == SD_OK)
        st = sd_fs_read_all(path, "checkpoint", buf, size, err);
    remove(path);
    return st;
}

/* ---- reading ---------------------------------------------------------------- */

typedef struct sd_h5_reader {
    sd_snapshot *s;
    size_t image_size;
    sd_error *err;
    sd_status st;
} sd_h5_reader;

static sd_status sd_h5_fail(sd_h5_reader *r, const char *key, const char *what)
{
    if (r->st == SD_OK)
        r->st = sd_error_set(r->err, SD_ERR_INPUT, "", 0, key, "%s", what);
    return r->st;
}

static int sd_h5_valid_name(const char *s)
{
    if (!s[0])
        return 0;
    for (const char *c = s; *c; ++c)
        if (!((*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9') || *c == '_'))
            return 0;
    return 1;
}

static void sd_h5_read_dataset(sd_h5_reader *r, hid_t g, const char *group, const char *name)
{
    char full[128];
    snprintf(full, sizeof full, "%s/%s", group, name);
    if (strlen(group) + strlen(name) + 2 > sizeof r->s->items[0].name || !sd_h5_valid_name(name)) {
        sd_h5_fail(r, "", "a dataset name that shapedem never writes");
        return;
    }
    hid_t d = H5Dopen2(g, name, H5P_DEFAULT);
    if (d < 0) {
        sd_h5_fail(r, full, "a dataset HDF5 cannot open (damaged file?)");
        return;
    }
    int type = -1;
    hid_t sp = H5Dget_space(d), t = H5Dget_type(d);
    hsize_t dims[2] = {0, 0};
    int rank = sp >= 0 ? H5Sget_simple_extent_ndims(sp) : -1;
    if (!sd_h5_attr_read(d, "type", H5T_INTEGER, H5T_NATIVE_INT, &type) || type < 0 || type >= SD_ST_TYPE_COUNT)
        sd_h5_fail(r, full, "a dataset without shapedem's type attribute");
    else if (t < 0 || (rank != 1 && rank != 2) || H5Sget_simple_extent_dims(sp, dims, NULL) != rank)
        sd_h5_fail(r, full, "a dataset of another rank than 1 or 2");
    else {
        sd_state_type st = (sd_state_type)type;
        H5T_class_t want = st == SD_ST_F64 ? H5T_FLOAT : H5T_INTEGER;
        size_t es = sd_state_type_size(st);
        hsize_t count = dims[0], comps = rank == 2 ? dims[1] : 1;
        if (H5Tget_class(t) != want || H5Tget_size(t) != es)
            sd_h5_fail(r, full, "a dataset whose HDF5 type is not its shapedem type");
        /* an empty dataset holds no bytes whatever its row size (a world
         * without insertions saves its process record of ~100 kB so) */
        else if (comps == 0 || (rank == 2 && comps == 1) || comps > ((hsize_t)1 << 32) ||
                 (count > 0 && (count > r->image_size || comps > r->image_size ||
                                count * comps > r->image_size / es)))
            sd_h5_fail(r, full, "a dataset larger than the file holds (damaged file?)");
        else if (r->s->n >= SD_CKPT_MAX_ITEMS)
            sd_h5_fail(r, full, "more datasets than shapedem writes");
        else {
            sd_snap_item *it = sd_snapshot_add(r->s, full, st, (size_t)comps, (size_t)count, NULL);
            if (!it)
                r->st = sd_error_set(r->err, SD_ERR_MEMORY, "", 0, full, "out of memory");
            else if (count > 0 && H5Dread(d, sd_h5_native(st), H5S_ALL, H5S_ALL, H5P_DEFAULT, it->data) < 0)
                sd_h5_fail(r, full, "a dataset HDF5 cannot read (damaged file?)");
        }
    }
    if (t >= 0)
        H5Tclose(t);
    if (sp >= 0)
        H5Sclose(sp);
    H5Dclose(d);
}

/* Children of a group by index (the same calls in HDF5 1.10 and 1.12+),
 * in the name index's native order (the items are sorted by name after
 * reading): for a group with dense link storage HDF5 then walks its
 * B-tree of names, where increasing order builds and frees a table of
 * every link for each call, the path on which damaged link records
 * (bit flips with a resealed checksum, issue 31) made libhdf5 free
 * invalid pointers. */
static char *sd_h5_child_name(hid_t g, hsize_t k, char *buf, size_t size)
{
    ssize_t n = H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_NATIVE, k, NULL, 0, H5P_DEFAULT);
    if (n <= 0 || (size_t)n >= size)
        return NULL;
    if (H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_NATIVE, k, buf, size, H5P_DEFAULT) != n)
        return NULL;
    return buf;
}

static void sd_h5_read_all(sd_h5_reader *r, hid_t f)
{
    H5G_info_t gi;
    if (H5Gget_info(f, &gi) < 0) {
        sd_h5_fail(r, "", "the file's root group cannot be read (damaged file?)");
        return;
    }
    if (gi.nlinks > 64) {
        sd_h5_fail(r, "", "more groups than shapedem writes");
        return;
    }
    for (hsize_t k = 0; r->st == SD_OK && k < gi.nlinks; ++k) {
        char group[64];
        if (!sd_h5_child_name(f, k, group, sizeof group) || !sd_h5_valid_name(group)) {
            sd_h5_fail(r, "", "a group name that shapedem never writes (damaged file?)");
            return;
        }
        hid_t o = H5Oopen(f, group, H5P_DEFAULT);
        if (o < 0 || H5Iget_type(o) != H5I_GROUP) {
            if (o >= 0)
                H5Oclose(o);
            sd_h5_fail(r, group, "an object at the root that is not a group");
            return;
        }
        H5G_info_t ci;
        if (H5Gget_info(o, &ci) < 0 || ci.nlinks > SD_CKPT_MAX_ITEMS) {
            H5Oclose(o);
            sd_h5_fail(r, group, "a group that cannot be read or holds too many datasets");
            return;
        }
        for (hsize_t j = 0; r->st == SD_OK && j < ci.nlinks; ++j) {
            char name[64];
            if (!sd_h5_child_name(o, j, name, sizeof name)) {
                sd_h5_fail(r, group, "a dataset name that cannot be read (damaged file?)");
                break;
            }
            sd_h5_read_dataset(r, o, group, name);
        }
        H5Oclose(o);
    }
}

sd_status sd_checkpoint_decode(const void *buf, size_t size, sd_snapshot *out, sd_error *err)
{
    sd_snapshot_init(out);
    sd_h5_quiet();
    sd_status hst = sd_ckpt_check_header(buf, size, err);
    if (hst != SD_OK)
        return hst;
    hid_t fapl = sd_h5_core_fapl();
    /* the image is copied by HDF5 (no callbacks): buf stays the caller's */
    if (fapl >= 0 && H5Pset_file_image(fapl, (void *)(uintptr_t)buf, size) < 0) {
        H5Pclose(fapl);
        fapl = -1;
    }
    char name[64];
    snprintf(name, sizeof name, "sd-checkpoint-in-%u.h5", sd_ckpt_counter++);
    hid_t f = fapl < 0 ? -1 : H5Fopen(name, H5F_ACC_RDONLY, fapl);
    if (fapl >= 0)
        H5Pclose(fapl);
    if (f < 0)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "HDF5 cannot open it: the file is truncated or damaged "
                            "(%zu bytes)", size);
    sd_h5_reader r = {.s = out, .image_size = size, .err = err, .st = SD_OK};
    char format[64] = "";
    uint32_t version = 0;
    int64_t step = 0;
    int32_t dim = 0;
    uint64_t checksum = 0;
    if (!sd_h5_attr_str_read(f, "format", format, sizeof format) || strcmp(format, SD_CKPT_FORMAT) != 0)
        sd_h5_fail(&r, "", "an HDF5 file, but not a shapedem checkpoint (no format attribute '" SD_CKPT_FORMAT "')");
    else if (!sd_h5_attr_read(f, "version", H5T_INTEGER, H5T_NATIVE_UINT32, &version))
        sd_h5_fail(&r, "", "a checkpoint without its format version");
    else if (version < SD_SNAPSHOT_VERSION_OLDEST || version > SD_SNAPSHOT_VERSION) {
        r.st = sd_error_set(err, SD_ERR_INPUT, "", 0, "", "checkpoint format version %u; this shapedem (%s) reads "
                            "versions %u to %u", version, SD_VERSION_STRING, SD_SNAPSHOT_VERSION_OLDEST,
                            SD_SNAPSHOT_VERSION);
    } else if (!sd_h5_attr_read(f, "scene_hash", H5T_INTEGER, H5T_NATIVE_UINT64, &out->scene_hash) ||
               !sd_h5_attr_read(f, "checksum", H5T_INTEGER, H5T_NATIVE_UINT64, &checksum) ||
               !sd_h5_attr_read(f, "step", H5T_INTEGER, H5T_NATIVE_INT64, &step) ||
               !sd_h5_attr_read(f, "time", H5T_FLOAT, H5T_NATIVE_DOUBLE, &out->time) ||
               !sd_h5_attr_read(f, "dimension", H5T_INTEGER, H5T_NATIVE_INT32, &dim) ||
               !sd_h5_attr_str_read(f, "solver", out->solver, sizeof out->solver) ||
               !sd_h5_attr_str_read(f, "writer", out->writer, sizeof out->writer))
        sd_h5_fail(&r, "", "a checkpoint that lacks one of its root attributes (scene_hash, checksum, step, time, "
                   "dimension, solver, writer)");
    if (r.st == SD_OK)
        sd_h5_read_all(&r, f);
    H5Fclose(f);
    if (r.st != SD_OK) {
        sd_snapshot_free(out);
        return r.st;
    }
    out->version = version;
    out->step = (long)step;
    out->dimension = dim;
    sd_snapshot_sort(out);
    for (size_t k = 1; k < out->n; ++k)
        if (strcmp(out->items[k - 1].name, out->items[k].name) == 0) {
            sd_snapshot_free(out);
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "a dataset appears twice");
        }
    uint64_t sum = sd_snapshot_checksum(out);
    if (sum != checksum) {
        sd_snapshot_free(out);
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "the file is damaged: its data's checksum is %016llx, "
                            "the file says %016llx", (unsigned long long)sum, (unsigned long long)checksum);
    }
    out->checksum = sum;
    return SD_OK;
}

sd_status sd_checkpoint_read_file(const char *path, sd_snapshot *out, sd_error *err)
{
    sd_snapshot_init(out);
    void *buf;
    size_t n;
    sd_status st = sd_fs_read_all(path, "checkpoint", &buf, &n, err);
    if (st != SD_OK)
        return st;
    st = sd_checkpoint_decode(buf, n, out, err);
    sd_free(buf);
    if (st != SD_OK && err) {
        snprintf(err->file, sizeof err->file, "%s", path);
        err->line = 0;
    }
    return st;
}

/* Makes a finished file durable before it gets its name, and the rename
 * durable after (best effort on file systems that refuse a directory
 * fsync). */
static int sd_fsync_path(const char *path)
{
    int fd = open(path, O_RDONLY);
    if (fd < 0)
        return -1;
    int r = fsync(fd);
    close(fd);
    return r;
}

/* The temporary beside path (rename stays on one file system):
 * dir/.name.tmp, sd_malloc'd; NULL out of memory. */
static char *sd_ckpt_tmp_name(const char *path)
{
    size_t len = strlen(path);
    const char *slash = strrchr(path, '/');
    size_t dl = slash ? (size_t)(slash - path) + 1 : 0;
    char *tmp = sd_malloc(len + 6);
    if (!tmp)
        return NULL;
    memcpy(tmp, path, dl);
    tmp[dl] = '.';
    memcpy(tmp + dl + 1, path + dl, len - dl);
    memcpy(tmp + len + 1, ".tmp", 5);
    return tmp;
}

/* A written temporary made durable and renamed to path (st: how its
 * writing went); removed on any failure. */
static sd_status sd_ckpt_finish(sd_status st, const char *tmp, const char *path, sd_error *err)
{
    if (st == SD_OK && sd_fsync_path(tmp) != 0)
        st = sd_error_set(err, SD_ERR_IO, tmp, 0, "", "cannot flush the checkpoint to disk: %s", strerror(errno));
    if (st == SD_OK && rename(tmp, path) != 0)
        st = sd_error_set(err, SD_ERR_IO, path, 0, "", "cannot rename the finished checkpoint into place: %s",
                          strerror(errno));
    if (st != SD_OK) {
        remove(tmp);
        return st;
    }
    const char *slash = strrchr(path, '/');
    size_t dl = slash ? (size_t)(slash - path) + 1 : 0;
    char *dir = sd_malloc(dl + 2);
    if (dir) {
        if (dl)
            memcpy(dir, path, dl);
        else
            dir[dl++] = '.';
        dir[dl] = '\0';
        (void)sd_fsync_path(dir);
        sd_free(dir);
    }
    return SD_OK;
}

sd_status sd_checkpoint_write_file(const sd_snapshot *s, const char *path, sd_error *err)
{
    char *tmp = sd_ckpt_tmp_name(path);
    if (!tmp)
        return sd_error_set(err, SD_ERR_MEMORY, path, 0, "", "out of memory");
    const char *what = sd_fs_not_regular(tmp);
    sd_status st = what ? sd_error_set(err, SD_ERR_IO, tmp, 0, "", "cannot write the checkpoint: %s is in the way",
                                       what)
                        : sd_ckpt_finish(sd_h5_write_path(s, NULL, tmp, err), tmp, path, err);
    sd_free(tmp);
    return st;
}

int sd_checkpoint_collective(void)
{
#ifdef SHAPEDEM_HDF5_MPIIO
    return 1;
#else
    return 0;
#endif
}

sd_status sd_checkpoint_write_collective(const sd_snapshot *s, const sd_ckpt_part *parts, const char *path,
                                         sd_error *err)
{
#ifdef SHAPEDEM_HDF5_MPIIO
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    char *tmp = sd_ckpt_tmp_name(path);
    const char *what = tmp ? sd_fs_not_regular(tmp) : NULL;
    /* every process takes the same way: rank 0's look at the temporary,
     * and every process's name for it */
    int mine = tmp && (rank != 0 || !what), go = 0;
    MPI_Allreduce(&mine, &go, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD);
    sd_status st = SD_OK;
    if (!go)
        st = what ? sd_error_set(err, SD_ERR_IO, tmp, 0, "", "cannot write the checkpoint: %s is in the way", what)
                  : sd_error_set(err, SD_ERR_MEMORY, path, 0, "", "out of memory");
    else {
        st = sd_h5_write_path(s, parts, tmp, err); /* collective; closed on every process on return */
        int ok = st == SD_OK, all = 0;
        MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD); /* every process has closed it */
        if (rank == 0) {
            if (all && st == SD_OK)
                st = sd_ckpt_seal(tmp, err);
            else if (st == SD_OK)
                st = sd_error_set(err, SD_ERR_IO, path, 0, "", "HDF5 could not write the checkpoint on another "
                                  "process (disk full?)");
            st = sd_ckpt_finish(st, tmp, path, err);
        }
    }
    int code = (int)st; /* rank 0's status on every process */
    MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
    st = (sd_status)code;
    sd_free(tmp);
    return st;
#else
    (void)s;
    (void)parts;
    return sd_error_set(err, SD_ERR_INTERNAL, path, 0, "", "this build writes checkpoints from one process (its "
                        "HDF5 has no MPI-IO)");
#endif
}

/* ---- the public calls (shapedem/scene.h) -------------------------------------- */

sd_status sd_checkpoint_write(const sd_world *w, const char *path, sd_error *err)
{
    if (!w || !path)
        return sd_error_null(err, "sd_checkpoint_write", !w ? "world" : "path");
    sd_snapshot s;
    sd_status st = sd_world_snapshot(w, &s, err);
    if (st != SD_OK)
        return st;
    st = sd_checkpoint_write_file(&s, path, err);
    sd_snapshot_free(&s);
    return st;
}

sd_status sd_checkpoint_restore(sd_world *w, const char *path, sd_error *err)
{
    if (!w || !path)
        return sd_error_null(err, "sd_checkpoint_restore", !w ? "world" : "path");
    sd_snapshot s;
    sd_status st = sd_checkpoint_read_file(path, &s, err);
    if (st == SD_OK) {
        st = sd_world_restore(w, &s, err);
        if (st != SD_OK && err) {
            snprintf(err->file, sizeof err->file, "%s", path);
            err->line = 0;
        }
    }
    sd_snapshot_free(&s);
    return st;
}

sd_status sd_checkpoint_print(FILE *f, const char *path, sd_error *err)
{
    if (!f || !path)
        return sd_error_null(err, "sd_checkpoint_print", !f ? "f" : "path");
    sd_snapshot s;
    sd_status st = sd_checkpoint_read_file(path, &s, err);
    if (st != SD_OK) {
        sd_snapshot_free(&s);
        return st;
    }
    uint64_t n = 0, ng = 0, np = 0, nwp = 0, gn = 0;
    sd_snapshot_get_u64(&s, "particles/n", &n);
    sd_snapshot_get_u64(&s, "ghosts/n", &ng);
    sd_snapshot_get_u64(&s, "pairs/n", &np);
    sd_snapshot_get_u64(&s, "wall_pairs/n", &nwp);
    sd_snapshot_get_u64(&s, "grid/n", &gn);
    const sd_snap_item *walls = sd_snapshot_find(&s, "walls/force");
    size_t bytes = 0;
    for (size_t k = 0; k < s.n; ++k)
        bytes += s.items[k].count * s.items[k].comps * sd_state_type_size(s.items[k].type);
    fprintf(f, "checkpoint   %s\n", path);
    fprintf(f, "format       " SD_CKPT_FORMAT " version %u, written by shapedem %s\n", s.version, s.writer);
    fprintf(f, "scene hash   %016llx\n", (unsigned long long)s.scene_hash);
    fprintf(f, "checksum     %016llx (verified)\n", (unsigned long long)s.checksum);
    fprintf(f, "run          %dD, solver %s, step %ld, t = %.9g s\n", s.dimension, s.solver, s.step, s.time);
    fprintf(f, "particles    %llu", (unsigned long long)(n + gn));
    if (ng)
        fprintf(f, " (and %llu periodic images)", (unsigned long long)ng);
    fprintf(f, "\n");
    if (!strcmp(s.solver, "cells"))
        fprintf(f, "pairs        %llu particle pairs, %llu particle-wall pairs (with their contact history)\n",
                (unsigned long long)np, (unsigned long long)nwp);
    fprintf(f, "walls        %zu\n", walls ? walls->count : (size_t)0);
    fprintf(f, "datasets     %zu, %zu bytes of data:\n", s.n, bytes);
    for (size_t k = 0; k < s.n; ++k) {
        const sd_snap_item *it = &s.items[k];
        fprintf(f, "  %-28s %-5s %zu x %zu\n", it->name, sd_state_type_name(it->type), it->count, it->comps);
    }
    sd_snapshot_free(&s);
    return SD_OK;
}
