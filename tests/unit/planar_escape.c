/* planar_escape.c — sd_escape (core/error.h): a message that quotes file
 * content shows control bytes, ANSI escapes and non-ASCII bytes as
 * escapes, never raw (robustness probe F13), and is cut with "..." when the
 * buffer is short, without writing past it. */
#include <string.h>

#include "core/error.h"
#include "test.h"

static void expect(const char *label, const char *in, size_t len, size_t size, const char *want)
{
    char buf[64];
    memset(buf, 'Z', sizeof buf);
    sd_escape(buf, size, in, len);
    int ok = strcmp(buf, want) == 0;
    for (size_t i = size; i < sizeof buf; ++i)
        ok = ok && buf[i] == 'Z'; /* nothing written past size */
    printf("%-4s %-28s computed '%s' expected '%s'\n", ok ? "ok" : "FAIL", label, buf, want);
    CHECK(ok);
}

int main(void)
{
    expect("plain text", "1.0,2.0", (size_t)-1, 64, "1.0,2.0");
    expect("ANSI escape and CR", "f 1 2 \x1b[31mRED\r", (size_t)-1, 64, "f 1 2 \\x1b[31mRED\\r");
    expect("tab, newline, backslash", "a\tb\nc\\", (size_t)-1, 64, "a\\tb\\nc\\\\");
    expect("non-UTF-8 and UTF-8 bytes", "\xb5m \xc3\xa9", (size_t)-1, 64, "\\xb5m \\xc3\\xa9");
    expect("DEL and NUL-bounded length", "ab\x7f" "cd", 3, 64, "ab\\x7f");
    expect("cut to the buffer", "0123456789abcdef", (size_t)-1, 12, "01234567...");
    expect("cut inside an escape", "0123\x01\x02", (size_t)-1, 10, "0123...");
    char small[8];
    CHECK(strcmp(sd_escape(small, sizeof small, NULL, 5), "") == 0);
    return sd_test_summary();
}
