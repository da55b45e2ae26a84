/* text_escape.h: text from the input made safe to print in a message (chapter 1).
 *
 * Error messages quote what the input said: a word of a scene file, a file name, an option. Those bytes
 * come from anyone; printed raw, a control character such as ESC (0x1b) is obeyed by the terminal (it
 * can recolour, move the cursor or retitle the window) and a stray byte garbles the line. So every byte
 * that is not printable text is written as \xNN instead: the control characters 0x00-0x1f and 0x7f,
 * the C1 controls U+0080-U+009F, the characters that show as nothing or as a plain space or reorder the
 * text (a no-break space, zero-width ones, the direction overrides, the byte-order mark: each of their
 * bytes), and any byte that is not part of valid UTF-8. Printable ASCII and valid UTF-8 (a name with an
 * accent, a multiplication sign) pass unchanged. */
#ifndef WHITTED_TEXT_ESCAPE_H
#define WHITTED_TEXT_ESCAPE_H

#include <stddef.h>

/* Copies `text` into out (out_size bytes, at least 1), escaping as described above, and always ends it
 * with a NUL. When it does not fit, the copy stops before the first character (or escape) that would
 * not fit whole. Returns the length of the copy. */
size_t text_escape(const char *text, char *out, size_t out_size);

#endif
