/* shim.h: the C interface of the Verilated models, for bindgen. Plain C, no Verilator types.
 * Every function that evaluates the model or touches the Verilator runtime sets the model's
 * context on the calling thread first (the input setters only store a value); a model must be
 * used only from the thread that created it. */
#ifndef BOTSIM_SHIM_H
#define BOTSIM_SHIM_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the KCPSM6 test harness (rtl/sim/kcpsm6_harness.v) ---------------------------------- */

typedef struct CpuSim CpuSim;

/* Inputs driven during one cycle and sampled at its closing rising edge. */
typedef struct {
    uint8_t reset;
    uint8_t sleep;
    uint8_t interrupt;
} CpuPins;

/* The core's ports during one cycle (before its closing edge). */
typedef struct {
    uint16_t address;
    uint32_t instruction;
    uint8_t bram_enable;
    uint8_t port_id;
    uint8_t out_port;
    uint8_t in_port;
    uint8_t read_strobe;
    uint8_t write_strobe;
    uint8_t k_write_strobe;
    uint8_t interrupt_ack;
} CpuPorts;

/* The core's state: architectural, and the sequencer flops the lock-step also compares. */
typedef struct {
    uint16_t pc;
    uint8_t t_state;
    uint8_t carry;
    uint8_t zero;
    uint8_t interrupt_enable;
    uint8_t bank;
    uint8_t xb;
    uint8_t depth;
    uint8_t run;
    uint8_t internal_reset;
    uint8_t active_interrupt;
    uint8_t registers[32];
    uint8_t scratch_pad[256];
    uint16_t scratch_pad_size;
} CpuState;

/* A harness with a 64, 128 or 256-byte scratch pad (other sizes: NULL). The three variants
 * are built with different hwbuild and interrupt_vector parameters, see build.rs. */
CpuSim* cpu_sim_new(uint32_t scratch_pad_size);
void cpu_sim_free(CpuSim* sim);
/* Open a VCD of the whole harness; returns 0 on success. */
int cpu_sim_open_vcd(CpuSim* sim, const char* path);
void cpu_sim_close_vcd(CpuSim* sim);
void cpu_sim_load_rom(CpuSim* sim, const uint32_t* words, size_t count);
void cpu_sim_set_inputs(CpuSim* sim, const uint8_t* values /* 256 */);
/* One clock cycle; `ports` (may be NULL) receives the ports during it. Returns 0, or -1 once
 * the model has finished ($finish), after which nothing is evaluated. */
int cpu_sim_tick(CpuSim* sim, CpuPins pins, CpuPorts* ports);
/* `cycles` cycles with constant pins, in one call. Returns the cycles run. */
uint64_t cpu_sim_run(CpuSim* sim, CpuPins pins, uint64_t cycles);
void cpu_sim_state(CpuSim* sim, CpuState* state);
uint64_t cpu_sim_cycle(const CpuSim* sim);
/* As bot_sim_take_fatal. */
size_t cpu_sim_take_fatal(CpuSim* sim, char* buf, size_t len);

/* ---- the BotSim 2.0 top, `bot` (rtl/bot.v) ------------------------------------------------ */

typedef struct BotSim BotSim;

/* The six visible registers. */
typedef struct {
    uint8_t loc_x;
    uint8_t loc_y;
    uint8_t sensors;
    uint8_t bot_info;
    uint8_t lm_dist;
    uint8_t rm_dist;
} BotRegs;

/* The outputs during one cycle. */
typedef struct {
    BotRegs regs;
    uint8_t upd_sysregs;
    uint8_t vid_pixel_out;
} BotOutputs;

/* A port access on the CPU bus: the cycle its strobe is high, port_id and the data (out_port
 * for writes, in_port for reads). kind: 0 read (read_strobe), 1 write, 2 OUTPUTK write. */
typedef struct {
    uint64_t cycle;
    uint8_t kind;
    uint8_t port;
    uint8_t value;
} BotPortEvent;

/* A new model; `debug`: the build with the KCPSM6's debug signals (for waveforms). */
BotSim* bot_sim_new(int debug);
void bot_sim_free(BotSim* sim);
int bot_sim_open_vcd(BotSim* sim, const char* path);
void bot_sim_close_vcd(BotSim* sim);
/* Replace the program ROM (1024 words) and the world (16384 cells of 2 bits, row-major). */
void bot_sim_load_program(BotSim* sim, const uint32_t* words, size_t count);
void bot_sim_load_world(BotSim* sim, const uint8_t* cells, size_t count);
/* Inputs, applied from the next cycle on. */
void bot_sim_set_motctl(BotSim* sim, uint8_t motctl);
void bot_sim_set_reset(BotSim* sim, uint8_t reset);
void bot_sim_set_video(BotSim* sim, uint16_t row, uint16_t col);
/* One cycle; `out` (may be NULL) receives the outputs during it. 0, or -1 once finished. */
int bot_sim_tick(BotSim* sim, BotOutputs* out);
/* Run until upd_sysregs rises: returns 1 with the cycle in which it is first high and the
 * registers then (the simulation stops at the start of that cycle); 0 if `budget` cycles
 * passed without a rise; -1 once finished. */
int bot_sim_run_until_update(BotSim* sim, uint64_t budget, uint64_t* cycle, BotRegs* regs);
/* `cycles` cycles in one call; returns the cycles run. */
uint64_t bot_sim_run(BotSim* sim, uint64_t cycles);
/* As bot_sim_run_until_update (with `stop_on_update`) or bot_sim_run (without, returning 0
 * after `budget` cycles), recording every port access into `events` (capacity `cap`; `*count`
 * is set). Returns 1, 0 or -1 as bot_sim_run_until_update, or -2 when `events` is full. */
int bot_sim_run_recording(BotSim* sim, uint64_t budget, int stop_on_update, uint64_t* cycle, BotRegs* regs,
                          BotPortEvent* events, size_t cap, size_t* count);
uint64_t bot_sim_cycle(const BotSim* sim);
/* `cycles` cycles of Verilator's minimal loop (clock low, eval, clock high, eval; nothing
 * checked, dumped or recorded): the reference `botsim bench` measures bot_sim_run against. */
void bot_sim_bench_minimal(BotSim* sim, uint64_t cycles);
/* The message of the fatal runtime error that stopped this model (a failed VCD write, say):
 * at most len - 1 bytes of it, NUL-terminated, into `buf` (nothing when len is 0); returns its
 * whole length, 0 if none. Clears it. */
size_t bot_sim_take_fatal(BotSim* sim, char* buf, size_t len);
/* Where the CPU is: its program counter; 1 if it is held in (internal) reset. */
int bot_sim_cpu_in_reset(const BotSim* sim, uint16_t* pc);

#ifdef __cplusplus
}
#endif

#endif
