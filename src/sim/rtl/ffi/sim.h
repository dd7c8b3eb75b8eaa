// sim.h: one Verilated model with its own context, the clock discipline and tracing.
//
// Every Verilator 5.006 hazard of spec/verilator.md is handled here, once:
//  H1  teardown in reverse order with the thread's context set (Sim::~Sim);
//  H2  Verilated::threadContextp(ctx) at every entry that runs RTL or touches the runtime;
//  H3  ctx->threads(1): no idle worker threads per model;
//  H4  $finish only sets gotFinish (vl_finish below, runtime built with VL_USER_FINISH), and
//      nothing is evaluated after it (tick() refuses);
//  H5  fatalOnError(false): $stop/$error/$fatal set gotError/gotFinish instead of abort().
#pragma once

#include <atomic>
#include <cstdint>
#include <cstring>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>

#include "verilated.h"
#include "verilated_vcd_c.h"
#if VM_COVERAGE
#include "verilated_cov.h"
#endif

// Half a clock period in the model's time precision (`timescale 1ns / 1ps`): 100 MHz.
static const uint64_t HALF_PERIOD_PS = 5000;

// Where vl_fatal keeps its message: the model that runs on this thread now (Sim::enter), so a
// fatal error is reported by the model it stopped, not by another one on the same thread.
inline thread_local std::string* current_fatal = nullptr;

// Copy `msg` into `buf` (`len` bytes, NUL-terminated when len > 0); its full length.
inline size_t copy_message(const std::string& msg, char* buf, size_t len) {
    if (len > 0) {
        const size_t n = msg.size() < len - 1 ? msg.size() : len - 1;
        std::memcpy(buf, msg.data(), n);
        buf[n] = 0;
    }
    return msg.size();
}

template <class V>
struct Sim {
    VerilatedContext* ctx;
    V* top;
    VerilatedVcdC* vcd = nullptr;
    uint64_t cycle = 0;
    uint64_t last_dump = ~0ull;  // time of the last VCD sample: each time stamp is dumped once
    std::string fatal;           // the fatal runtime error that stopped this model, if any

    Sim() {
        ctx = new VerilatedContext;
        Verilated::threadContextp(ctx);
        ctx->threads(1);
        ctx->fatalOnError(false);
        ctx->traceEverOn(true);
        // X hygiene: with BOTSIM_X_SEED=N every variable without a power-up value starts
        // from random bits (the build uses --x-initial unique), so a test run with several
        // seeds shows the RTL depends on no state the device does not initialise.
        if (const char* seed = std::getenv("BOTSIM_X_SEED")) {
            ctx->randReset(2);
            ctx->randSeed(std::atoi(seed));
        }
        top = new V{ctx, "TOP"};
        top->clk = 0;
        top->eval();  // initialisation: never an edge
    }

    ~Sim() {
        enter();
        close_vcd();
        top->final();
#if VM_COVERAGE
        // A coverage build writes one file per model into $BOTSIM_COVERAGE_DIR.
        static std::atomic<unsigned> serial{0};
        if (const char* dir = std::getenv("BOTSIM_COVERAGE_DIR")) {
            std::string path = std::string(dir) + "/cov-" + std::to_string(getpid()) + "-" +
                               std::to_string(serial++) + ".dat";
            ctx->coveragep()->write(path.c_str());
        }
#endif
        delete top;
        delete ctx;
        if (current_fatal == &fatal) current_fatal = nullptr;
    }

    void enter() {
        Verilated::threadContextp(ctx);
        current_fatal = &fatal;
    }

    // Take the fatal message (see copy_message); it is cleared.
    size_t take_fatal(char* buf, size_t len) {
        const size_t n = copy_message(fatal, buf, len);
        fatal.clear();
        return n;
    }

    bool finished() const { return ctx->gotFinish(); }

    // Open a VCD file; its first sample is the current state.
    bool open_vcd(const char* path, int depth) {
        enter();
        close_vcd();
        vcd = new VerilatedVcdC;
        top->trace(vcd, depth);
        vcd->open(path);
        if (!vcd->isOpen()) {
            delete vcd;
            vcd = nullptr;
            return false;
        }
        dump();
        return true;
    }

    void close_vcd() {
        if (vcd) {
            vcd->flush();
            vcd->close();
            delete vcd;
            vcd = nullptr;
        }
    }

    void dump() {
        if (vcd && last_dump != ctx->time()) {
            vcd->dump(ctx->time());
            last_dump = ctx->time();
        }
    }

    // Settle the inputs set for this cycle with the clock low (dumped at the cycle's start;
    // settling the same cycle again after changing an input re-evaluates without a second dump).
    void settle() {
        top->clk = 0;
        top->eval();
        dump();
    }

    // The rising edge that ends the cycle; the clock falls at the start of the next settle().
    void rise() {
        ctx->timeInc(HALF_PERIOD_PS);
        top->clk = 1;
        top->eval();
        dump();
        ctx->timeInc(HALF_PERIOD_PS);
        cycle++;
    }
};
