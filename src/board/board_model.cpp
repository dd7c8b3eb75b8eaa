// board_model.cpp: compiled with each design, what harness.cpp knows of its model
// (board_model.h): the wrapper's ports, the root object, the evaluation functions and the
// analyses' results (botsim_observed.h). Small on purpose: the harness itself is compiled
// once for every design.
#include "Vboard.h"
#include "Vboard___024root.h"
#include "board_model.h"

#include "botsim_observed.h"

// The model's evaluation proper, which Vboard::eval() wraps (Verilator 5's generated name).
// eval() also marks activity for the waveform and does a single-threaded model's thread
// bookkeeping through thread-local variables, which in a shared library cost more than the
// evaluation of a small design; runs without a waveform call this directly (measured in
// docs/PERFORMANCE.md).
void Vboard___024root___eval(Vboard___024root* vlSelf);
// Its trigger computation alone: at a falling edge of a board whose only trigger is the
// clock's rising edge, it notes the clock's level and nothing else happens (the build checks
// the design for this: src/fastforward/checks.rs). Its name is the Verilator version's
// (BOTSIM_EVAL_TRIGGERS, from botsim_observed.h); without one, every edge is evaluated.
#ifdef BOTSIM_EVAL_TRIGGERS
void BOTSIM_EVAL_TRIGGERS(Vboard___024root* vlSelf);
#endif

namespace {
Vboard* top_of(void* top) { return static_cast<Vboard*>(top); }
Vboard___024root* root_of(uint8_t* root) { return reinterpret_cast<Vboard___024root*>(root); }
const Vboard___024root* root_of(const uint8_t* root) { return reinterpret_cast<const Vboard___024root*>(root); }
}  // namespace

DesignModel botsim_model_new(VerilatedContext* ctx) {
    Vboard* t = new Vboard(ctx, "TOP");
    DesignModel m{};
    m.top = t;
    m.root = reinterpret_cast<uint8_t*>(t->rootp);
    m.root_size = sizeof(Vboard___024root);
    m.io.clk = &t->clk;
    m.io.reset_pressed = &t->reset_pressed;
    m.io.btn = &t->btn;
    m.io.sw = &t->sw;
    m.io.uart_push = &t->uart_push;
    m.io.ps2_push = &t->ps2_push;
    m.io.push_n = &t->push_n;
    m.io.push_bytes = &t->push_bytes;
    m.io.uart_div = &t->uart_div;
    m.io.tilt_x = &t->tilt_x;
    m.io.tilt_y = &t->tilt_y;
    m.io.tilt_z = &t->tilt_z;
    m.io.an = &t->an;
    m.io.seg = &t->seg;
    m.io.dp = &t->dp;
    m.io.led = &t->led;
    m.io.vga_r = &t->vga_r;
    m.io.vga_g = &t->vga_g;
    m.io.vga_b = &t->vga_b;
    m.io.hsync = &t->hsync;
    m.io.vsync = &t->vsync;
    m.io.lines = &t->lines;
    m.io.uart_room = &t->uart_room;
    m.io.uart_pending = &t->uart_pending;
    m.io.ps2_room = &t->ps2_room;
    m.io.ps2_pending = &t->ps2_pending;
    m.io.bot_upd = &t->bot_upd;
    m.io.bot_locx = &t->bot_locx;
    m.io.bot_locy = &t->bot_locy;
    m.io.bot_info = &t->bot_info;
    m.io.bot_sensors = &t->bot_sensors;
    m.io.bot_lmdist = &t->bot_lmdist;
    m.io.bot_rmdist = &t->bot_rmdist;
    m.io.bot_motctl = &t->bot_motctl;
    m.io.bot_cycles = &t->bot_cycles;
    m.io.xbot_upd = &t->xbot_upd;
    m.io.xbot_regs[0] = &t->xbot_regs1;
    m.io.xbot_regs[1] = &t->xbot_regs2;
    m.io.xbot_regs[2] = &t->xbot_regs3;
    m.observed_known = kObservedKnown;
    m.out_port_free = botsim_out_port_free;
    m.apart = botsim_apart;
    m.reads_at = botsim_reads_at;
    m.reads = botsim_reads;
    m.external = botsim_external;
    m.members = [](const uint8_t* r, std::vector<BoardMember>& out) { botsim_members(root_of(r), out); };
    m.counters = [](const uint8_t* r, std::vector<BoardCounter>& out) { botsim_counters(root_of(r), out); };
    m.eval = [](void* top) { top_of(top)->eval(); };
    m.eval_step = [](uint8_t* r) { Vboard___024root___eval(root_of(r)); };
#ifdef BOTSIM_EVAL_TRIGGERS
    m.eval_triggers = [](uint8_t* r) { BOTSIM_EVAL_TRIGGERS(root_of(r)); };
#else
    m.eval_triggers = nullptr;
#endif
#ifdef BOTSIM_TIMING
    m.events_pending = [](void* top) { return top_of(top)->eventsPending(); };
    m.next_time_slot = [](void* top) { return (uint64_t)top_of(top)->nextTimeSlot(); };
#else
    m.events_pending = [](void*) { return false; };
    m.next_time_slot = [](void*) { return ~(uint64_t)0; };
#endif
    m.trace = [](void* top, VerilatedVcdC* vcd, int levels) { top_of(top)->trace(vcd, levels); };
    m.final = [](void* top) { top_of(top)->final(); };
    m.destroy = [](void* top) { delete top_of(top); };
    return m;
}
