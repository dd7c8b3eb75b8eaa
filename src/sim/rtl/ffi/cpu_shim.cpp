// cpu_shim.cpp: the KCPSM6 harness models behind shim.h.
#include <cstring>
#include <string>

#include "shim.h"
#include "sim.h"

#include "Vcpu64.h"
#include "Vcpu64___024root.h"
#include "Vcpu128.h"
#include "Vcpu128___024root.h"
#include "Vcpu256.h"
#include "Vcpu256___024root.h"

// $finish only marks the context finished (spec/verilator.md H4).
void vl_finish(const char* filename, int linenum, const char* hier) VL_MT_UNSAFE {
    (void)filename;
    (void)linenum;
    (void)hier;
    Verilated::threadContextp()->gotFinish(true);
}

// A fatal runtime error (a VCD write that failed on a full disk, say) stops the model instead
// of aborting the process: the message is kept by the model it stopped (current_fatal, set by
// Sim::enter) for its caller (bot_sim_take_fatal, cpu_sim_take_fatal).
void vl_fatal(const char* filename, int linenum, const char* hier, const char* msg) VL_MT_UNSAFE {
    (void)filename;
    (void)linenum;
    (void)hier;
    Verilated::threadContextp()->gotError(true);
    Verilated::threadContextp()->gotFinish(true);
    if (current_fatal && current_fatal->empty()) *current_fatal = msg;
}

struct CpuSim {
    virtual ~CpuSim() {}
    virtual int open_vcd(const char* path) = 0;
    virtual void close_vcd() = 0;
    virtual void load_rom(const uint32_t* words, size_t count) = 0;
    virtual void set_inputs(const uint8_t* values) = 0;
    virtual int tick(CpuPins pins, CpuPorts* ports) = 0;
    virtual uint64_t run(CpuPins pins, uint64_t cycles) = 0;
    virtual void state(CpuState* s) = 0;
    virtual uint64_t cycle() const = 0;
    virtual size_t take_fatal(char* buf, size_t len) = 0;
};

template <class V, unsigned SPM>
struct CpuModel final : CpuSim {
    Sim<V> sim;

    int open_vcd(const char* path) override { return sim.open_vcd(path, 99) ? 0 : -1; }
    void close_vcd() override {
        sim.enter();
        sim.close_vcd();
    }

    void load_rom(const uint32_t* words, size_t count) override {
        sim.enter();
        auto& rom = sim.top->rootp->kcpsm6_harness__DOT__rom;
        for (size_t i = 0; i < 4096; i++) rom[i] = i < count ? (words[i] & 0x3FFFF) : 0;
    }

    void set_inputs(const uint8_t* values) override {
        sim.enter();
        auto& in = sim.top->rootp->kcpsm6_harness__DOT__inputs;
        for (size_t i = 0; i < 256; i++) in[i] = values[i];
    }

    void drive(CpuPins pins) {
        V* t = sim.top;
        t->reset = pins.reset;
        t->sleep = pins.sleep;
        t->__SYM__interrupt = pins.interrupt;  // `interrupt` is a C++ word: renamed by Verilator
    }

    int tick(CpuPins pins, CpuPorts* p) override {
        sim.enter();
        if (sim.finished()) return -1;
        V* t = sim.top;
        drive(pins);
        sim.settle();
        if (p) {
            p->address = t->address;
            p->instruction = t->instruction;
            p->bram_enable = t->bram_enable;
            p->port_id = t->port_id;
            p->out_port = t->out_port;
            p->in_port = t->in_port;
            p->read_strobe = t->read_strobe;
            p->write_strobe = t->write_strobe;
            p->k_write_strobe = t->k_write_strobe;
            p->interrupt_ack = t->interrupt_ack;
        }
        sim.rise();
        return 0;
    }

    uint64_t run(CpuPins pins, uint64_t cycles) override {
        sim.enter();
        uint64_t n = 0;
        drive(pins);
        for (; n < cycles && !sim.finished(); n++) {
            sim.settle();
            sim.rise();
        }
        return n;
    }

    void state(CpuState* s) override {
        sim.enter();
        auto* r = sim.top->rootp;
        s->pc = r->kcpsm6_harness__DOT__cpu__DOT__pc;
        s->t_state = r->kcpsm6_harness__DOT__cpu__DOT__t_state;
        s->carry = r->kcpsm6_harness__DOT__cpu__DOT__carry;
        s->zero = r->kcpsm6_harness__DOT__cpu__DOT__zero;
        s->interrupt_enable = r->kcpsm6_harness__DOT__cpu__DOT__interrupt_enable;
        s->bank = r->kcpsm6_harness__DOT__cpu__DOT__bank;
        s->xb = r->kcpsm6_harness__DOT__cpu__DOT__xb;
        s->depth = r->kcpsm6_harness__DOT__cpu__DOT__depth;
        s->run = r->kcpsm6_harness__DOT__cpu__DOT__run;
        s->internal_reset = r->kcpsm6_harness__DOT__cpu__DOT__internal_reset;
        s->active_interrupt = r->kcpsm6_harness__DOT__cpu__DOT__active_interrupt;
        for (int i = 0; i < 32; i++) s->registers[i] = r->kcpsm6_harness__DOT__cpu__DOT__registers[i];
        std::memset(s->scratch_pad, 0, sizeof s->scratch_pad);
        for (unsigned i = 0; i < SPM; i++) s->scratch_pad[i] = r->kcpsm6_harness__DOT__cpu__DOT__scratch_pad[i];
        s->scratch_pad_size = SPM;
    }

    uint64_t cycle() const override { return sim.cycle; }
    size_t take_fatal(char* buf, size_t len) override { return sim.take_fatal(buf, len); }
};

extern "C" {

CpuSim* cpu_sim_new(uint32_t scratch_pad_size) {
    switch (scratch_pad_size) {
        case 64: return new CpuModel<Vcpu64, 64>;
        case 128: return new CpuModel<Vcpu128, 128>;
        case 256: return new CpuModel<Vcpu256, 256>;
        default: return nullptr;
    }
}

void cpu_sim_free(CpuSim* sim) { delete sim; }
int cpu_sim_open_vcd(CpuSim* sim, const char* path) { return sim->open_vcd(path); }
void cpu_sim_close_vcd(CpuSim* sim) { sim->close_vcd(); }
void cpu_sim_load_rom(CpuSim* sim, const uint32_t* words, size_t count) { sim->load_rom(words, count); }
void cpu_sim_set_inputs(CpuSim* sim, const uint8_t* values) { sim->set_inputs(values); }
int cpu_sim_tick(CpuSim* sim, CpuPins pins, CpuPorts* ports) { return sim->tick(pins, ports); }
uint64_t cpu_sim_run(CpuSim* sim, CpuPins pins, uint64_t cycles) { return sim->run(pins, cycles); }
void cpu_sim_state(CpuSim* sim, CpuState* state) { sim->state(state); }
uint64_t cpu_sim_cycle(const CpuSim* sim) { return sim->cycle(); }
size_t cpu_sim_take_fatal(CpuSim* sim, char* buf, size_t len) { return sim->take_fatal(buf, len); }
}
