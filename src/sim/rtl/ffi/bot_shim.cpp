// bot_shim.cpp: the BotSim `bot` model behind shim.h. The clock loop runs here, in C++, so
// a whole sample costs one call from Rust. Two builds of rtl/bot.v: `Vbot`, and `Vbotdbg`
// with the KCPSM6's debug signals for waveforms (BOTSIM_DEBUG: the instruction's text, the
// status, the registers), whose `always @(instruction)` costs a fifth of the speed, so runs
// without a waveform use the first.
#include "shim.h"
#include "sim.h"

#include "Vbot.h"
#include "Vbot___024root.h"
#include "Vbotdbg.h"
#include "Vbotdbg___024root.h"
#include "botsim_disasm.h"

// The text of an instruction word, from Rust's disassembler (src/sim/rtl/mod.rs).
extern "C" void botsim_disasm_text(uint32_t word, char* text);

// rtl/kcpsm6.v's debug signal kcpsm6_opcode, in Vbotdbg.
extern "C" void botsim_disasm(int word, svBitVecVal* text) {
    botsim_disasm_pack(word, text, [](uint32_t w, char* s) {
        botsim_disasm_text(w, s);
        return true;
    });
}

// Port accesses of the CPU, appended to a caller's buffer.
struct Recorder {
    BotPortEvent* events;
    size_t cap;
    size_t* count;

    // Record this cycle's access, if any; false when the buffer is full.
    template <class V>
    bool take(const Sim<V>& sim) {
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

// The interface shim.h's functions reach either model through.
struct BotSim {
    virtual ~BotSim() {}
    virtual int open_vcd(const char* path) = 0;
    virtual void close_vcd() = 0;
    virtual void load_program(const uint32_t* words, size_t count) = 0;
    virtual void load_world(const uint8_t* cells, size_t count) = 0;
    virtual void set_inputs(const uint8_t* motctl, const uint8_t* reset, const uint16_t* row, const uint16_t* col) = 0;
    virtual int tick(BotOutputs* out) = 0;
    virtual int run(uint64_t budget, bool stop_on_update, uint64_t* cycle, BotRegs* regs, Recorder* rec) = 0;
    virtual uint64_t cycle() const = 0;
    virtual void bench_minimal(uint64_t cycles) = 0;
    virtual size_t take_fatal(char* buf, size_t len) = 0;
    virtual int cpu_in_reset(uint16_t* pc) const = 0;
};

template <class V>
struct BotModel final : BotSim {
    Sim<V> sim;
    bool prev_upd = false;  // upd_sysregs in the previous cycle

    BotModel() {
        sim.top->reset = 0;
        sim.top->MotCtl_in = 0;
        sim.top->vid_row = 0;
        sim.top->vid_col = 0;
    }

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
        const V* t = sim.top;
        r->loc_x = t->LocX_reg;
        r->loc_y = t->LocY_reg;
        r->sensors = t->Sensors_reg;
        r->bot_info = t->BotInfo_reg;
        r->lm_dist = t->LMDist_reg;
        r->rm_dist = t->RMDist_reg;
    }
    int open_vcd(const char* path) override { return sim.open_vcd(path, 99) ? 0 : -1; }

    void close_vcd() override {
        sim.enter();
        sim.close_vcd();
    }

    void load_program(const uint32_t* words, size_t count) override {
        sim.enter();
        auto& rom = sim.top->rootp->bot__DOT__BOTSIMPGM__DOT__rom;
        for (size_t i = 0; i < 1024; i++) rom[i] = i < count ? (words[i] & 0x3FFFF) : 0;
    }

    void load_world(const uint8_t* cells, size_t count) override {
        sim.enter();
        auto& map = sim.top->rootp->bot__DOT__MAP__DOT__world__DOT__cells;
        for (size_t i = 0; i < 16384; i++) map[i] = i < count ? (cells[i] & 3) : 0;
    }

    // Each input that is given (not null) from the next cycle on.
    void set_inputs(const uint8_t* motctl, const uint8_t* reset, const uint16_t* row, const uint16_t* col) override {
        if (motctl) sim.top->MotCtl_in = *motctl;
        if (reset) sim.top->reset = *reset;
        if (row) sim.top->vid_row = *row & 0x3FF;
        if (col) sim.top->vid_col = *col & 0x3FF;
    }

    int tick(BotOutputs* out) override {
        sim.enter();
        if (sim.finished()) return -1;
        settle();
        if (out) {
            regs(&out->regs);
            out->upd_sysregs = sim.top->upd_sysregs;
            out->vid_pixel_out = sim.top->vid_pixel_out;
        }
        rise();
        return 0;
    }

    int run(uint64_t budget, bool stop_on_update, uint64_t* cycle, BotRegs* regs, Recorder* rec) override {
        return rec ? clock<true>(budget, stop_on_update, cycle, regs, rec)
                   : clock<false>(budget, stop_on_update, cycle, regs, nullptr);
    }

    uint64_t cycle() const override { return sim.cycle; }

    void bench_minimal(uint64_t cycles) override {
        sim.enter();
        V* top = sim.top;
        VerilatedContext* ctx = sim.ctx;
        for (uint64_t i = 0; i < cycles; i++) {
            top->clk = 0;
            top->eval();
            ctx->timeInc(HALF_PERIOD_PS);
            top->clk = 1;
            top->eval();
            ctx->timeInc(HALF_PERIOD_PS);
        }
        sim.cycle += cycles;
    }

    size_t take_fatal(char* buf, size_t len) override { return sim.take_fatal(buf, len); }

    int cpu_in_reset(uint16_t* pc) const override {
        const auto* r = sim.top->rootp;
        *pc = r->bot__DOT__BOTSIMCPU__DOT__pc;
        return r->bot__DOT__BOTSIMCPU__DOT__internal_reset;
    }
};

extern "C" {

BotSim* bot_sim_new(int debug) {
    if (debug) return new BotModel<Vbotdbg>;
    return new BotModel<Vbot>;
}

void bot_sim_free(BotSim* b) { delete b; }
int bot_sim_open_vcd(BotSim* b, const char* path) { return b->open_vcd(path); }
void bot_sim_close_vcd(BotSim* b) { b->close_vcd(); }
void bot_sim_load_program(BotSim* b, const uint32_t* words, size_t count) { b->load_program(words, count); }
void bot_sim_load_world(BotSim* b, const uint8_t* cells, size_t count) { b->load_world(cells, count); }
void bot_sim_set_motctl(BotSim* b, uint8_t v) { b->set_inputs(&v, nullptr, nullptr, nullptr); }
void bot_sim_set_reset(BotSim* b, uint8_t v) { b->set_inputs(nullptr, &v, nullptr, nullptr); }
void bot_sim_set_video(BotSim* b, uint16_t row, uint16_t col) { b->set_inputs(nullptr, nullptr, &row, &col); }
int bot_sim_tick(BotSim* b, BotOutputs* out) { return b->tick(out); }

int bot_sim_run_until_update(BotSim* b, uint64_t budget, uint64_t* cycle, BotRegs* regs) {
    return b->run(budget, true, cycle, regs, nullptr);
}

int bot_sim_run_recording(BotSim* b, uint64_t budget, int stop_on_update, uint64_t* cycle, BotRegs* regs,
                          BotPortEvent* events, size_t cap, size_t* count) {
    Recorder rec{events, cap, count};
    *count = 0;
    return b->run(budget, stop_on_update != 0, cycle, regs, &rec);
}

uint64_t bot_sim_run(BotSim* b, uint64_t cycles) {
    const uint64_t start = b->cycle();
    uint64_t cycle;
    b->run(cycles, false, &cycle, nullptr, nullptr);
    return b->cycle() - start;
}

uint64_t bot_sim_cycle(const BotSim* b) { return b->cycle(); }
void bot_sim_bench_minimal(BotSim* b, uint64_t cycles) { b->bench_minimal(cycles); }
size_t bot_sim_take_fatal(BotSim* b, char* buf, size_t len) { return b->take_fatal(buf, len); }
int bot_sim_cpu_in_reset(const BotSim* b, uint16_t* pc) { return b->cpu_in_reset(pc); }
}
