// bot_shim.cpp: the BotSim `bot` model behind shim.h. The clock loop runs here, in C++, so
// a whole sample costs one call from Rust.
#include "shim.h"
#include "sim.h"

#include "Vbot.h"
#include "Vbot___024root.h"

// Port accesses of the CPU, appended to a caller's buffer.
struct Recorder {
    BotPortEvent* events;
    size_t cap;
    size_t* count;

    // Record this cycle's access, if any; false when the buffer is full.
    bool take(const Sim<Vbot>& sim) {
        const auto* r = sim.top->rootp;
        // The strobes are registered in the CPU: at most one is high in a cycle.
        const int kind = r->bot__DOT__read_strobe    ? 0
                         : r->bot__DOT__write_strobe ? 1
                         : r->bot__DOT__k_write_strobe ? 2
                                                       : -1;
        if (kind < 0) return true;
        if (*count == cap) return false;
        BotPortEvent& e = events[(*count)++];
        e.cycle = sim.cycle;
        e.kind = (uint8_t)kind;
        e.port = r->bot__DOT__port_id;
        e.value = kind == 0 ? r->bot__DOT__in_port : r->bot__DOT__out_port;
        return true;
    }
};

struct BotSim {
    Sim<Vbot> sim;
    bool prev_upd = false;  // upd_sysregs in the previous cycle

    void settle() { sim.settle(); }

    void rise() {
        prev_upd = sim.top->upd_sysregs;
        sim.rise();
    }

    // The clock loop behind every run call: up to `budget` cycles, stopping at the start of
    // a cycle in which upd_sysregs rises when `stop_on_update` (1, with its cycle and the
    // registers); 0 when the budget is spent (`*cycle` is then the next cycle), -1 once
    // finished. With Record, every port access is appended to `rec` (-2 when it is full; the
    // next call resumes with the same cycle). One template, so the plain loop has no recording
    // test in it.
    template <bool Record>
    int clock(uint64_t budget, bool stop_on_update, uint64_t* cycle, BotRegs* regs, Recorder* rec) {
        sim.enter();
        for (uint64_t n = 0; n < budget; n++) {
            if (sim.finished()) return -1;
            settle();
            if (stop_on_update && sim.top->upd_sysregs && !prev_upd) {
                *cycle = sim.cycle;
                this->regs(regs);
                prev_upd = true;  // seen: the next call continues with this cycle's edge
                return 1;
            }
            if (Record && !rec->take(sim)) return -2;
            rise();
        }
        *cycle = sim.cycle;
        return 0;
    }

    void regs(BotRegs* r) const {
        const Vbot* t = sim.top;
        r->loc_x = t->LocX_reg;
        r->loc_y = t->LocY_reg;
        r->sensors = t->Sensors_reg;
        r->bot_info = t->BotInfo_reg;
        r->lm_dist = t->LMDist_reg;
        r->rm_dist = t->RMDist_reg;
    }
};

extern "C" {

BotSim* bot_sim_new(void) {
    BotSim* b = new BotSim;
    b->sim.top->reset = 0;
    b->sim.top->MotCtl_in = 0;
    b->sim.top->vid_row = 0;
    b->sim.top->vid_col = 0;
    return b;
}

void bot_sim_free(BotSim* b) { delete b; }

int bot_sim_open_vcd(BotSim* b, const char* path) {
    return b->sim.open_vcd(path, 99) ? 0 : -1;
}

void bot_sim_close_vcd(BotSim* b) {
    b->sim.enter();
    b->sim.close_vcd();
}

void bot_sim_load_program(BotSim* b, const uint32_t* words, size_t count) {
    b->sim.enter();
    auto& rom = b->sim.top->rootp->bot__DOT__BOTSIMPGM__DOT__rom;
    for (size_t i = 0; i < 1024; i++) rom[i] = i < count ? (words[i] & 0x3FFFF) : 0;
}

void bot_sim_load_world(BotSim* b, const uint8_t* cells, size_t count) {
    b->sim.enter();
    auto& map = b->sim.top->rootp->bot__DOT__MAP__DOT__world__DOT__cells;
    for (size_t i = 0; i < 16384; i++) map[i] = i < count ? (cells[i] & 3) : 0;
}

void bot_sim_set_motctl(BotSim* b, uint8_t v) {
    b->sim.top->MotCtl_in = v;
}

void bot_sim_set_reset(BotSim* b, uint8_t v) {
    b->sim.top->reset = v;
}

void bot_sim_set_video(BotSim* b, uint16_t row, uint16_t col) {
    b->sim.top->vid_row = row & 0x3FF;
    b->sim.top->vid_col = col & 0x3FF;
}

int bot_sim_tick(BotSim* b, BotOutputs* out) {
    b->sim.enter();
    if (b->sim.finished()) return -1;
    b->settle();
    if (out) {
        b->regs(&out->regs);
        out->upd_sysregs = b->sim.top->upd_sysregs;
        out->vid_pixel_out = b->sim.top->vid_pixel_out;
    }
    b->rise();
    return 0;
}

int bot_sim_run_until_update(BotSim* b, uint64_t budget, uint64_t* cycle, BotRegs* regs) {
    return b->clock<false>(budget, true, cycle, regs, nullptr);
}

int bot_sim_run_recording(BotSim* b, uint64_t budget, int stop_on_update, uint64_t* cycle, BotRegs* regs,
                          BotPortEvent* events, size_t cap, size_t* count) {
    Recorder rec{events, cap, count};
    *count = 0;
    return b->clock<true>(budget, stop_on_update != 0, cycle, regs, &rec);
}

uint64_t bot_sim_run(BotSim* b, uint64_t cycles) {
    const uint64_t start = b->sim.cycle;
    uint64_t cycle;
    b->clock<false>(cycles, false, &cycle, nullptr, nullptr);
    return b->sim.cycle - start;
}

uint64_t bot_sim_cycle(const BotSim* b) { return b->sim.cycle; }

void bot_sim_bench_minimal(BotSim* b, uint64_t cycles) {
    b->sim.enter();
    Vbot* top = b->sim.top;
    VerilatedContext* ctx = b->sim.ctx;
    for (uint64_t i = 0; i < cycles; i++) {
        top->clk = 0;
        top->eval();
        ctx->timeInc(HALF_PERIOD_PS);
        top->clk = 1;
        top->eval();
        ctx->timeInc(HALF_PERIOD_PS);
    }
    b->sim.cycle += cycles;
}

size_t bot_sim_take_fatal(BotSim* b, char* buf, size_t len) { return b->sim.take_fatal(buf, len); }

int bot_sim_cpu_in_reset(const BotSim* b, uint16_t* pc) {
    const auto* r = b->sim.top->rootp;
    *pc = r->bot__DOT__BOTSIMCPU__DOT__pc;
    return r->bot__DOT__BOTSIMCPU__DOT__internal_reset;
}
}
