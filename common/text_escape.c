/* text_escape.c: non-printable bytes of quoted input written as \xNN (chapter 1). */
#include "text_escape.h"

#include <stdbool.h>
#include <stdint.h>

/* Whether `code` is a character that shows as nothing or as a plain space, or reorders what follows it:
 * a no-break space, a soft hyphen, the zero-width characters and joiners, the marks and overrides of
 * writing direction (U+202E shows "y'" after it as "'y"), the invisible operators, and the byte-order
 * mark. Quoted raw, "radius 1<U+00A0>" reads as "radius 1 " and "<U+FEFF>sphere" as "sphere": escaped,
 * the message shows what is really there. */
static bool is_invisible_format(uint32_t code) {
    return code == 0xa0 || code == 0xad || code == 0x61c || code == 0x180e || (code >= 0x200b && code <= 0x200f) ||
           (code >= 0x2028 && code <= 0x202f) || (code >= 0x2060 && code <= 0x206f) || code == 0xfeff ||
           (code >= 0xfff9 && code <= 0xfffb);
}

/* Returns how many bytes the printable character at `s` takes (1 to 4), or 0 when the byte at `s` must
 * be escaped: a control character, or not the start of a valid, shortest-form UTF-8 character. */
static size_t printable_length(const unsigned char *s) {
    if (s[0] < 0x80)
        return (s[0] >= 0x20 && s[0] != 0x7f) ? 1 : 0;
    size_t length = s[0] >= 0xc2 && s[0] <= 0xdf ? 2 : s[0] >= 0xe0 && s[0] <= 0xef ? 3
                  : s[0] >= 0xf0 && s[0] <= 0xf4 ? 4 : 0;
    if (length == 0)
        return 0; /* a continuation byte, an overlong start (0xc0, 0xc1) or beyond U+10FFFF */
    uint32_t code = s[0] & (0x7f >> length);
    for (size_t k = 1; k < length; k++) {
        if ((s[k] & 0xc0) != 0x80) /* also stops at the terminating NUL */
            return 0;
        code = code << 6 | (s[k] & 0x3f);
    }
    static const uint32_t smallest[5] = {0, 0, 0x80, 0x800, 0x10000}; /* below: an overlong form */
    if (code < smallest[length] || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff))
        return 0;
    if (code <= 0x9f || is_invisible_format(code)) /* the C1 controls U+0080..U+009F, and see below */
        return 0;
    return length;
}

size_t text_escape(const char *text, char *out, size_t out_size) {
    static const char hex[] = "0123456789abcdef";
    const unsigned char *s = (const unsigned char *)text;
    size_t used = 0;
    while (*s != '\0') {
        size_t length = printable_length(s);
        size_t needed = length == 0 ? 4 : length; /* "\xNN" */
        if (used + needed >= out_size)
            break;
        if (length == 0) {
            out[used++] = '\\';
            out[used++] = 'x';
            out[used++] = hex[*s >> 4];
            out[used++] = hex[*s & 0xf];
            s++;
        } else {
            for (size_t k = 0; k < length; k++)
                out[used++] = (char)*s++;
        }
    }
    out[used] = '\0';
    return used;
}
