/* botsim_pch.h: forced into every file of a board build (-include), first. It holds what
 * every file parses the same way: botsim_print.h (Verilator's runtime prints through the
 * harness), Verilator's headers and the standard library's. Compiled once into a
 * precompiled header kept beside Verilator's run-time objects (src/board/build.rs,
 * `Runtime`), it saves each build parsing them in every file; a compiler that finds the
 * precompiled header unusable parses this file instead, with the same result. */
#ifndef BOTSIM_PCH_H
#define BOTSIM_PCH_H
#include "botsim_print.h"
#ifdef __cplusplus
#include "verilated.h"
#include "verilated_dpi.h"
#include "verilated_syms.h"
#include "verilated_vcd_c.h"
#include "svdpi.h"
#ifdef BOTSIM_TIMING
#include "verilated_timing.h"
#endif
#include <algorithm>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <string>
#include <vector>
#endif
#endif
