/* error.c — error values and their one-line text form. */
#include "core/error.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static void sd_copy(char *dst, size_t size, const char *src)
{
    if (!src)
        src = "";
    size_t n = strlen(src);
    if (n >= size)
        n = size - 1;
    memcpy(dst, src, n);
    dst[n] = '\0';
}

sd_status sd_error_set(sd_error *err, sd_status code, const char *file, int line, const char *key,
                       const char *fmt, ...)
{
    if (!err)
        return code;
    err->code = code;
    sd_copy(err->file, sizeof err->file, file);
    err->line = line;
    sd_copy(err->key, sizeof err->key, key);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    return code;
}

const char *sd_escape(char *buf, size_t size, const char *s, size_t len)
{
    static const char hex[] = "0123456789abcdef";
    if (!buf || size == 0)
        return buf;
    buf[0] = '\0';
    if (!s)
        return buf;
    size_t o = 0;
    for (size_t i = 0; i < len && s[i] != '\0'; ++i) {
        const unsigned char c = (unsigned char)s[i];
        char e[5];
        size_t k = 0;
        if (c == '\r' || c == '\n' || c == '\t' || c == '\\') {
            e[k++] = '\\';
            e[k++] = c == '\r' ? 'r' : (c == '\n' ? 'n' : (c == '\t' ? 't' : '\\'));
        } else if (c < 0x20 || c >= 0x7f) { /* control bytes, DEL, and every byte of a non-ASCII sequence */
            e[k++] = '\\';
            e[k++] = 'x';
            e[k++] = hex[c >> 4];
            e[k++] = hex[c & 15];
        } else {
            e[k++] = (char)c;
        }
        if (o + k + 4 > size) { /* keep room for "..." and the NUL (o + 4 <= size holds here) */
            if (size >= 4)
                memcpy(buf + o, "...", 4);
            else
                buf[0] = '\0';
            return buf;
        }
        memcpy(buf + o, e, k);
        o += k;
    }
    buf[o] = '\0';
    return buf;
}

sd_status sd_error_null(sd_error *err, const char *call, const char *arg)
{
    return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "%s: %s is NULL", call, arg);
}

void sd_error_clear(sd_error *err)
{
    if (err)
        memset(err, 0, sizeof *err);
}

void sd_error_format(const sd_error *err, char *buf, size_t size)
{
    if (!buf || size == 0)
        return;
    buf[0] = '\0';
    if (!err)
        return;
    size_t used = 0;
    int n;
    if (err->file[0]) {
        n = err->line > 0 ? snprintf(buf, size, "%s:%d: ", err->file, err->line)
                          : snprintf(buf, size, "%s: ", err->file);
        used = n > 0 ? (size_t)n : 0;
    }
    if (used < size && err->key[0]) {
        n = snprintf(buf + used, size - used, "%s: ", err->key);
        used += n > 0 ? (size_t)n : 0;
    }
    if (used < size)
        snprintf(buf + used, size - used, "%s", err->msg[0] ? err->msg : sd_status_name(err->code));
}

const char *sd_status_name(sd_status s)
{
    switch (s) {
    case SD_OK: return "ok";
    case SD_ERR_INPUT: return "bad input";
    case SD_ERR_IO: return "input/output error";
    case SD_ERR_MEMORY: return "out of memory";
    case SD_ERR_PHYSICS: return "invalid physical state";
    case SD_ERR_INTERNAL: return "internal error";
    case SD_ERR_INTERRUPTED: return "interrupted";
    }
    return "unknown status";
}
