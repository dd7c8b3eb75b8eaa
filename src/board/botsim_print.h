/* botsim_print.h: forced into every file of a board build (-include), so that Verilator's
 * runtime prints the design's $display, $write and warnings through the harness
 * (VL_PRINTF/VL_VPRINTF are these; src/board/harness.cpp routes and caps them). */
#include <stdarg.h>
#ifdef __cplusplus
extern "C" {
#endif
int botsim_printf(const char* format, ...);
int botsim_vprintf(const char* format, va_list ap);
#ifdef __cplusplus
}
#endif
