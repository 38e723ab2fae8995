/* error.h — filling sd_error values (errors are values: DESIGN.md rule 8). */
#ifndef SD_CORE_ERROR_H
#define SD_CORE_ERROR_H

#include <shapedem/shapedem.h>

#if defined(__GNUC__)
#define SD_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define SD_PRINTF(a, b)
#endif

/* Sets every field of err (err may be NULL) and returns code. */
sd_status sd_error_set(sd_error *err, sd_status code, const char *file, int line, const char *key,
                       const char *fmt, ...) SD_PRINTF(6, 7);
void sd_error_clear(sd_error *err);
/* The public calls' answer to a NULL handle or pointer (every call is safe
 * in every state, issue 31): SD_ERR_INPUT, "CALL: ARG is NULL". */
sd_status sd_error_null(sd_error *err, const char *call, const char *arg);

/* Writes s[0 .. len) (len (size_t)-1: up to its NUL) into buf (size >= 8)
 * with every byte that is not printable ASCII escaped: \r \n \t \\ and
 * \xNN for the rest (control bytes, ANSI escapes, non-UTF-8 garbage), so a
 * message that quotes file content cannot move the user's cursor or recolour
 * the terminal. Cut with "..." when it does not fit. Returns buf. */
const char *sd_escape(char *buf, size_t size, const char *s, size_t len);

#endif
