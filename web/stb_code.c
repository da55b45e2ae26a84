/* stb_code.c: the code of the stb functions the chapters call (reading and writing PNG and JPEG), for
 * the WebAssembly build (make web). Natively it comes from Debian's libstb; here it is compiled from
 * the same headers, since there is no WebAssembly libstb to link. */
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image.h>
#include <stb_image_write.h>
