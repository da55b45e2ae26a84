/* stb_image_impl.c: stb_image's decoder compiled into the fuzz harnesses by clang with the fuzzer's
 * coverage and the sanitizers (make fuzz; not part of any chapter), so that libFuzzer sees its branches
 * and AddressSanitizer its reads. The chapters link the same header's code from Debian's libstb; the
 * harnesses' own copy comes first at link time, so every call goes to it. */
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
