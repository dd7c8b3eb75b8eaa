/* board_abi.h: the C interface of a board simulation library (harness.cpp). */
#include <stddef.h>
#include <stdint.h>

typedef struct Board Board;

enum {
    BOARD_EVENT_DISPLAY = 1,
    BOARD_EVENT_LEDS = 2,
    BOARD_EVENT_SAMPLE = 3,
    BOARD_EVENT_VGA = 4,
    BOARD_EVENT_BOT = 5,
    BOARD_EVENT_REPEAT = 6,
    BOARD_EVENT_LINES = 7,
    BOARD_EVENT_OTHER_SAMPLE = 8
};
/* The devices botsim_push feeds. */
enum { BOARD_UART = 0, BOARD_KEYBOARD = 1 };
enum { BOARD_UNTIL = 0, BOARD_BUFFER_FULL = 1, BOARD_SAMPLES = 2, BOARD_FINISHED = 3 };

/* One thing the board showed. DISPLAY: a = an | seg << 8 | dp << 15. LEDS: a = led.
 * SAMPLE: a = sample index, b = LocX | LocY << 8 | BotInfo << 16 | Sensors << 24 |
 * LMDist << 32 | RMDist << 40 | MotCtl << 48, c = the bot's clock cycles since power-up.
 * OTHER_SAMPLE: another bot's upd_sysregs; a = its sample index | the bot (1..3) << 28, b as
 * SAMPLE's, c = the first bot's clock cycles.
 * VGA (when board_record_vga is on): a = r << 8 | g << 4 | b | hsync << 12 | vsync << 13.
 * BOT (when board_record_bot is on): any of the bot's outputs changed; a = upd_sysregs,
 * b = LocX | LocY << 8 | BotInfo << 16 | Sensors << 24 | LMDist << 32 | RMDist << 40.
 * LINES: the peripherals' lines, a = RsTx | ampPWM << 1 | ampSD << 2 | RsRx << 3 |
 * PS2_CLK << 4 | PS2_DATA << 5 | aclSCK << 6 | aclMOSI << 7 | aclMISO << 8 | aclSS << 9
 * (as on the board; idle where the design has no such pin, ampSD 1 with ampPWM alone).
 * REPEAT (a fast-forward over a period in which the board showed something): the a records
 * before this one happen c more times, each b ps after the last (time_ps: the first
 * repetition's start). */
typedef struct BoardEvent {
    uint64_t time_ps;
    uint32_t kind;
    uint32_t a;
    uint64_t b;
    uint64_t c;
} BoardEvent;

/* botsim board --cpu iss: the host's model of one KCPSM6 instance begins with a pointer to
 * its functions (kcpsm6_iss.v packs the pins and unpacks the state). */
typedef struct BoardCpuFns {
    uint64_t (*tick)(void* cpu, uint64_t pins);
    uint64_t (*state)(void* cpu);
    /* Debug builds: the active bank's s0..sF (s0 in the low byte of regs[0]) and the flags
     * bank | zero << 1 | carry << 2 | ie << 3 | reset << 4 | sleep << 5 | entry << 6. */
    void (*debug)(void* cpu, uint32_t* regs, uint32_t* flags);
    /* The design reads this instance's out_port only under a write strobe (the analysis of
     * src/fastforward/strobes.rs): a count shown there between OUTPUTs cannot change the board. */
    void (*out_port_free)(void* cpu);
    /* The design lets this instance run apart from the board (src/fastforward/apart.rs), as its
     * entry in botsim_observed.h's `botsim_apart` says; or no longer (null: a run that
     * compares all of the board). */
    void (*apart_capable)(void* cpu, const char* entry);
    /* Since the last mark the instance runs apart: the fast-forward compares neither it nor
     * its followers, and the host runs it on its own over a skip (up to just before its next
     * port access). Until the next mark, or until its reset, sleep or interrupt rises (which
     * counts as activity). */
    int (*apart)(void* cpu);
} BoardCpuFns;

/* A probe on one RTL KCPSM6's ports (the lock-step build), which begins with a pointer to
 * its function: the pins and state of one cycle, packed as kcpsm6_iss.v packs them, and
 * the time of the rising edge that ends it. */
typedef struct BoardProbeFns {
    void (*record)(void* probe, uint64_t pins, uint64_t state, uint64_t time_ps);
} BoardProbeFns;

/* botsim board --bot model: the host's model of the bot (rtl/board/bot_model.v) begins with a
 * pointer to its function: one rising edge, pins = MotCtl_in | reset << 8, returning
 * LocX | LocY << 8 | BotInfo << 16 | Sensors << 24 | LMDist << 32 | RMDist << 40 |
 * upd_sysregs << 48. */
typedef struct BoardBotFns {
    uint64_t (*edge)(void* bot, uint32_t pins);
} BoardBotFns;

/* What a design built for --cpu iss or lockstep asks of its host: a model (or a probe) for
 * the instance whose hierarchical name is `path`, or null (the run then stops with a fatal
 * error). */
typedef struct BoardHost {
    void* ctx;
    /* `now`: the board's time in ps, the time of the edge being evaluated (for traces). */
    void* (*cpu_new)(void* ctx, const char* path, uint32_t hwbuild, uint32_t vector, uint32_t scratch_pad,
                     const uint64_t* now);
    void* (*probe_new)(void* ctx, const char* path);
    /* --bot model: the model of the bot instance `path`, or null. */
    void* (*bot_new)(void* ctx, const char* path);
    /* Debug builds: the disassembly of `word`, 20 characters padded with spaces. */
    void (*disasm)(uint32_t word, char* text);
    /* The fast-forward (harness.cpp): counted up by the models at every interrupt, write of
     * the bot's firmware and change of the bot's inputs; mark every model's state; take a
     * phase snapshot of every model's state (the snapshots since the mark are numbered from
     * 1); are the KCPSM6 models as marked (their cycle counts aside: 1), or as marked but for
     * a count their firmware keeps (2, src/fastforward/counts.rs; 0: neither); how many periods (each
     * as long as the time since the mark) the bot's outputs stay as they are with its inputs
     * held, at most `periods`; do they stay so for `periods` periods and then up to phase
     * snapshot `phase`; run every model `periods` periods on and then to phase snapshot
     * `phase` (0: none) of the next (the CPUs' state repeats; the bot runs on), returning the
     * bot's clock edges in them (called at the end of the mark's first period; the mark and
     * the snapshots move on to the start of the period the models are then in). */
    uint64_t activity;
    void (*ff_mark)(void* ctx);
    void (*ff_snap)(void* ctx);
    int (*ff_same)(void* ctx);
    uint64_t (*ff_room)(void* ctx, uint64_t periods);
    int (*ff_fits)(void* ctx, uint64_t periods, uint32_t phase);
    uint64_t (*ff_skip)(void* ctx, uint64_t periods, uint32_t phase);
} BoardHost;
