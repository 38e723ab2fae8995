/* fuzz_util.h — what the fuzz targets share: a private temporary
 * directory per process, and writing an input there under a given name.
 *
 * The readers under test take paths, not buffers (they resolve a scene's
 * relative `file:` keys against the scene's directory, and the mesh reader
 * chooses STL or OBJ by the extension), so a target writes its input to a
 * file and calls the reader as `shapedem` does. The directory is removed
 * at exit; a target that fails to make it aborts (a harness problem, not a
 * finding).
 *
 * Invariant: after sd_fuzz_write the file holds exactly the bytes given.
 */
#ifndef SD_FUZZ_UTIL_H
#define SD_FUZZ_UTIL_H

#include <stddef.h>
#include <stdint.h>

#include <shapedem/shapedem.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Each target defines this: libFuzzer's entry, and replay.c's. */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The process's temporary directory (made on the first call). */
const char *sd_fuzz_dir(void);

/* Writes data[0 .. size) to sd_fuzz_dir()/name, puts that path in
 * path[0 .. path_size) and returns path. Aborts when the file cannot be
 * written. */
const char *sd_fuzz_write(const char *name, const uint8_t *data, size_t size, char *path, size_t path_size);

/* With SD_FUZZ_VERBOSE set in the environment, prints what a reader said
 * of the input (stage: "ok" or the formatted error) to stderr: to see how
 * far a corpus file gets. Silent otherwise (the fuzzer's speed). */
void sd_fuzz_report(const char *stage, sd_status st, const sd_error *err);

#ifdef __cplusplus
}
#endif

#endif
