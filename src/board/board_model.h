// board_model.h: what the harness knows of a design's Verilated model. harness.cpp is compiled
// once (for every design of a Verilator and its flags) and sees the model only through this;
// board_model.cpp, compiled with each design, fills it in. The ports are the wrapper's
// (botsim_board, core/src/frontend/wrapper.rs), the same for every design.
#ifndef BOTSIM_BOARD_MODEL_H
#define BOTSIM_BOARD_MODEL_H

#include "verilated.h"
#include "verilated_vcd_c.h"

#include <cstddef>
#include <cstdint>
#include <vector>

// One variable of the root object: its bytes, and whether a run without a waveform or VGA
// frames observes it (src/fastforward/observed.rs decides; botsim_observed.h lists them).
struct BoardMember {
    size_t off, len;
    bool observed;
    const char* name;
};
// A variable a counter is compared with: its bytes, and the constant added to the counter
// first (`count + 1 >= half`).
struct BoardBound {
    size_t off, len;
    uint64_t offset;
};
// A comparison (demand.rs's Cmp): the counter on its left.
enum class BoardCmp : uint8_t { Lt, Le, Gt, Ge, Eq, Ne };
// A comparison of a counter: with the constant `value`, or with its bound number `value`.
struct BoardGuard {
    BoardCmp op;
    bool bound;
    uint64_t value;
};
// A read of a counter's bits from `lo` up that happens only where all its guards hold.
struct BoardGuarded {
    uint32_t lo;
    std::vector<BoardGuard> guards;
};
// A counter the fast-forward moves on by arithmetic (src/fastforward/counters.rs): its bytes, its
// width in bits, whether it counts down, its largest step, the lowest bit a shifted read sees
// (64: none), the constants it is compared with, the bit below which only masks read it
// (64: none; the low part then repeats while the rest counts), the lowest bit a read
// above that split sees (64: none), the variables it is compared with, its guarded reads and
// the constants it may be set to.
struct BoardCounter {
    size_t off, len;
    uint32_t bits;
    bool down;
    uint64_t step;
    uint32_t shift;
    std::vector<uint64_t> consts;
    uint32_t split, split_shift;
    std::vector<BoardBound> bounds;
    std::vector<BoardGuarded> guarded;
    std::vector<uint64_t> sets;
};

// The wrapper's ports: where the model keeps each (in its root object).
struct BoardPorts {
    // What the harness drives.
    CData *clk, *reset_pressed, *btn;
    SData* sw;
    CData *uart_push, *ps2_push, *push_n;
    QData* push_bytes;
    IData* uart_div;
    SData *tilt_x, *tilt_y, *tilt_z;
    // What the board shows.
    CData *an, *seg, *dp;
    SData* led;
    CData *vga_r, *vga_g, *vga_b, *hsync, *vsync;
    SData* lines;
    CData *uart_room, *uart_pending, *ps2_room, *ps2_pending;
    // The bot's registers at its ports, and its clock count (botsim's, not the design's).
    CData *bot_upd, *bot_locx, *bot_locy, *bot_info, *bot_sensors, *bot_lmdist, *bot_rmdist, *bot_motctl;
    QData* bot_cycles;
    // The design's other bots: their upd_sysregs (bit k - 1 for bot k) and registers, packed
    // as a SAMPLE's (board_abi.h).
    CData* xbot_upd;
    QData* xbot_regs[3];
};

// A design's model.
struct DesignModel {
    void* top;        // the Vboard
    uint8_t* root;    // its root object: all of its state (src/fastforward/checks.rs)
    size_t root_size;
    BoardPorts io;
    // The analyses' results (botsim_observed.h): whether the observed variables are known,
    // the root's variables and its counters.
    bool observed_known;
    void (*members)(const uint8_t* root, std::vector<BoardMember>& out);
    // Member i's reads: reads[reads_at[i] .. reads_at[i + 1]) (indices among the members, the
    // observed ones' only), and whether it touches what leaves the model (external[i]).
    const uint32_t* reads_at;
    const uint32_t* reads;
    const uint8_t* external;
    // The KCPSM6 models (by the Verilator name of their instance) whose out_port the design
    // reads only under a write strobe (src/fastforward/strobes.rs); null-terminated.
    const char* const* out_port_free;
    // The KCPSM6 models that may run apart from the board (src/fastforward/apart.rs): each entry
    // the instance's Verilator name and its followers, separated by spaces; null-terminated.
    const char* const* apart;
    void (*counters)(const uint8_t* root, std::vector<BoardCounter>& out);
    // Vboard::eval(); the evaluation proper, which eval() wraps; the trigger computation
    // alone, or null when the Verilator has none (BOTSIM_EVAL_TRIGGERS).
    void (*eval)(void* top);
    void (*eval_step)(uint8_t* root);
    void (*eval_triggers)(uint8_t* root);
    // A design with delays (a build with Verilator's --timing): its next timed event.
    bool (*events_pending)(void* top);
    uint64_t (*next_time_slot)(void* top);
    void (*trace)(void* top, VerilatedVcdC* vcd, int levels);
    void (*final)(void* top);
    void (*destroy)(void* top);
};

// The design's model in a context (board_model.cpp).
DesignModel botsim_model_new(VerilatedContext* ctx);

#endif
