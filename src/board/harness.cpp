// harness.cpp: the C++ side of botsim's board simulation, linked with each design's
// Verilated `botsim_board` into one shared library that botsim loads at run time. It is
// compiled once for every design (beside Verilator's run-time library) and sees the design's
// model through board_model.h.
//
// The scheduler: the board oscillator (100 MHz, the wrapper's `clk`) and every
// botsim_clkgen instance (found by its public variables) are clocks with exact rational
// periods; the harness advances time to the next edge of any running clock, sets every clock
// that changes then, evaluates once, dumps the waveform if one is open, and records what the
// board shows (display and LED changes, every upd_sysregs of the bot) into the caller's buffer.
#include "board_model.h"
#include "verilated.h"
#include "verilated_syms.h"
#include "verilated_vcd_c.h"
#include "svdpi.h"
#include "botsim_disasm.h"

#include <algorithm>
#include <array>
#include <sstream>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <string>
#include <vector>

extern "C" {
#include "board_abi.h"
}

namespace {

// A clock edge's time, rounded to the picosecond: q + r / den, the numerator carrying den / 2
// for the rounding. Stepping it by a period adds and carries; nothing divides per edge.
struct EdgeTime {
    uint64_t q = 0, r = 0;
};

struct Clock {
    CData* q;                  // the level the harness drives
    const CData* run;          // null: always runs
    uint64_t num, den;         // period = num / den ps
    uint64_t phase_num;        // rising edge k at (phase_num + k * num) / den ps
    uint64_t high_num;         // the high time, num * duty / 1000
    uint64_t step_q = 0, step_r = 0;  // num / den, num % den
    EdgeTime rise, fall;       // the next rising and falling edges
    bool next_high = true;
    uint64_t next_t = 0;
    bool stopped = false;
    bool parked = false;       // not run: it drives nothing a fast-forwarding run observes

    Clock(CData* q_, const CData* run_, uint64_t num_, uint64_t den_, uint64_t phase_num_, uint64_t duty_permille)
        : q(q_), run(run_), num(num_), den(den_), phase_num(phase_num_),
          high_num((uint64_t)((unsigned __int128)num_ * duty_permille / 1000)),
          step_q(num_ / den_), step_r(num_ % den_) {}

    // Start with period k's rising edge.
    void start_at(uint64_t k) {
        unsigned __int128 nr = (unsigned __int128)phase_num + (unsigned __int128)k * num + den / 2;
        unsigned __int128 nf = nr + high_num;
        rise = {(uint64_t)(nr / den), (uint64_t)(nr % den)};
        fall = {(uint64_t)(nf / den), (uint64_t)(nf % den)};
        next_high = true;
        next_t = rise.q;
    }
    // The first rising edge at or after `now` (when a clock starts).
    void schedule_from(uint64_t now) {
        unsigned __int128 scaled = (unsigned __int128)now * den;
        unsigned __int128 k = scaled > phase_num ? (scaled - phase_num + num - 1) / num : 0;
        start_at((uint64_t)k);
    }
    void step(EdgeTime& e) const {
        e.q += step_q;
        e.r += step_r;
        if (e.r >= den) {
            e.r -= den;
            e.q++;
        }
    }
    // Skip `k` whole periods (the level and the kind of the next edge stay).
    void skip(uint64_t k) {
        for (EdgeTime* e : {&rise, &fall}) {
            unsigned __int128 r = (unsigned __int128)e->r + (unsigned __int128)k * step_r;
            e->q += k * step_q + (uint64_t)(r / den);
            e->r = (uint64_t)(r % den);
        }
        next_t = next_high ? rise.q : fall.q;
    }
    void advance() {
        if (next_high) {
            next_high = false;
            next_t = fall.q;
            step(rise);
        } else {
            next_high = true;
            next_t = rise.q;
            step(fall);
        }
    }
};

}  // namespace

// The longest period the fast-forward looks for (2^22 clocks of 100 MHz, 42 ms); how long the
// models must have been quiet (no interrupt, nothing from or to the bot) before it marks,
// while the firmware answers (2^14 clocks, 164 us); how long a first mark waits for its
// period when none is known yet (each later one waits twice as long, up to the longest); how
// many phase snapshots a period gets at most (each at least the settling time apart, or a
// sixteenth of the period found last when that is shorter).
constexpr uint64_t kMaxPeriodPs = (1ull << 22) * 10000;
constexpr uint64_t kSettlePs = (1ull << 14) * 10000;
constexpr uint64_t kFirstPatiencePs = (1ull << 16) * 10000;
// After a counter's value became one the design can tell apart (a digit of the display
// lit, a divider's toggle flipped), the board settles this long before a mark (2^8 clocks),
// and a mark waits at least this long for its period (2^10 clocks) before another is taken.
constexpr uint64_t kCounterSettlePs = (1ull << 8) * 10000;
constexpr uint64_t kShortPatiencePs = (1ull << 10) * 10000;
constexpr size_t kMaxPhases = 64;
constexpr uint64_t kPhasesPerPeriod = 16;
// A skip of fewer clocks than this costs more than it saves (a mark, a proof, a skip:
// about 60 clocks' simulation each); after this many in a row (a UART's baud tick ending
// every skip) every settle lasts a rest, doubled after as many again up to the longest,
// and none once a skip pays.
constexpr uint64_t kWorthPs = (1ull << 8) * 10000;
constexpr int kPoorSkips = 64;
constexpr uint64_t kFirstRestPs = (1ull << 10) * 10000;
constexpr uint64_t kMaxRestPs = (1ull << 16) * 10000;
// A counter that turns at every skip is tried as state when its turns are this many in a row,
// at most this far apart, at least this many of the period found apart, and the longer
// period is at most this many turns (see Counting); a trial pays when it skips at least this
// many periods.
constexpr int kTurnsBeforeTrial = 3;
constexpr uint64_t kMaxTurnEveryPs = (1ull << 16) * 10000;
constexpr uint64_t kTurnPeriods = 2;
constexpr uint64_t kMaxTrialTurns = 4;
constexpr uint64_t kTrialPays = 4;
// A free part (FreePart): how long the board is watched for one (2^13 clocks), how long its
// cycle may be (2^16 clocks), and how many marks in a row its contact may end before it is
// given up.
constexpr uint64_t kFreeWatchPs = (1ull << 13) * 10000;
constexpr uint64_t kMaxFreeCycle = 1ull << 16;
constexpr int kFreeContactMisses = 8;
// After a watch that found none, this many marks without a period pass before the next watch,
// doubled after each such up to the most.
constexpr int kFreeMostWait = 64;
// The values a counter's turns are remembered at (Counting::turns), the least recently turned
// at forgotten first.
constexpr size_t kTurnValues = 8;
// The most records a period may show (the display's pins multiplexed every few clocks, an LED
// dimmed): more, and the mark is taken again. A skip writes one period's and a phase's; the
// caller's buffer (model.rs's RECORDS) has room for both.
constexpr size_t kMaxShown = 1 << 16;
// The most records one evaluation writes: the display, the VGA pins, the LEDs, the lines, the
// bot's outputs, its sample and the other bots' three.
constexpr uint32_t kMaxPerEval = 9;
// Words that differed before the last, looked at before a full comparison (ff_step).
constexpr size_t kOldHints = 3;

// The fast-forward (a one-clock board whose KCPSM6s are models and whose bot is a model):
// after a rising edge, when the whole model (every byte of Verilator's state, every KCPSM6
// model's state but for its cycle count) is as it was at a mark, with nothing written,
// interrupted or changed at the bot's inputs since, the board repeats that period for as long
// as nothing changes it. The board then skips ahead to just before the next change it can
// foresee (the bot's next port write, the end of the run): whole periods, then part of one by
// putting back a snapshot taken at that phase while the period was proved. The models run on
// by as many cycles (the bot simulates them, cheaply), and what the board showed in the
// period (display and LED changes) is repeated into the records, so the records are the same
// as the edge-by-edge run's. The build checks that Verilator's state is all in its root
// object (src/fastforward/checks.rs).
//
// A run that records only what the board shows (no waveform later, no VGA frames) compares
// and puts back only the variables it observes (src/fastforward/observed.rs); the parts nothing
// recorded reads (a VGA timing generator) are left as they are, and clocks that drive only
// such parts (its pixel clock) are not run. That lets a VGA design skip ahead too, as a
// one-clock board: its frame and its display refresh never repeat together within a sample,
// but its display refresh and firmware do.
struct Span {
    uint32_t off, len;  // bytes of the root object
};

// A counter at run time: the values around the mark's in which no read of the design can tell
// it apart, [lo, lo + width) modulo 2^bits, and how far it moved in the period last found.
//
// How much of it counts: a counter is first taken whole (level 0: it must stay in its
// interval from the mark until the skip). One that leaves it before a period is found twice
// in a row (once may be a long counter marked just before its turn; the mark is then taken
// again) is a short counter (a wrap counter of a few clocks, the low byte a PWM compares): it
// is then compared as state, its bits below the split only (level 1: they repeat, the rest
// still counts), or all of them (level 2). A level holds from mark to mark, until a mark
// finds no period.
//
// A counter that turns at every skip, at each of its values the same time apart (a VGA line's
// pixel counter: each line is a few marks, a short period proved and a skip to the next value
// a read tells apart, where the sync pulse or the visible part begins or ends; the counter
// turns at each of those values once a line) may be the inner one of a longer period with another counter
// (a few lines, with the line counter): when that period (a few of its turns: the least
// common multiple of the turns and the period found) is short, the counter is tried as state
// (level 2), so that the longer period is found and skipped whole. A trial that finds no
// period, or one too short to skip much, puts it back and waits longer to try again.
struct Counting {
    BoardCounter c;
    uint64_t mask = 0;
    uint64_t lo = 0, width = 0;
    // The part of the interval around the mark's value without a constant the counter may
    // be set to (see FastForward::unsteady).
    uint64_t steady_lo = 0, steady_width = 0;
    uint64_t drift = 0;
    int level = 0;
    uint64_t exact = 0;  // the bits compared as state (level 1: those below the split)
    int early = 0;       // marks in a row it left its interval before a period was found
    // Its last turns after a skip, one per value it turned at (a VGA line's pixel counter
    // turns at a few values a line: where the sync pulse and the visible part begin and end):
    // when, how long after its turn at the same value before, how many times in a row so.
    struct Turn {
        uint64_t value = 0, at = 0, every = 0;
        int repeats = 0;
    };
    std::array<Turn, kTurnValues> turns{};
    size_t nturns = 0;
    // Tried as state for a longer period: its first skip to come judges it (Open), or it
    // paid (Paid) and stays state until a mark finds no period.
    enum class Trial : uint8_t { None, Open, Paid } trial = Trial::None;
    int tried = 0;                           // trials ended since one last paid
    std::vector<uint64_t> bound_values;      // the compared variables' values at the mark
};

// Where a clock is in its period at a moment `t`: its next edges after `t` (the fractions of a
// picosecond kept), which comes next, and whether it runs. Two moments with every clock where
// it was differ by whole periods of each.
struct ClockPhase {
    uint64_t rise = 0, rise_r = 0, fall = 0, fall_r = 0;
    bool next_high = false, stopped = false;
    bool operator==(const ClockPhase& o) const {
        return stopped == o.stopped &&
               (stopped || (rise == o.rise && rise_r == o.rise_r && fall == o.fall && fall_r == o.fall_r &&
                            next_high == o.next_high));
    }
};
inline ClockPhase phase_of(const Clock& c, uint64_t t) {
    return {c.rise.q - t, c.rise.r, c.fall.q - t, c.fall.r, c.next_high, c.stopped};
}
inline void set_phase(Clock& c, const ClockPhase& p, uint64_t t) {
    c.rise = {t + p.rise, p.rise_r};
    c.fall = {t + p.fall, p.fall_r};
    c.next_high = p.next_high;
    c.stopped = p.stopped;
    c.next_t = c.next_high ? c.rise.q : c.fall.q;
}

struct Phase {
    uint64_t at = 0;            // ps after the mark
    std::vector<uint8_t> root;  // Verilator's state then
    std::vector<ClockPhase> clocks;  // and every clock's
    size_t shown = 0;           // the period's records up to then
    uint64_t bot_cycles = 0;    // the bot's clock edges from the mark to then (the wrapper's count)
};

// A KCPSM6 model's outputs register in kcpsm6_iss.v and the model: the fast-forward compares
// the model (ff_same), not its outputs, and sets them from the model after a skip (a core that
// counts shows its count on out_port).
struct IssShim {
    size_t q, cpu;
    // Verilator's delayed copy of `q` (`__Vdly__...botsim_iss_q`, made when other
    // non-blocking logic reads the outputs at the same edge), or SIZE_MAX: the outputs again,
    // so neither compared nor left stale after a skip.
    size_t q_dly;
};

// A KCPSM6 model that may run apart from the board (src/fastforward/apart.rs: what it shows between
// port accesses reaches nothing but its followers, the variables that only feed its own
// `instruction` and `in_port`). While the host says it runs apart (from a mark on), neither
// it nor its followers are compared: the host runs it on its own over a skip, up to just
// before its next port access, and the followers, written in full at every edge, are its
// again an edge later.
struct ApartCore {
    size_t cpu;                   // where its model pointer is
    std::vector<Span> followers;  // their bytes
    bool on = false;
};

// A free part: variables that change among themselves alone while everything they read from
// the rest of the board, and everything of theirs the rest reads, stays as it was (a baud
// rate divider running beside an idle UART, a free-running LFSR whose output nothing takes
// while the firmware waits). Such a part, closed but for constants, repeats its own cycle
// forever, whatever the rest does; the rest sees only constants from it, so its period is
// found without it. Its contact (what crosses between the two, by the reads of
// src/fastforward/observed.rs) stays as it was at every clock, it comes back to its bytes within
// its cycle, the rest repeats its period: a skip then puts the part at its place in its cycle,
// a table of its bytes at each clock since the cycle began. Found by watching which variables
// change after a mark finds no period: those that change, joined with what reads them, in a
// group that touches nothing that leaves the model (records, DPI); a board may have several.
struct FreeGroup {
    std::vector<Span> part, contact;  // its bytes; those that must stay as at `origin`
    size_t bytes = 0;                 // its bytes in all
    std::vector<uint8_t> cycle;       // its bytes at each clock since `origin`
    // The contact as aligned words of the root and the bytes of each it covers (a load and a
    // compare each at every clock), and their values at `origin`.
    std::vector<std::pair<size_t, uint64_t>> words;
    std::vector<uint64_t> touch_words;
    uint64_t q = 0;                   // its cycle in clocks (0: not found yet)
    uint64_t origin = 0;              // when the cycle's first bytes were taken
    uint64_t next_t = 0;              // the clock it looks at next (another: one not seen)
    int misses = 0;                   // contact changes since its last skip
};
struct FreePart {
    bool watching = false;
    std::vector<BoardMember> order;   // the members in botsim_observed.h's order (reads' indices)
    std::vector<uint8_t> vary;        // while watching: the bits that changed from a mark
    std::vector<Span> watched;        // the observed variables' bytes
    uint64_t watch_until = 0;
    int wait = 0, waited = 0;         // marks without a period before the next watch
    size_t blocker = 0;               // the byte that kept the mark before the watch
    std::vector<FreeGroup> groups;    // the free parts found, each with its own cycle
    std::vector<char> taken;          // the bytes of the root in one of them
    std::vector<Counting> counters;   // their counters: not counted while they are free
};

struct FastForward {
    bool on = false;
    FreePart free;
    std::vector<IssShim> shims;
    std::vector<ApartCore> apart;
    std::vector<char> apart_bytes;  // the root's bytes of the followers of the cores apart
    std::vector<Span> all_spans;    // the compared spans with no free part and no core apart
    std::vector<uint8_t> mark;  // Verilator's state at the mark
    std::vector<ClockPhase> mark_clocks;  // and every clock's
    bool marked = false;
    bool proven = false;        // the mark's period is known, and `shown` holds it
    uint64_t mark_t = 0;        // the mark's time
    uint64_t activity = ~0ull;  // the models' activity count last seen, and since when
    uint64_t quiet_from = 0;
    uint64_t patience = 0;      // how long the mark waits for its period
    uint64_t last_period = 0;   // the period found last (the next is likely the same)
    std::vector<Span> spans;     // what is compared and put back
    bool observed_only = false;  // the spans are what a run observes (no VGA pins)
    size_t hint = 0;             // the aligned word that differed last, and its compared bytes
    uint64_t hint_mask = 0;
    bool hint_is_span = false;   // (a word of the spans, not a counter's compared bits)
    // Words of the spans that differed before it (see ff_step).
    std::array<size_t, kOldHints> old_hint{};
    std::array<uint64_t, kOldHints> old_mask{};
    size_t next_old = 0;
    size_t bot_cycles = 0;       // where the wrapper's bot_cycles counter is (not compared)
    uint64_t mark_bot_cycles = 0;  // its value at the mark
    std::vector<BoardEvent> shown;  // what the board showed in the period, times from the mark
    bool overflow = false;          // too much for `shown`: no skip from this mark
    std::vector<Phase> phases;      // snapshots while the period is proved (buffers reused)
    size_t nphases = 0;
    uint64_t phase_every = 0;  // ps between snapshots
    uint64_t skips = 0, skipped_ps = 0;
    // Counters (observed-only runs): compared by what the design can tell of them, moved on
    // by their drift per period once two periods in a row moved each by the same amount.
    std::vector<Counting> counters;
    bool drifting = false;       // the last period moved a counter: the next must move it as far
    // Since the mark, a counter took a value outside its steady interval (one it may be set
    // to, or beyond): it may have been set to a constant, so a period that moved it proves
    // nothing alone. Without that, every write to a counter in the period was a step (a set
    // would have left it on its constant), and the next period moves each as far: one
    // period is proof enough.
    bool unsteady = false;
    uint64_t settle = 0;         // how long the models stay quiet before a mark
    int poor = 0;                // skips in a row too short to pay for their proof
    uint64_t rest = 0;           // after too many: how long every settle lasts at least
    // Why marks found no period: for each variable (by offset), how many marks it ended by
    // still differing, or by a counter leaving its interval before a skip.
    std::vector<BoardMember> members;
    std::vector<uint64_t> busy;
    // For each variable, how many skips a counter's interval ended (the next value the
    // design compares it with came before anything else did).
    std::vector<uint64_t> cut;
};

// The hints forgotten (the compared spans changed): the next edge compares in full.
inline void reset_hints(FastForward& f) {
    f.hint = 0;
    f.hint_mask = 0;
    f.old_mask.fill(0);
    f.hint_is_span = false;
}

// The variable whose byte `off` is, in the (sorted) members, or -1.
inline long member_at(const FastForward& f, size_t off) {
    size_t lo = 0, hi = f.members.size();
    while (lo < hi) {
        const size_t mid = (lo + hi) / 2;
        if (f.members[mid].off + f.members[mid].len <= off) lo = mid + 1;
        else hi = mid;
    }
    return lo < f.members.size() && f.members[lo].off <= off ? (long)lo : -1;
}

// The variable counted most often in `times` (by member), and how often; 0 when none was.
inline uint64_t most_often(const FastForward& f, const std::vector<uint64_t>& times, const char** name) {
    uint64_t most = 0;
    *name = "";
    for (size_t i = 0; i < times.size(); i++) {
        if (times[i] > most) {
            most = times[i];
            *name = f.members[i].name;
        }
    }
    return most;
}

// The design's name of the variable at `off` (for BOTSIM_FF_TRACE), or "?".
inline const char* member_name(const FastForward& f, size_t off) {
    for (const BoardMember& m : f.members)
        if (m.off == off) return m.name;
    return "?";
}

struct Board {
    VerilatedContext ctx;
    DesignModel model{};  // the design's (board_model.cpp)
    BoardPorts io{};      // its ports
    VerilatedVcdC* vcd = nullptr;
    std::vector<Clock> clocks;
    uint64_t now = 0;
    uint64_t evals = 0;
    uint8_t last_an = 0xFF, last_seg = 0x7F, last_dp = 1;
    uint16_t last_led = 0;
    uint16_t last_lines = 0xFFFF;  // the peripherals' lines (none yet: the first is recorded)
    bool rising_only = false;  // evaluate at rising clock edges only (nothing on falling ones)
    bool vga = false;  // record the VGA pins (only when frames are asked for)
    uint16_t last_vga = 0x3000;
    bool bot = false;  // record every change of the bot's outputs (lock-step runs)
    uint64_t last_bot = 0;
    bool last_upd = false;
    uint64_t samples = 0;
    uint8_t last_xupd = 0;        // the other bots' upd_sysregs
    uint32_t xsamples[3] = {0, 0, 0};
    std::string fatal;
    std::string finish;      // where the design called $finish
    std::string error_said;  // the message of the design's last $error or $fatal
    BoardHost* host = nullptr;  // the KCPSM6 models of a --cpu iss build
    FastForward ff;
};

static thread_local Board* current = nullptr;

// Thrown by the runtime's fatal-error, $stop and $readmem handlers (below) out of the
// model's evaluation to the harness's entry point.
struct Stopped {};

// Close a board's waveform. One that could not be written (a full disk) stopped the run;
// closing it writes no more.
static void close_vcd(Board* b) {
    if (!b->vcd) return;
    try {
        b->vcd->close();
    } catch (const Stopped&) {
    }
    delete b->vcd;
    b->vcd = nullptr;
}

// Every call into a board first makes it the thread's current one: for the harness's DPI
// functions and vl_fatal, and for Verilator's runtime, which reaches the model's context
// through the thread (several boards on one thread, as in a lock-step run, take turns).
static inline void enter(Board* b) {
    current = b;
    Verilated::threadContextp(&b->ctx);
}

// The whole evaluation (Vboard::eval()), for inputs set from outside a run.
static inline void eval(Board* b) { b->model.eval(b->model.top); }

extern "C" {

Board* board_new_hosted(int argc, const char** argv, BoardHost* host) {
    Board* b = new Board;
    b->host = host;
    b->ctx.commandArgs(argc, argv);
    b->ctx.traceEverOn(true);
    b->ctx.fatalOnError(false);
    enter(b);
    b->model = botsim_model_new(&b->ctx);
    b->io = b->model.io;
    *b->io.clk = 0;
    *b->io.reset_pressed = 0;
    *b->io.btn = 0;
    *b->io.sw = 0;
    *b->io.uart_div = 868;  // 115200 baud
    *b->io.tilt_z = 1000;   // lying flat: +1 g on z
    // A design that stops at power-up (a $fatal, a loop that never settles) is a board that
    // has finished: its first run says so.
    try {
        eval(b);
    } catch (const Stopped&) {
    }
    // The oscillator, then every generated clock.
    Clock osc(b->io.clk, nullptr, 10000, 1, 0, 500);
    osc.schedule_from(1);
    b->clocks.push_back(osc);
    for (auto& kv : *b->ctx.scopeNameMap()) {
        const VerilatedScope* s = kv.second;
        const VerilatedVar* q = s->varFind("q");
        const VerilatedVar* num = s->varFind("botsim_period_num");
        if (!q || !num) continue;
        uint64_t period_num = (uint32_t) * (IData*)num->datap();
        uint64_t period_den = (uint32_t) * (IData*)s->varFind("botsim_period_den")->datap();
        if (period_den == 0 || period_num == 0) continue;
        int32_t mdeg = *(IData*)s->varFind("botsim_phase_mdeg")->datap();
        int64_t m = ((int64_t)mdeg % 360000 + 360000) % 360000;
        Clock c((CData*)q->datap(), (const CData*)s->varFind("running")->datap(), period_num, period_den,
                period_num * (uint64_t)m / 360000, *(IData*)s->varFind("botsim_duty_permille")->datap());
        c.stopped = true;
        b->clocks.push_back(c);
    }
    return b;
}

Board* board_new(int argc, const char** argv) { return board_new_hosted(argc, argv, nullptr); }

void board_free(Board* b) {
    if (!b) return;
    enter(b);
    close_vcd(b);
    try {
        b->model.final(b->model.top);
    } catch (const Stopped&) {
    }
    b->model.destroy(b->model.top);
    delete b;
}

int board_open_vcd(Board* b, const char* path) {
    enter(b);
    if (b->vcd) return 0;
    b->vcd = new VerilatedVcdC;
    b->model.trace(b->model.top, b->vcd, 99);
    b->vcd->open(path);
    if (!b->vcd->isOpen()) {
        delete b->vcd;
        b->vcd = nullptr;
        return 0;
    }
    b->vcd->dump(b->now);
    return 1;
}

void board_close_vcd(Board* b) {
    enter(b);
    close_vcd(b);
}

size_t board_clock_count(Board* b) { return b->clocks.size(); }

void board_clock(Board* b, size_t i, uint64_t* num, uint64_t* den) {
    *num = b->clocks[i].num;
    *den = b->clocks[i].den;
}

void board_set_inputs(Board* b, uint32_t reset_pressed, uint32_t buttons, uint32_t switches) {
    enter(b);
    *b->io.reset_pressed = reset_pressed & 1;
    *b->io.btn = buttons & 0x1F;
    *b->io.sw = switches & 0xFFFF;
    try {
        eval(b);
    } catch (const Stopped&) {
    }
    b->evals++;
    // The fast-forward's mark and snapshots hold the inputs they saw: look for a new period.
    b->ff.marked = false;
    b->ff.quiet_from = b->now;
}

// Send `n` (1-8) bytes to a device (BOARD_UART, BOARD_KEYBOARD): 1 when it takes them (at the
// next clock edge); 0 when a push waits for its clock edge (try at the next); -1 when its
// queue has too little room (try when it has sent some; a design without the device has
// none).
int board_push(Board* b, uint32_t device, const uint8_t* bytes, uint32_t n) {
    enter(b);
    const BoardPorts& io = b->io;
    const uint32_t room = device == BOARD_UART ? *io.uart_room : *io.ps2_room;
    if (n == 0 || n > 8 || *io.uart_pending || *io.ps2_pending) return 0;
    if (room < n) return -1;
    uint64_t v = 0;
    for (uint32_t i = 0; i < n; i++) v |= (uint64_t)bytes[i] << (8 * i);
    *io.push_bytes = v;
    *io.push_n = n;
    if (device == BOARD_UART) *io.uart_push ^= 1;
    else *io.ps2_push ^= 1;
    try {
        eval(b);
    } catch (const Stopped&) {
    }
    b->evals++;
    b->ff.marked = false;
    b->ff.quiet_from = b->now;
    return 1;
}

// The UART's clocks of 100 MHz per bit into the FPGA, and the board's tilt in mg.
void board_set_uart_div(Board* b, uint32_t div) {
    enter(b);
    *b->io.uart_div = div < 1 ? 1 : div;
    b->ff.marked = false;
}
void board_set_tilt(Board* b, int32_t x, int32_t y, int32_t z) {
    enter(b);
    *b->io.tilt_x = (uint16_t)(int16_t)x;
    *b->io.tilt_y = (uint16_t)(int16_t)y;
    *b->io.tilt_z = (uint16_t)(int16_t)z;
    b->ff.marked = false;
    b->ff.quiet_from = b->now;
}

void board_record_vga(Board* b, int on) { b->vga = on != 0; }
void board_record_bot(Board* b, int on) { b->bot = on != 0; }

uint64_t board_time_ps(Board* b) { return b->now; }
uint64_t board_evals(Board* b) { return b->evals; }
uint64_t board_bot_cycles(Board* b) { return *b->io.bot_cycles; }

static inline void record(BoardEvent* buf, uint32_t* n, uint64_t t, uint32_t kind, uint32_t a, uint64_t bb, uint64_t c) {
    BoardEvent& e = buf[(*n)++];
    e.time_ps = t;
    e.kind = kind;
    e.a = a;
    e.b = bb;
    e.c = c;
}

// Evaluate at rising clock edges only (the build found that nothing happens on the falling
// ones); a waveform still gets every edge.
int board_rising_edges_only(Board* b, int on) {
    if (!b->model.eval_triggers) on = 0;  // without it the levels cannot be noted alone
    b->rising_only = on != 0;
    return b->rising_only;
}

// The KCPSM6 models of the design (kcpsm6_iss.v's `botsim_iss_q` and `botsim_iss_cpu`), and
// what the build found of each: the design reads its out_port only under a write strobe.
void find_shims(Board* b, const std::vector<BoardMember>& ms) {
    static const char kQ[] = "__DOT__botsim_iss_q", kCpu[] = "__DOT__botsim_iss_cpu";
    FastForward& f = b->ff;
    f.shims.clear();
    for (const BoardMember& m : ms) {
        const std::string name = m.name;
        if (name.size() <= sizeof kQ - 1 || name.compare(name.size() - (sizeof kQ - 1), std::string::npos, kQ) != 0)
            continue;
        const std::string core = name.substr(0, name.size() - (sizeof kQ - 1));
        for (const BoardMember& c : ms) {
            if (c.name != core + kCpu) continue;
            size_t dly = SIZE_MAX;
            for (const BoardMember& d : ms)
                if (d.name == "__Vdly__" + name && d.len == m.len) dly = d.off;
            f.shims.push_back({m.off, c.off, dly});
            void* cpu = *(void* const*)(b->model.root + c.off);
            bool free = false;
            for (const char* const* p = b->model.out_port_free; p && *p; p++) free |= core == *p;
            if (cpu && free) (*(const BoardCpuFns* const*)cpu)->out_port_free(cpu);
            // A core that may run apart: its entry is its name, then its followers'.
            for (const char* const* p = b->model.apart; cpu && p && *p; p++) {
                std::istringstream names(*p);
                std::string name;
                names >> name;
                if (name != core) continue;
                ApartCore a;
                a.cpu = c.off;
                while (names >> name && name[0] != '@')
                    for (const BoardMember& v : ms)
                        if (v.name == name) a.followers.push_back({(uint32_t)v.off, (uint32_t)v.len});
                f.apart.push_back(a);
                (*(const BoardCpuFns* const*)cpu)->apart_capable(cpu, *p);
            }
        }
    }
}


// After a skip: every KCPSM6 model's outputs register as the model's outputs now.
inline void refresh_shims(Board* b) {
    for (const IssShim& x : b->ff.shims) {
        void* cpu = *(void* const*)(b->model.root + x.cpu);
        if (!cpu) continue;
        const uint64_t q = (*(const BoardCpuFns* const*)cpu)->state(cpu);
        *(uint64_t*)(b->model.root + x.q) = q;
        if (x.q_dly != SIZE_MAX) *(uint64_t*)(b->model.root + x.q_dly) = q;
    }
}

// The fast-forward off (0), comparing the whole state (1: a run that opens a waveform later),
// or what a run observes (2: a run that records only what the board shows); the caller knows
// when the run allows it (no VGA capture, no traces, breakpoints or lock-step). Returns
// whether it is on: the board's KCPSM6s and bot are models, and it has one clock, or only the
// oscillator drives what the run observes.
int board_fast_forward(Board* b, int mode) {
    FastForward& f = b->ff;
    const bool observed = mode == 2 && b->model.observed_known;
    // No core runs apart but where the run compares what it observes (found again below).
    for (const ApartCore& a : f.apart) {
        void* cpu = *(void* const*)(b->model.root + a.cpu);
        if (cpu) (*(const BoardCpuFns* const*)cpu)->apart_capable(cpu, nullptr);
    }
    f.apart.clear();
    f.spans.clear();
    f.counters.clear();
    if (observed) {
        std::vector<BoardCounter> cs;
        b->model.counters(b->model.root, cs);
        for (const BoardCounter& c : cs) {
            Counting k;
            k.c = c;
            k.mask = c.bits >= 64 ? ~0ull : (1ull << c.bits) - 1;
            f.counters.push_back(k);
        }
        auto counter_at = [&](size_t off) {
            for (const Counting& k : f.counters)
                if (k.c.off == off) return true;
            return false;
        };
        std::vector<BoardMember>& ms = f.members;
        ms.clear();
        b->model.members(b->model.root, ms);
        std::sort(ms.begin(), ms.end(), [](const BoardMember& x, const BoardMember& y) { return x.off < y.off; });
        f.busy.assign(ms.size(), 0);
        f.cut.assign(ms.size(), 0);
        find_shims(b, ms);
        auto shim_at = [&](size_t off) {
            for (const IssShim& x : f.shims)
                if (x.q == off || x.q_dly == off) return true;
            return false;
        };
        // Observed variables, neighbours merged across padding (no variable between them); the
        // counters apart.
        bool open = false;  // the last span may grow: no unobserved variable since it began
        for (const BoardMember& m : ms) {
            if (!m.observed || counter_at(m.off) || shim_at(m.off)) {
                open = false;
            } else if (open) {
                f.spans.back().len = (uint32_t)(m.off + m.len - f.spans.back().off);
            } else {
                f.spans.push_back({(uint32_t)m.off, (uint32_t)m.len});
                open = true;
            }
        }
    } else {
        f.spans.push_back({0, (uint32_t)b->model.root_size});
        f.members.clear();
        f.busy.clear();
        f.cut.clear();
        f.shims.clear();
    }
    // Comparing the whole state (for a waveform that opens later) finds a period only on a
    // one-clock board: a second clock's part (a VGA frame) and the rest repeat together too
    // rarely; the caller then compares what the run observes.
    f.on = mode != 0 && b->host && b->host->ff_same && !f.spans.empty() && (observed || b->clocks.size() == 1);
    f.observed_only = observed;
    // A clock that drives only what the run does not observe is not run at all (what it
    // drives stays as it is); the others run, and the fast-forward compares where each is in
    // its period too. A clock taken back goes on from now.
    for (size_t i = 1; i < b->clocks.size(); i++) {
        Clock& c = b->clocks[i];
        const size_t q = (size_t)((const uint8_t*)c.q - b->model.root);
        bool seen = !observed;
        for (const Span& x : f.spans) seen |= q >= x.off && q < x.off + x.len;
        const bool park = f.on && !seen;
        if (c.parked && !park && !c.stopped) c.schedule_from(b->now + 1);
        c.parked = park;
    }
    reset_hints(f);
    f.free = FreePart{};
    if (observed) {
        b->model.members(b->model.root, f.free.order);
        for (const BoardMember& m : f.members) {  // (sorted by their bytes)
            if (!m.observed) continue;
            std::vector<Span>& w = f.free.watched;
            if (!w.empty() && w.back().off + w.back().len >= m.off)
                w.back().len = std::max(w.back().len, (uint32_t)(m.off + m.len - w.back().off));
            else
                w.push_back({(uint32_t)m.off, (uint32_t)m.len});
        }
    }
    f.free.taken.assign(b->model.root_size, 0);
    f.apart_bytes.assign(b->model.root_size, 0);
    f.all_spans = f.spans;
    f.mark.assign(b->model.root_size, 0);
    f.marked = false;
    f.activity = ~0ull;
    f.drifting = false;
    f.settle = kSettlePs;
    f.bot_cycles = (size_t)((const uint8_t*)b->io.bot_cycles - b->model.root);
    return f.on;
}

// Skips so far and the time they covered.
void board_fast_forwarded(Board* b, uint64_t* skips, uint64_t* ps) {
    *skips = b->ff.skips;
    *ps = b->ff.skipped_ps;
}

// The variable that most often kept a mark from its period (Verilator's name), and how
// often; 0 when none did.
uint64_t board_fast_forward_busy(Board* b, const char** name) {
    return most_often(b->ff, b->ff.busy, name);
}

// The counter whose interval most often ended a skip (Verilator's name), and how often; 0
// when none did.
uint64_t board_fast_forward_cut(Board* b, const char** name) {
    return most_often(b->ff, b->ff.cut, name);
}

}  // extern "C"

namespace {

// What the board showed last; kept in locals while a run loops (the model's eval() is opaque
// to the compiler, so fields behind `b` would be reloaded after every evaluation).
struct Shown {
    uint8_t an, seg, dp;
    uint16_t led, vga, lines;
    uint64_t bot;
    bool upd;
    uint64_t samples, evals;
    uint8_t xupd;             // the other bots' upd_sysregs
    uint32_t xsamples[3];     // and their samples
};


// Eight bytes of the root (or its copy, of the same size: a multiple of the cache line).
inline uint64_t load64(const uint8_t* p) {
    uint64_t v;
    std::memcpy(&v, p, 8);
    return v;
}

// A counter's value in the root (or a copy of it), and a new one (Verilator keeps the bits
// above its width zero).
inline uint64_t counter_value(const uint8_t* root, const Counting& k) {
    const uint8_t* p = root + k.c.off;
    uint64_t v = 0;
    // (Verilator's CData, SData, IData and QData: a load each, not a call.)
    switch (k.c.len) {
        case 1: v = *p; break;
        case 2: { uint16_t x; std::memcpy(&x, p, 2); v = x; break; }
        case 4: { uint32_t x; std::memcpy(&x, p, 4); v = x; break; }
        default: std::memcpy(&v, p, 8); break;
    }
    return v & k.mask;
}
inline void set_counter(uint8_t* root, const Counting& k, uint64_t v) {
    v &= k.mask;
    std::memcpy(root + k.c.off, &v, k.c.len);
}
// `x` moved on by `n` drifts, in the counter's direction.
inline uint64_t counter_after(const Counting& k, uint64_t x, uint64_t n) {
    return (k.c.down ? x - n * k.drift : x + n * k.drift) & k.mask;
}

// A compared variable's value in the root image `at`.
inline uint64_t bound_value(const uint8_t* at, const BoardBound& v) {
    uint64_t x = 0;
    std::memcpy(&x, at + v.off, std::min<size_t>(v.len, 8));
    return x;
}

// Whether a guarded read's comparisons all hold with the counter at `x` (the compared
// variables' values as at the mark).
bool guard_holds(const BoardGuarded& r, uint64_t x, const std::vector<uint64_t>& bound_values) {
    for (const BoardGuard& g : r.guards) {
        const uint64_t v = g.bound ? bound_values[g.value] : g.value;
        bool holds = true;
        switch (g.op) {
            case BoardCmp::Lt: holds = x < v; break;
            case BoardCmp::Le: holds = x <= v; break;
            case BoardCmp::Gt: holds = x > v; break;
            case BoardCmp::Ge: holds = x >= v; break;
            case BoardCmp::Eq: holds = x == v; break;
            case BoardCmp::Ne: holds = x != v; break;
        }
        if (!holds) return false;
    }
    return true;
}

// The values around `x` that no read of the design tells apart from it: the same bits at and
// above the lowest shifted read, the same side of every compared constant (and not it), and of
// every compared variable's value in the root image `at` (and not it, nor where the sum with
// the constant added first wraps; the variable must then hold: counter_inside), no wrap. At
// level 1 only the shifted reads above the split count (the bits below it are compared as
// state); at level 2 the whole counter is state.
void counter_interval(Counting& k, uint64_t x, const uint8_t* at) {
    const BoardCounter& c = k.c;
    k.bound_values.clear();
    if (k.level == 2) {
        // (Compared whole, it cannot drift.)
        k.lo = k.steady_lo = 0;
        k.width = k.steady_width = ~0ull;
        return;
    }
    for (const BoardBound& v : c.bounds) k.bound_values.push_back(bound_value(at, v));
    uint32_t shift = k.level == 1 ? c.split_shift : c.shift;
    if (k.level == 0) {
        // A read under a guard counts where the guard holds: the interval ends where it
        // turns (its comparison is among the counter's), so it holds in all of it or none.
        for (const BoardGuarded& g : c.guarded)
            if (shift > g.lo && guard_holds(g, x, k.bound_values)) shift = g.lo;
    }
    // The values below and above `x` in the interval, and in the steady one.
    uint64_t below = x, above = k.mask - x;
    uint64_t steady_below = below, steady_above = above;
    auto apart_from = [&](uint64_t v, uint64_t& below, uint64_t& above) {
        if (v > k.mask) return;  // never reached
        if (v == x) {
            below = above = 0;
        } else if (v > x) {
            above = std::min(above, v - x - 1);
        } else {
            below = std::min(below, x - v - 1);
        }
    };
    auto steady = [&]() {
        steady_below = std::min(steady_below, below);
        steady_above = std::min(steady_above, above);
        bool empty = false;
        for (uint64_t v : c.sets) {
            empty |= v == x;
            apart_from(v, steady_below, steady_above);
        }
        k.steady_lo = x - steady_below;
        k.steady_width = empty ? 0 : steady_below + steady_above + 1;
    };
    if (shift >= c.bits && c.consts.empty() && c.bounds.empty()) {
        // Nothing reads it (above the split): it may even wrap.
        k.lo = 0;
        k.width = ~0ull;
        steady();
        return;
    }
    if (shift < c.bits) {
        const uint64_t low = (1ull << shift) - 1;
        below = std::min(below, x & low);
        above = std::min(above, low - (x & low));
    }
    // A value the design tells apart: the interval stops short of it.
    auto apart = [&](uint64_t v) { apart_from(v, below, above); };
    for (uint64_t v : c.consts) apart(v);
    for (size_t i = 0; i < c.bounds.size(); i++) {
        const uint64_t offset = c.bounds[i].offset & k.mask;
        apart((k.bound_values[i] - offset) & k.mask);
        if (offset) apart((0 - offset) & k.mask);  // where the sum wraps
    }
    k.lo = x - below;
    k.width = below + above == ~0ull ? ~0ull : below + above + 1;
    steady();
}

// How far a counter in its interval may still move in its direction before it leaves it.
inline uint64_t room_left(const Counting& k, const uint8_t* root) {
    const uint64_t at = (counter_value(root, k) - k.lo) & k.mask;
    return k.c.down ? at : k.width - 1 - at;
}

// A counter is still in its interval, and the variables it is compared with hold.
inline bool inside_at(const Counting& k, const uint8_t* root, uint64_t v) {
    for (size_t i = 0; i < k.bound_values.size(); i++)
        if (bound_value(root, k.c.bounds[i]) != k.bound_values[i]) return false;
    return ((v - k.lo) & k.mask) < k.width;
}
inline bool counter_inside(const Counting& k, const uint8_t* root) {
    return k.width == ~0ull || inside_at(k, root, counter_value(root, k));
}
// Every counter is in its interval (and the board's unsteady once one leaves its steady one).
// At every edge: each counter's value read once.
inline bool counters_inside(FastForward& f, const uint8_t* root) {
    bool unsteady = false;
    for (const Counting& k : f.counters) {
        if (k.width == ~0ull && k.steady_width == ~0ull) continue;
        const uint64_t v = counter_value(root, k);
        if (!inside_at(k, root, v)) return false;
        unsteady |= ((v - k.steady_lo) & k.mask) >= k.steady_width;
    }
    f.unsteady |= unsteady;
    return true;
}

// A counter's level (see Counting), and the bits it compares as state.
void set_level(Counting& k, int level) {
    k.level = level;
    k.exact = level == 0 ? 0 : level == 1 ? (1ull << k.c.split) - 1 : k.mask;
}

// A counter tried as state is a counter again, and waits longer before another trial.
void end_trial(Counting& k) {
    set_level(k, 0);
    k.trial = Counting::Trial::None;
    k.tried++;
}

// BOTSIM_FF_TRACE=1 in the environment: the fast-forward's decisions on standard error (marks,
// periods, skips), for botsim's developers. Off the per-edge path.
static const bool kFfTrace = std::getenv("BOTSIM_FF_TRACE") != nullptr;
#define FF_TRACE(...)                                   \
    do {                                                \
        if (kFfTrace) std::fprintf(stderr, __VA_ARGS__); \
    } while (0)

inline void free_bytes_out(const FreeGroup& g, const uint8_t* root, uint8_t* out);
bool free_track(Board* b, uint64_t t);
void free_start(Board* b, FreeGroup& g, uint64_t t);

void free_apply(FastForward& f);
// At a mark: which cores run apart (the host decided); the compared spans without their
// followers when that changed.
void apart_mark(Board* b, uint64_t t) {
    FastForward& f = b->ff;
    bool changed = false;
    for (ApartCore& a : f.apart) {
        void* cpu = *(void* const*)(b->model.root + a.cpu);
        const bool on = cpu && (*(const BoardCpuFns* const*)cpu)->apart(cpu);
        if (on == a.on) continue;
        a.on = on;
        changed = true;
        FF_TRACE("ff %.6f ms: a core %s apart (%zu followers' spans)\n", t / 1e9, on ? "runs" : "no longer runs",
                 a.followers.size());
    }
    if (!changed) return;
    std::fill(f.apart_bytes.begin(), f.apart_bytes.end(), 0);
    for (const ApartCore& a : f.apart)
        for (const Span& x : a.followers)
            if (a.on) std::fill(f.apart_bytes.begin() + x.off, f.apart_bytes.begin() + x.off + x.len, 1);
    free_apply(f);
}

// Mark the state the fast-forward compares with. `drifting`: the counters' drifts found in the
// period that ends here stay, for the next to confirm.
void ff_mark(Board* b, uint64_t t, bool drifting = false) {
    FastForward& f = b->ff;
    std::memcpy(f.mark.data(), b->model.root, f.mark.size());
    f.drifting = drifting;
    f.unsteady = false;
    for (Counting& k : f.counters) {
        counter_interval(k, counter_value(f.mark.data(), k), f.mark.data());
        if (!drifting) k.drift = 0;
    }
    FF_TRACE("ff %.6f ms: mark%s, patience %llu clocks\n", t / 1e9, drifting ? " (drifting)" : "",
             (unsigned long long)(f.patience / 10000));
    f.mark_clocks.resize(b->clocks.size());
    for (size_t i = 0; i < b->clocks.size(); i++) f.mark_clocks[i] = phase_of(b->clocks[i], t);
    f.mark_t = t;
    f.mark_bot_cycles = *b->io.bot_cycles;
    f.marked = true;
    f.proven = false;
    f.shown.clear();
    f.overflow = false;
    f.nphases = 0;
    // Phase snapshots the settling time apart, or a sixteenth of the period last found when
    // that is shorter (a skip across a 2 ms display refresh turn ends within a sixteenth of a
    // VGA line's period of where it may, not a whole period short), enough to span the wait.
    uint64_t every = kSettlePs;
    if (f.last_period) every = std::min(every, std::max(f.last_period / kPhasesPerPeriod, kCounterSettlePs));
    f.phase_every = std::max(every, f.patience / kMaxPhases);
    b->host->ff_mark(b->host->ctx);
    if (!f.apart.empty()) apart_mark(b, t);
}

// While the period is proved: a snapshot of every model, now and then (inline: most edges
// end at its first tests).
__attribute__((noinline)) void ff_snap_take(Board* b, uint64_t t);
inline __attribute__((always_inline)) void ff_snap(Board* b, uint64_t t) {
    FastForward& f = b->ff;
    if (f.proven || f.nphases == kMaxPhases) return;
    const uint64_t last = f.nphases ? f.phases[f.nphases - 1].at : 0;
    if (t - f.mark_t - last < f.phase_every) return;
    ff_snap_take(b, t);
}

void ff_snap_take(Board* b, uint64_t t) {
    FastForward& f = b->ff;
    if (f.phases.size() == f.nphases) f.phases.emplace_back();
    Phase& p = f.phases[f.nphases++];
    p.at = t - f.mark_t;
    const uint8_t* root = b->model.root;
    p.root.assign(root, root + f.mark.size());
    p.clocks.resize(b->clocks.size());
    for (size_t i = 0; i < b->clocks.size(); i++) p.clocks[i] = phase_of(b->clocks[i], t);
    p.shown = f.shown.size();
    p.bot_cycles = *b->io.bot_cycles - f.mark_bot_cycles;
    b->host->ff_snap(b->host->ctx);
}

uint64_t ff_compare(Board* b, uint64_t t, uint64_t until_ps, BoardEvent* buf, uint32_t cap, uint32_t* n, Shown& s);
uint64_t ff_restart(Board* b, uint64_t t);

// A free part's bytes (FreePart) from `root` into `out`, or from `in` into `root`.
inline void free_bytes_out(const FreeGroup& g, const uint8_t* root, uint8_t* out) {
    for (const Span& x : g.part) {
        std::memcpy(out, root + x.off, x.len);
        out += x.len;
    }
}
inline void free_bytes_in(const FreeGroup& g, uint8_t* root, const uint8_t* in) {
    for (const Span& x : g.part) {
        std::memcpy(root + x.off, in, x.len);
        in += x.len;
    }
}

// The runs of bytes of `from` (sorted, disjoint) where `keep[byte]`, merged.
std::vector<Span> spans_where(const std::vector<Span>& from, const std::vector<char>& keep) {
    std::vector<Span> out;
    for (const Span& x : from) {
        for (uint32_t i = x.off; i < x.off + x.len; i++) {
            if (!keep[i]) continue;
            if (!out.empty() && out.back().off + out.back().len == i) out.back().len++;
            else out.push_back({i, 1});
        }
    }
    return out;
}

// A board may have a free part when what it compares is what the run observes, its reads are
// known, and it runs one clock.
bool free_possible(const Board* b) {
    if (!b->ff.observed_only || !b->model.reads_at || b->ff.free.order.empty()) return false;
    for (size_t i = 1; i < b->clocks.size(); i++)
        if (!b->clocks[i].parked) return false;
    return true;
}

// A watch that found none: a longer wait before the next.
void free_none(FreePart& p) {
    p.watching = false;
    p.wait = p.wait ? std::min(2 * p.wait, kFreeMostWait) : 1;
    p.waited = 0;
}

// The compared spans and the counters as the free parts leave them (`taken`): the spans with
// none free less their bytes, each counter counted or kept apart; the hints taken afresh.
void free_apply(FastForward& f) {
    FreePart& p = f.free;
    std::vector<char> rest(p.taken.size());
    for (size_t j = 0; j < rest.size(); j++) rest[j] = !p.taken[j] && !f.apart_bytes[j];
    f.spans = spans_where(f.all_spans, rest);
    std::vector<Counting> all = std::move(f.counters);
    all.insert(all.end(), p.counters.begin(), p.counters.end());
    f.counters.clear();
    p.counters.clear();
    for (Counting& k : all) (p.taken[k.c.off] ? p.counters : f.counters).push_back(std::move(k));
    reset_hints(f);
}

// Give free part `i` up: its bytes compared again, its counters counters again.
void free_drop(FastForward& f, size_t i) {
    FreePart& p = f.free;
    p.groups.erase(p.groups.begin() + (long)i);
    std::fill(p.taken.begin(), p.taken.end(), 0);
    for (const FreeGroup& g : p.groups)
        for (const Span& x : g.part) std::fill(p.taken.begin() + x.off, p.taken.begin() + x.off + x.len, 1);
    free_apply(f);
    free_none(p);
}

// The watch is over: the variables that changed, each joined with the variables that read a
// changing one (its readers change with it, or stay only as long as it lets them); a group
// that touches nothing leaving the model, and holds the variable that kept the last mark from
// its period (`blocker`, an offset), is free.
void free_choose(Board* b, uint64_t t, size_t blocker) {
    FastForward& f = b->ff;
    FreePart& p = f.free;
    const std::vector<BoardMember>& ms = p.order;
    const DesignModel& model = b->model;
    const size_t n = ms.size();
    std::vector<char> varying(n, 0);
    for (size_t i = 0; i < n; i++) {
        if (!ms[i].observed) continue;
        for (size_t j = 0; j < ms[i].len && !varying[i]; j++) varying[i] = p.vary[ms[i].off + j] != 0;
    }
    std::vector<uint32_t> up(n);
    for (size_t i = 0; i < n; i++) up[i] = (uint32_t)i;
    auto find = [&](uint32_t i) {
        while (up[i] != i) i = up[i] = up[up[i]];
        return i;
    };
    for (size_t i = 0; i < n; i++) {
        if (!ms[i].observed) continue;
        for (uint32_t k = model.reads_at[i]; k < model.reads_at[i + 1]; k++) {
            const uint32_t r = model.reads[k];
            if (varying[r]) up[find((uint32_t)i)] = find(r);
        }
    }
    std::vector<char> changes(n, 0), leaves(n, 0);
    for (size_t i = 0; i < n; i++) {
        if (!ms[i].observed) continue;
        const uint32_t c = find((uint32_t)i);
        changes[c] |= varying[i];
        leaves[c] |= model.external[i];
    }
    // The group of the variable that kept the mark from its period, if it is free (another
    // free group, a display's refresh counter with its digit, is left to the counters).
    size_t group = n;
    for (size_t i = 0; i < n; i++)
        if (ms[i].observed && blocker >= ms[i].off && blocker < ms[i].off + ms[i].len) group = find((uint32_t)i);
    std::vector<char> in(n, 0);
    size_t count = 0;
    bool joins = false;  // it holds a free part found before: not one apart from it
    for (size_t i = 0; i < n && group < n; i++) {
        in[i] = ms[i].observed && find((uint32_t)i) == group && changes[group] && !leaves[group];
        count += in[i];
        joins |= in[i] && p.taken[ms[i].off];
    }
    if (!count || joins) {
        FF_TRACE("ff %.6f ms: no free part (what kept the mark changes with %s)\n", t / 1e9,
                 count ? "a free part found before" : "what leaves the model");
        free_none(p);
        return;
    }
    // What crosses between the part and the rest: whatever one side reads of the other.
    std::vector<char> part_byte(b->model.root_size, 0), contact_byte(b->model.root_size, 0);
    size_t bytes = 0;
    for (size_t i = 0; i < n; i++) {
        if (!ms[i].observed) continue;
        if (in[i]) {
            std::memset(&part_byte[ms[i].off], 1, ms[i].len);
            bytes += ms[i].len;
        }
        for (uint32_t k = model.reads_at[i]; k < model.reads_at[i + 1]; k++) {
            const uint32_t r = model.reads[k];
            if (in[i] != in[r]) std::memset(&contact_byte[ms[r].off], 1, ms[r].len);
        }
    }
    const std::vector<Span> all{{0, (uint32_t)b->model.root_size}};
    FreeGroup g;
    g.part = spans_where(all, part_byte);
    g.contact = spans_where(all, contact_byte);
    g.bytes = bytes;
    for (size_t i = 0; i < part_byte.size(); i++) p.taken[i] |= part_byte[i];
    free_apply(f);
    p.watching = false;
    p.groups.push_back(std::move(g));
    free_start(b, p.groups.back(), t);
    if (kFfTrace) {
        std::fprintf(stderr, "ff %.6f ms: a free part of %zu variables (%zu bytes; %zu spans of contact):", t / 1e9, count,
                     bytes, p.groups.back().contact.size());
        for (size_t i = 0, shown = 0; i < n && shown < 6; i++)
            if (in[i]) std::fprintf(stderr, "%s %s", shown++ ? "," : "", ms[i].name);
        std::fprintf(stderr, "%s\n", count > 6 ? ", ..." : "");
    }
}

// Every clock of a mark while a free part is watched for: false when the watch chose (the
// board is marked afresh).
__attribute__((noinline)) bool free_watch(Board* b, uint64_t t) {
    FastForward& f = b->ff;
    FreePart& p = f.free;
    const uint8_t* root = b->model.root;
    const uint8_t* m = f.mark.data();
    for (const Span& x : p.watched)
            for (size_t j = x.off; j < x.off + x.len; j++) p.vary[j] |= root[j] ^ m[j];
    if (t < p.watch_until) return true;
    free_choose(b, t, p.blocker);
    f.marked = false;
    f.quiet_from = t;
    return false;
}

// A free part's cycle taken from `t` on.
void free_start(Board* b, FreeGroup& g, uint64_t t) {
    if (g.cycle.size() < g.bytes) g.cycle.resize(g.bytes);
    free_bytes_out(g, b->model.root, g.cycle.data());
    g.words.clear();
    g.touch_words.clear();
    for (const Span& x : g.contact) {
        for (size_t i = x.off; i < x.off + x.len; i++) {
            const size_t w = i & ~(size_t)7;
            if (g.words.empty() || g.words.back().first != w) g.words.push_back({w, 0});
            g.words.back().second |= 0xFFull << (8 * (i - w));
        }
    }
    for (const auto& [w, mask] : g.words) g.touch_words.push_back(load64(b->model.root + w) & mask);
    g.q = 0;
    g.origin = t;
    g.next_t = t + b->clocks[0].num;
}

// Every clock while free parts are on, marked or not: each one's contact as at its cycle's
// start (else the cycle starts over, and a mark is over: false), its bytes until it is back.
__attribute__((noinline)) bool free_track(Board* b, uint64_t t) {
    FastForward& f = b->ff;
    FreePart& p = f.free;
    const uint8_t* root = b->model.root;
    const uint64_t clock = b->clocks[0].num;
    bool mark_over = false;
    for (size_t i = 0; i < p.groups.size(); i++) {
        FreeGroup& g = p.groups[i];
        // A clock it did not see (the fast-forward was off for a while): its contact is not
        // known to have stayed, the cycle starts over.
        if (t != g.next_t) {
            free_start(b, g, t);
            mark_over = true;
            continue;
        }
        g.next_t = t + clock;
        bool changed = false;
        for (size_t k = 0; k < g.words.size(); k++) {
            if ((load64(root + g.words[k].first) & g.words[k].second) != g.touch_words[k]) {
                FF_TRACE("ff %.6f ms: a free part's contact changed (%s)\n", t / 1e9,
                         member_name(f, g.words[k].first + (size_t)__builtin_ctzll(
                                                               (load64(root + g.words[k].first) & g.words[k].second) ^
                                                               g.touch_words[k]) / 8));
                changed = true;
                break;
            }
        }
        if (changed) {
            mark_over = true;
            if (++g.misses >= kFreeContactMisses) {
                FF_TRACE("ff %.6f ms: its contact changes too often: the free part is given up\n", t / 1e9);
                free_drop(f, i--);
                continue;
            }
            free_start(b, g, t);
            continue;
        }
        if (g.q) continue;
        const uint64_t e = (t - g.origin) / clock;
        if (e >= kMaxFreeCycle) {
            FF_TRACE("ff %.6f ms: a free part is not back within %llu clocks: it is given up\n", t / 1e9,
                     (unsigned long long)e);
            free_drop(f, i--);
            mark_over = true;
            continue;
        }
        if (g.cycle.size() < (e + 1) * g.bytes) g.cycle.resize(2 * (e + 1) * g.bytes);
        uint8_t* at = g.cycle.data() + e * g.bytes;
        free_bytes_out(g, root, at);
        if (std::memcmp(at, g.cycle.data(), g.bytes) == 0) {
            g.q = e;
            FF_TRACE("ff %.6f ms: a free part's cycle is %llu clocks\n", t / 1e9, (unsigned long long)e);
        }
    }
    if (!mark_over) return true;
    const bool marked = f.marked;
    f.marked = false;
    if (marked) f.quiet_from = t;
    return !marked;
}

// Remember that counter `k` turned at `value` at `t`: how long after its last turn there, and
// how many times in a row it was that long (0: the first, or another time apart).
Counting::Turn note_turn(Counting& k, uint64_t value, uint64_t t) {
    size_t i = 0;
    while (i < k.nturns && k.turns[i].value != value) i++;
    Counting::Turn turn{value, t, 0, 0};
    if (i < k.nturns) {
        const Counting::Turn& was = k.turns[i];
        turn.every = t - was.at;
        turn.repeats = was.every == turn.every ? was.repeats + 1 : 0;
    } else if (k.nturns < k.turns.size()) {
        i = k.nturns++;
    } else {
        i = 0;
        for (size_t j = 1; j < k.nturns; j++)
            if (k.turns[j].at < k.turns[i].at) i = j;
    }
    k.turns[i] = turn;
    return turn;
}

// A counter took a value the design can tell apart. Before its mark's period is found the
// second time in a row, it is a short counter: from now on it is state (its low part, or all
// of it), compared with the mark's value, which stays. Otherwise the mark is no more (after
// a skip, or the first time); another once the board has settled, waiting a few periods for
// its own.
__attribute__((noinline)) uint64_t ff_counter_moved(Board* b, uint64_t t) {
    FastForward& f = b->ff;
    const uint8_t* root = b->model.root;
    if (!f.proven) {
        bool again = false, trial = false;
        for (Counting& k : f.counters) {
            again |= !counter_inside(k, root) && ++k.early >= 2;
            trial |= k.trial != Counting::Trial::None;
        }
        if (again && trial) {
            // The longer period of a counter tried as state needs the others in their
            // intervals for a few of its turns: one that leaves its own twice before (a sprite's
            // row counter, read at every line within the sprite) says it cannot pay here. The
            // counter on trial counts again, and the board is marked afresh.
            FF_TRACE("ff %.6f ms: a counter left its interval within a trial: the trial ends\n", t / 1e9);
            for (Counting& k : f.counters) {
                if (k.trial != Counting::Trial::None) end_trial(k);
                k.early = 0;
            }
        } else if (again) {
            for (Counting& k : f.counters) {
                if (!counter_inside(k, root))
                    FF_TRACE("ff %.6f ms: counter at %zu (%s, %llu; its interval %llu + %llu) is state\n", t / 1e9,
                             k.c.off, member_name(f, k.c.off), (unsigned long long)counter_value(root, k),
                             (unsigned long long)k.lo, (unsigned long long)k.width);
                while (!counter_inside(k, root)) {
                    set_level(k, k.level == 0 && k.c.split < k.c.bits ? 1 : 2);
                    counter_interval(k, counter_value(f.mark.data(), k), f.mark.data());
                }
            }
            f.drifting = false;
            return 0;
        }
    }
    FF_TRACE("ff %.6f ms: a counter turned\n", t / 1e9);
    // After a skip: the same counter turning the same time apart, again and again, is tried
    // as state (see Counting).
    uint64_t trial_patience = 0;
    if (f.proven) {
        for (Counting& k : f.counters) {
            if (counter_inside(k, root)) continue;
            const Counting::Turn turn = note_turn(k, counter_value(root, k), t);
            const uint64_t every = turn.every;
            const uint64_t turns = f.last_period ? f.last_period / std::gcd(every, f.last_period) : ~0ull;
            if (k.level < 2 && k.trial == Counting::Trial::None && turn.repeats >= (kTurnsBeforeTrial << k.tried) && every <= kMaxTurnEveryPs &&
                every >= kTurnPeriods * f.last_period && turns <= kMaxTrialTurns) {
                FF_TRACE("ff %.6f ms: counter at %zu (%s) turns every %llu clocks: tried as state\n", t / 1e9, k.c.off,
                         member_name(f, k.c.off),
                         (unsigned long long)(every / 10000));
                set_level(k, 2);
                k.trial = Counting::Trial::Open;
                k.nturns = 0;
                trial_patience = std::max(trial_patience, 2 * turns * every);
            }
        }
    }
    f.marked = false;
    f.drifting = false;
    f.quiet_from = t;
    // After a skip the period is known: the board settles for two of them (a VGA line's
    // counter turns every line), or the settling time if that is shorter.
    f.settle = f.proven ? std::min(kCounterSettlePs, 2 * f.last_period) : kCounterSettlePs;
    f.settle = std::max(f.settle, f.rest);
    // After a skip the period is known: a few of them. Before one is found, no less than
    // the mark had (it may need all of it).
    const uint64_t few = std::max(4 * f.last_period, kShortPatiencePs);
    f.patience = f.proven ? few : std::max(f.patience, few);
    f.patience = std::max(f.patience, trial_patience);
    return 0;
}

// After the rising edge at `t`: mark, or compare with the mark and skip what repeats. The
// records of the skipped time go to `buf` (room permitting) and `s` is what the board shows
// after it; returns the cycles skipped. Inline in the run loop: most edges end at the word
// that differed last.
inline __attribute__((always_inline)) uint64_t ff_step(Board* b, uint64_t t, uint64_t until_ps, BoardEvent* buf,
                                                       uint32_t cap, uint32_t* n, Shown& s) {
    FastForward& f = b->ff;
    if (!f.free.groups.empty() && !free_track(b, t)) return 0;
    if (b->host->activity != f.activity || !f.marked || f.overflow || t - f.mark_t > f.patience)
        return ff_restart(b, t);
    if (f.free.watching && !free_watch(b, t)) return 0;
    uint8_t* root = b->model.root;
    if (!f.counters.empty() && !counters_inside(f, root)) return ff_counter_moved(b, t);
    uint8_t* m = f.mark.data();
    std::memcpy(m + f.bot_cycles, root + f.bot_cycles, 8);  // a counter, not state
    if ((load64(root + f.hint) ^ load64(m + f.hint)) & f.hint_mask) {
        ff_snap(b, t);
        return 0;
    }
    // A word that differed before and differs now becomes the word looked at first (a board
    // whose CPUs loop in a few clocks has words that match the mark often: the one that
    // differs longest is kept first, and is the one a mark's end blames).
    for (size_t i = 0; i < kOldHints; i++) {
        if ((load64(root + f.old_hint[i]) ^ load64(m + f.old_hint[i])) & f.old_mask[i]) {
            std::swap(f.hint, f.old_hint[i]);
            std::swap(f.hint_mask, f.old_mask[i]);
            // (A counter's bits are compared only while it is state: not kept.)
            if (!f.hint_is_span) f.old_mask[i] = 0;
            f.hint_is_span = true;
            ff_snap(b, t);
            return 0;
        }
    }
    return ff_compare(b, t, until_ps, buf, cap, n, s);
}

// The variable of the design to blame for member `i` (an index of the sorted members): itself,
// or for one of Verilator's own (a case table's index, `__Vtableidx2 = cpu_dig0`) the first
// variable inside the design it reads.
long design_member(const Board* b, long i) {
    const FastForward& f = b->ff;
    const char* name = f.members[i].name;
    if (std::strncmp(name, "__V", 3) != 0 || std::strncmp(name, "__Vdly__", 8) == 0 || !b->model.reads_at) return i;
    const std::vector<BoardMember>& order = f.free.order;
    for (size_t k = 0; k < order.size(); k++) {
        if (order[k].off != f.members[i].off) continue;
        for (uint32_t r = b->model.reads_at[k]; r < b->model.reads_at[k + 1]; r++) {
            const BoardMember& read = order[b->model.reads[r]];
            // (Not another of Verilator's, nor a port of the wrapper: a clock the block reads.)
            if (std::strncmp(read.name, "__V", 3) == 0 || !std::strstr(read.name, "__DOT__")) continue;
            const long j = member_at(f, read.off);
            if (j >= 0) return j;
        }
    }
    return i;
}

// Models active, no mark yet, or a mark that waited too long.
__attribute__((noinline)) uint64_t ff_restart(Board* b, uint64_t t) {
    FastForward& f = b->ff;
    BoardHost* h = b->host;
    if (h->activity != f.activity) {
        FF_TRACE("ff %.6f ms: activity\n", t / 1e9);
        f.activity = h->activity;
        f.quiet_from = t;
        f.settle = kSettlePs;
        f.marked = false;
        // The period found last, and a little more; or a first guess.
        f.patience = std::max(kFirstPatiencePs, f.last_period + f.last_period / 4);
        return 0;
    }
    if (!f.marked) {
        if (t - f.quiet_from >= f.settle) ff_mark(b, t);
        return 0;
    }
    if (f.overflow || t - f.mark_t > f.patience) {
        // What still differed from the mark.
        long busy = -1;
        const uint64_t differ =
            (load64(b->model.root + f.hint) ^ load64(f.mark.data() + f.hint)) & f.hint_mask;
        if (differ) {
            const unsigned byte = (unsigned)__builtin_ctzll(differ) / 8;
            busy = member_at(f, f.hint + byte);
            if (busy >= 0) f.busy[design_member(b, busy)]++;
        }
        FF_TRACE("ff %.6f ms: no period (%s; %s differs)\n", t / 1e9, f.overflow ? "too much shown" : "patience",
                 busy >= 0 ? f.members[busy].name : "?");
        // Marked too early (the firmware was still at work) or the period is longer; a counter
        // taken for a short one that is not back where it was may be a long one marked near
        // its turn: it counts again.
        f.patience = std::min(2 * f.patience, kMaxPeriodPs);
        FreePart& p = f.free;
        // (Not while skips are too short to pay: the board is busy, a UART sending.)
        if (busy >= 0 && !p.watching && !f.rest && ++p.waited > p.wait && free_possible(b)) {
            // Perhaps a part of the board runs apart from the rest: watch what changes.
            p.watching = true;
            p.vary.assign(b->model.root_size, 0);
            p.watch_until = t + std::min(f.patience, kFreeWatchPs);
            p.blocker = f.members[busy].off;
            FF_TRACE("ff %.6f ms: watching for a free part\n", t / 1e9);
        }
        const uint8_t* root = b->model.root;
        for (Counting& k : f.counters) {
            if (k.trial != Counting::Trial::None) {
                // No longer period: back to a counter, and a longer wait before another trial.
                end_trial(k);
                continue;
            }
            if ((counter_value(root, k) ^ counter_value(f.mark.data(), k)) & k.exact) {
                set_level(k, 0);
                k.early = 0;
            }
        }
        ff_mark(b, t);
    }
    return 0;
}

// The word that differed last is as marked: compare the rest, and skip if all of it is.
__attribute__((noinline)) uint64_t ff_compare(Board* b, uint64_t t, uint64_t until_ps, BoardEvent* buf, uint32_t cap,
                                              uint32_t* n, Shown& s) {
    FastForward& f = b->ff;
    BoardHost* h = b->host;
    uint8_t* root = b->model.root;
    uint8_t* m = f.mark.data();
    const Span* spans = f.spans.data();
    const size_t nspans = f.spans.size();
    for (size_t i = 0; i < nspans; i++) {
        const Span& x = spans[i];
        if (std::memcmp(root + x.off, m + x.off, x.len) == 0) continue;
        size_t p = x.off;
        while (root[p] == m[p]) p++;
        if (f.hint_mask && f.hint_is_span) {
            f.old_hint[f.next_old] = f.hint;
            f.old_mask[f.next_old] = f.hint_mask;
            f.next_old = (f.next_old + 1) % kOldHints;
        }
        f.hint_is_span = true;
        f.hint = p & ~(size_t)7;
        f.hint_mask = 0;
        for (size_t j = 0; j < 8; j++)
            for (size_t k = 0; k < nspans; k++)
                if (f.hint + j >= spans[k].off && f.hint + j < spans[k].off + spans[k].len) f.hint_mask |= 0xFFull << (8 * j);
        ff_snap(b, t);
        return 0;
    }
    // The counters compared as state: their bits below the split, or all.
    for (const Counting& k : f.counters) {
        const uint64_t differ = (counter_value(root, k) ^ counter_value(m, k)) & k.exact;
        if (!differ) continue;
        f.hint_is_span = false;
        f.hint = k.c.off & ~(size_t)7;
        const size_t at = k.c.off - f.hint;
        f.hint_mask = at + k.c.len <= 8 ? k.exact << (8 * at) : 0;
        ff_snap(b, t);
        return 0;
    }
    // Every clock that runs where it was in its period (the oscillator is: this is its
    // rising edge).
    for (size_t i = 1; i < b->clocks.size(); i++) {
        if (!b->clocks[i].parked && !(phase_of(b->clocks[i], t) == f.mark_clocks[i])) {
            ff_snap(b, t);
            return 0;
        }
    }
    // The models not as marked: not the period yet (the design may repeat a few times per
    // trip of a CPU's loop; marking again here would never reach the trip).
    const int models = h->ff_same(h->ctx);  // 2: as marked but for a count
    if (!models) {
        ff_snap(b, t);
        return 0;
    }
    // The counters: how far each moved in the period. No read could tell any apart (they
    // stayed in their intervals), so every period from the mark's on does the same, each
    // moving them as far, if none was set to a constant in it: none took a value it may be
    // set to (f.unsteady), or the next period moved each as far (a set would have ended both
    // at the same value). Beside a core that counts, always the next (its proof's room is
    // then that of the period after the first: a count found at its last period ends in
    // the second, not in a skip of none that would take it for an inner loop's).
    bool drift = false, same = f.drifting;
    for (Counting& k : f.counters) {
        const uint64_t now = counter_value(root, k), then = counter_value(m, k);
        const uint64_t d = (k.c.down ? then - now : now - then) & k.mask;
        drift |= d != 0;
        same &= d == k.drift;
        k.drift = d;
    }
    if (drift && !same && (f.unsteady || models == 2)) {
        ff_mark(b, t, true);
        return 0;
    }
    // A free part not yet back where it was at its cycle's start: no skip yet. The board
    // is marked again here (as after a period that drifted), so that the period found is
    // always the first from its mark: the records kept are of one period, the one a skip
    // repeats.
    if (std::any_of(f.free.groups.begin(), f.free.groups.end(), [](const FreeGroup& g) { return !g.q; })) {
        ff_mark(b, t, true);
        return 0;
    }
    // The board repeats the period since the mark. Whole periods, then a phase of the next,
    // within the run, with room for their records, up to the bot's next port write, and with
    // every counter in its interval. With no room for one, the mark moves on one period: the
    // next period found is this one again, whose records `shown` holds.
    const uint64_t period = t - f.mark_t;
    f.last_period = period;
    f.proven = true;
    for (Counting& c : f.counters) c.early = 0;
    // The records of the skip: the period's once, one record repeating them, the phase's
    // part; and room for one evaluation's to spare.
    const size_t per = f.shown.size();
    uint64_t k = 0;
    size_t phase = 0;
    if (t < until_ps && cap - *n >= 2 * per + 2 + kMaxPerEval) {
        const uint64_t ahead = until_ps - t;
        // Whole periods the counters allow (a phase of the next needs one more), and the
        // counter that allows the fewest.
        uint64_t counted = ~0ull;
        const Counting* cutter = nullptr;
        for (const Counting& c : f.counters) {
            if (!c.drift || c.width == ~0ull) continue;  // still, or free to wrap
            const uint64_t left = room_left(c, root);
            if (left / c.drift < counted) {
                counted = left / c.drift;
                cutter = &c;
            }
        }
        const uint64_t most = std::min(ahead / period, counted);
        k = most ? h->ff_room(h->ctx, most) : 0;
        if (cutter && counted <= ahead / period && k == counted) {
            const long m = member_at(f, cutter->c.off);
            if (m >= 0) f.cut[m]++;
        }
        // A phase whose counters are still in their intervals there: each moved on by the
        // k periods and by as far as it had moved at the phase in the period proved (it
        // counts one way, so it was in its interval all the way there).
        auto counters_fit = [&](const Phase& p) {
            for (const Counting& c : f.counters) {
                if (!c.drift || c.width == ~0ull) continue;
                const uint64_t left = room_left(c, root);
                const uint64_t was = counter_value(m, c), there = counter_value(p.root.data(), c);
                const uint64_t part = (c.c.down ? was - there : there - was) & c.mask;
                if (part > left - k * c.drift) return false;  // (k * drift <= left: k <= counted)
            }
            return true;
        };
        for (size_t j = f.nphases; j > 0; j--) {
            const Phase& p = f.phases[j - 1];
            if (k * period + p.at <= ahead && counters_fit(p) && h->ff_fits(h->ctx, k, (uint32_t)j)) {
                phase = j;
                break;
            }
        }
    }
    // A counter on trial as state: the longer period it let the board find pays if it skips
    // far; else it is a counter again (from the next mark).
    for (Counting& c : f.counters) {
        if (c.trial != Counting::Trial::Open) continue;
        if (k >= kTrialPays) {
            c.trial = Counting::Trial::Paid;
            c.tried = 0;
        } else {
            FF_TRACE("ff %.6f ms: counter at %zu: its trial skips %llu periods only\n", t / 1e9, c.c.off,
                     (unsigned long long)k);
            end_trial(c);
            f.marked = false;  // (after this skip: the counter's interval is taken again at the next mark)
            f.quiet_from = t;
            f.settle = kCounterSettlePs;
        }
    }
    uint64_t edges = h->ff_skip(h->ctx, k, (uint32_t)phase);
    // Period j after the mark's shows what the mark's did, j periods later: the first of
    // them written out, the others as a repeat of it.
    auto shown = [&](size_t count, uint64_t from) {
        for (size_t i = 0; i < count; i++) {
            buf[*n] = f.shown[i];
            buf[(*n)++].time_ps += from;
        }
    };
    if (k && per) {
        shown(per, f.mark_t + period);
        if (k > 1) record(buf, n, f.mark_t + 2 * period, BOARD_EVENT_REPEAT, (uint32_t)per, period, k - 1);
    }
    if (phase) shown(f.phases[phase - 1].shown, f.mark_t + (k + 1) * period);
    uint64_t skipped = k * period;
    const uint64_t bot_cycles = *b->io.bot_cycles;
    // The counters move on with the board: the mark and the snapshots to the period it is now
    // in, the board to its place in it (a counter compared as state: its value at the phase).
    for (const Counting& c : f.counters) {
        if (c.drift) {
            const uint64_t here = counter_after(c, counter_value(root, c), k);
            set_counter(m, c, counter_after(c, counter_value(m, c), k + 1));
            for (size_t j = 0; j < f.nphases; j++) {
                uint8_t* q = f.phases[j].root.data();
                set_counter(q, c, counter_after(c, counter_value(q, c), k + 1));
            }
            set_counter(root, c, phase ? counter_value(f.phases[phase - 1].root.data(), c) : here);
        } else if (phase) {
            set_counter(root, c, counter_value(f.phases[phase - 1].root.data(), c));
        }
    }
    if (phase) {
        const Phase& p = f.phases[phase - 1];
        for (size_t i = 0; i < nspans; i++) std::memcpy(root + spans[i].off, p.root.data() + spans[i].off, spans[i].len);
        skipped += p.at;
    }
    for (FreeGroup& g : f.free.groups) {
        // Each free part where its cycle is then.
        g.misses = 0;
        if (skipped) {
            const uint64_t e = (t + skipped - g.origin) / b->clocks[0].num;
            free_bytes_in(g, root, g.cycle.data() + (e % g.q) * g.bytes);
            g.next_t = t + skipped + b->clocks[0].num;
        }
    }
    refresh_shims(b);
    f.mark_t += (k + 1) * period;  // the start of the period the board is now in
    if (skipped >= kWorthPs) {
        f.poor = 0;
        f.rest = 0;
    } else if (++f.poor == kPoorSkips) {
        f.poor = 0;
        f.rest = f.rest ? std::min(2 * f.rest, kMaxRestPs) : kFirstRestPs;
        FF_TRACE("ff %.6f ms: skips too short to pay: a rest of %llu clocks before each mark\n", t / 1e9,
                 (unsigned long long)(f.rest / 10000));
    }
    // A core's count that ends in the next period (its room used up): that period is not the
    // mark's again (the count is reloaded, an outer one steps); the board is marked afresh
    // once it is over, and the period looked for within a few, not after the long wait a mark
    // may have grown to.
    if (models == 2 && h->ff_room(h->ctx, 1) == 0) {
        f.patience = std::max(4 * period, kShortPatiencePs);
        f.marked = false;
        f.quiet_from = t + skipped;
        f.settle = period + kCounterSettlePs;
    }
    FF_TRACE("ff %.6f ms: period %llu clocks, %zu shown, skip %llu periods + phase %zu (%.6f ms)\n", t / 1e9,
             (unsigned long long)(period / 10000), per, (unsigned long long)k, phase, skipped / 1e9);
    if (k == 0 && phase == 0) return 0;
    // Every clock that runs where it was at the phase, or now, that much later.
    for (size_t i = 0; i < b->clocks.size(); i++) {
        Clock& c = b->clocks[i];
        if (!c.parked) set_phase(c, phase ? f.phases[phase - 1].clocks[i] : phase_of(c, t), t + skipped);
    }
    // A bot of the team's own RTL (no model counts its edges): as many as the wrapper counted
    // in the periods and the phase proved.
    const uint64_t per_bot = bot_cycles - f.mark_bot_cycles;
    f.mark_bot_cycles = bot_cycles + k * per_bot;
    if (!edges) edges = k * per_bot + (phase ? f.phases[phase - 1].bot_cycles : 0);
    *b->io.bot_cycles = bot_cycles + edges;
    b->now = t + skipped;
    b->ctx.time(b->now);
    s.an = *b->io.an;
    s.seg = *b->io.seg;
    s.dp = *b->io.dp;
    s.led = *b->io.led;
    s.lines = *b->io.lines;
    f.skips++;
    f.skipped_ps += skipped;
    return skipped / b->clocks[0].num;
}

// The run loop. kOneClock: the oscillator is the only clock run (most designs have no other;
// a fast-forwarding run parks those that drive nothing it observes), so the scheduler
// reduces to stepping it.
template <bool kOneClock>
uint32_t run_loop(Board* b, uint64_t until_ps, uint64_t stop_after_samples, BoardEvent* buf, uint32_t cap,
                  uint32_t* n) {
    const DesignModel& model = b->model;
    const BoardPorts io = b->io;  // in locals: the evaluation is opaque to the compiler
    const size_t nc = b->clocks.size();
    Clock* clocks = b->clocks.data();
    const bool vga = b->vga, watch_bot = b->bot;
    // The fast-forward, without a waveform (the oscillator's period is a whole number of
    // picoseconds), after the oscillator's rising edges.
    const bool ff = b->ff.on && !b->vcd && clocks[0].den == 1 && !(vga && b->ff.observed_only);
    const bool rising_only = b->rising_only && !b->vcd;
    Shown s{b->last_an, b->last_seg, b->last_dp, b->last_led, b->last_vga, b->last_lines, b->last_bot, b->last_upd,
            b->samples, b->evals, b->last_xupd, {b->xsamples[0], b->xsamples[1], b->xsamples[2]}};
    uint32_t why = BOARD_BUFFER_FULL;
    // Room for one evaluation's records must remain.
    while (*n + kMaxPerEval <= cap) {
        uint64_t t;
        if (kOneClock) {
            t = clocks[0].next_t;
        } else {
            t = UINT64_MAX;
            for (size_t i = 0; i < nc; i++)
                if (!clocks[i].stopped && !clocks[i].parked && clocks[i].next_t < t) t = clocks[i].next_t;
#ifdef BOTSIM_TIMING
            // A design with delays: the next of its timed events (in picoseconds, the
            // build's time precision) is a moment to evaluate too.
            if (model.events_pending(model.top) && model.next_time_slot(model.top) < t)
                t = model.next_time_slot(model.top);
#endif
        }
        if (t > until_ps) {
            b->now = until_ps;
            why = BOARD_UNTIL;
            break;
        }
        b->ctx.time(t);
        const uint32_t n0 = *n;
        bool rose = false, osc_rose = false;
        if (kOneClock) {
            rose = osc_rose = clocks[0].next_high;
            *clocks[0].q = clocks[0].next_high;
            clocks[0].advance();
        } else {
            for (size_t i = 0; i < nc; i++) {
                Clock& c = clocks[i];
                if (c.stopped || c.parked || c.next_t != t) continue;
                rose |= c.next_high;
                osc_rose |= i == 0 && c.next_high;
                *c.q = c.next_high;
                c.advance();
            }
        }
        b->now = t;
        // Clocks that only fall change nothing but their levels on a board whose logic all
        // runs on rising edges: Verilator notes the levels, and nothing is evaluated.
        const bool evaluate = rose || !rising_only;
        if (!evaluate) {
            model.eval_triggers(model.root);
        } else if (b->vcd) {
            model.eval(model.top);
            b->vcd->dump(t);
        } else {
            model.eval_step(model.root);
        }
        s.evals += evaluate;
        if (b->ctx.gotFinish()) {  // $finish, or vl_fatal
            why = BOARD_FINISHED;
            break;
        }
        if (!kOneClock) {
            // Clocks that start or stop with this evaluation.
            for (size_t i = 1; i < nc; i++) {
                Clock& c = clocks[i];
                if (c.parked) continue;
                bool runs = *c.run != 0;
                if (c.stopped && runs) {
                    c.stopped = false;
                    c.schedule_from(t + 1);
                } else if (!c.stopped && !runs && *c.q == 0) {
                    c.stopped = true;
                }
            }
        }
        if (!evaluate) continue;
        uint8_t an = *io.an, seg = *io.seg, dp = *io.dp;
        if (an != s.an || seg != s.seg || dp != s.dp) {
            s.an = an;
            s.seg = seg;
            s.dp = dp;
            record(buf, n, t, BOARD_EVENT_DISPLAY, an | (uint32_t)seg << 8 | (uint32_t)dp << 15, 0, 0);
        }
        if (vga) {
            uint16_t v = (uint16_t)(*io.vga_r << 8 | *io.vga_g << 4 | *io.vga_b | *io.hsync << 12 | *io.vsync << 13);
            if (v != s.vga) {
                s.vga = v;
                record(buf, n, t, BOARD_EVENT_VGA, v, 0, 0);
            }
        }
        if (*io.led != s.led) {
            s.led = *io.led;
            record(buf, n, t, BOARD_EVENT_LEDS, s.led, 0, 0);
        }
        if (*io.lines != s.lines) {
            s.lines = *io.lines;
            record(buf, n, t, BOARD_EVENT_LINES, s.lines, 0, 0);
        }
        if (watch_bot) {
            uint64_t v = (uint64_t)*io.bot_locx | (uint64_t)*io.bot_locy << 8 | (uint64_t)*io.bot_info << 16 |
                         (uint64_t)*io.bot_sensors << 24 | (uint64_t)*io.bot_lmdist << 32 |
                         (uint64_t)*io.bot_rmdist << 40 | (uint64_t)*io.bot_upd << 48;
            if (v != s.bot) {
                s.bot = v;
                record(buf, n, t, BOARD_EVENT_BOT, (uint32_t)(v >> 48), v & 0xFFFFFFFFFFFFull, 0);
            }
        }
        // The other bots' samples (before the first's, which may end the run).
        const uint8_t xupd = *io.xbot_upd;
        if (xupd != s.xupd) {
            for (uint32_t k = 0; k < 3; k++) {
                if ((xupd >> k & 1) && !(s.xupd >> k & 1)) {
                    record(buf, n, t, BOARD_EVENT_OTHER_SAMPLE, s.xsamples[k]++ | (k + 1) << 28, *io.xbot_regs[k],
                           *io.bot_cycles);
                }
            }
            s.xupd = xupd;
        }
        bool upd = *io.bot_upd;
        if (upd != s.upd) {
            s.upd = upd;
            if (upd) {
                uint64_t regs = (uint64_t)*io.bot_locx | (uint64_t)*io.bot_locy << 8 |
                                (uint64_t)*io.bot_info << 16 | (uint64_t)*io.bot_sensors << 24 |
                                (uint64_t)*io.bot_lmdist << 32 | (uint64_t)*io.bot_rmdist << 40 |
                                (uint64_t)*io.bot_motctl << 48;
                record(buf, n, t, BOARD_EVENT_SAMPLE, (uint32_t)s.samples, regs, *io.bot_cycles);
                if (++s.samples >= stop_after_samples) {
                    why = BOARD_SAMPLES;
                    break;
                }
            }
        }
        if (ff) {
            FastForward& f = b->ff;
            if (*n != n0 && f.marked && !f.proven) {
                if (f.shown.size() + (*n - n0) > kMaxShown) {
                    f.overflow = true;
                } else {
                    for (uint32_t i = n0; i < *n; i++) {
                        f.shown.push_back(buf[i]);
                        f.shown.back().time_ps -= f.mark_t;
                    }
                }
            }
            if (osc_rose) s.evals += (rising_only ? 1 : 2) * ff_step(b, t, until_ps, buf, cap, n, s);
        }
    }
    b->last_an = s.an;
    b->last_seg = s.seg;
    b->last_dp = s.dp;
    b->last_led = s.led;
    b->last_lines = s.lines;
    b->last_vga = s.vga;
    b->last_bot = s.bot;
    b->last_upd = s.upd;
    b->samples = s.samples;
    b->evals = s.evals;
    b->last_xupd = s.xupd;
    for (int k = 0; k < 3; k++) b->xsamples[k] = s.xsamples[k];
    return why;
}

}  // namespace

extern "C" {

uint32_t board_run(Board* b, uint64_t until_ps, uint64_t stop_after_samples, BoardEvent* buf, uint32_t cap,
                   uint32_t* n) {
    enter(b);
    *n = 0;
    // Parked clocks are not run: the oscillator alone is then the one-clock loop's.
    bool one = true;
    for (size_t i = 1; i < b->clocks.size(); i++) one &= b->clocks[i].parked;
#ifdef BOTSIM_TIMING
    one = false;  // the design's own timed events are moments too (run_loop)
#endif
    if (b->ctx.gotFinish()) return BOARD_FINISHED;
    try {
        return one ? run_loop<true>(b, until_ps, stop_after_samples, buf, cap, n)
                   : run_loop<false>(b, until_ps, stop_after_samples, buf, cap, n);
    } catch (const Stopped&) {
        // The records written before the stop stand (*n counts them).
        return BOARD_FINISHED;
    }
}

const char* board_fatal(Board* b) { return b->fatal.c_str(); }

// The minimal harness the board harness is measured against (botsim board --bench): the
// oscillator alone, two evaluations per cycle, nothing checked or recorded. Use it on a board
// of its own: it moves the model's time without the scheduler.
void board_bench_minimal(Board* b, uint64_t cycles) {
    enter(b);
    const DesignModel& model = b->model;
    try {
        for (uint64_t i = 0; i < cycles && !b->ctx.gotFinish(); i++) {
            b->ctx.timeInc(5000);
            *model.io.clk = 1;
            model.eval(model.top);
            b->ctx.timeInc(5000);
            *model.io.clk = 0;
            model.eval(model.top);
        }
    } catch (const Stopped&) {
    }
}

}  // extern "C"

// --cpu iss (rtl/board/kcpsm6_iss.v): each KCPSM6 instance gets its model from the host when
// the design starts; every rising edge of its clock goes straight to the model's own tick.
namespace {
uint64_t no_tick(void*, uint64_t) { return 0; }
uint64_t no_state(void*) { return 0; }
void no_debug(void*, uint32_t* regs, uint32_t* flags) {
    for (int i = 0; i < 4; i++) regs[i] = 0;
    *flags = 0;
}
void no_out_port_free(void*) {}
void no_apart_capable(void*, const char*) {}
int no_apart(void*) { return 0; }
const BoardCpuFns no_fns = {no_tick, no_state, no_debug, no_out_port_free, no_apart_capable, no_apart};
const BoardCpuFns* const no_cpu = &no_fns;  // what an instance gets when there is no model
}  // namespace

extern "C" void* botsim_iss_new(const char* path, int hwbuild, int vector, int scratch_pad) {
    Board* b = current;
    void* cpu = b && b->host ? b->host->cpu_new(b->host->ctx, path, hwbuild, vector, scratch_pad, &b->now) : nullptr;
    if (cpu) return cpu;
    Verilated::threadContextp()->gotFinish(true);
    if (b && b->fatal.empty()) b->fatal = std::string("no instruction-set model for the KCPSM6 ") + path;
    return (void*)&no_cpu;
}

// --bot model (rtl/board/bot_model.v): the bot is the host's model, one call per rising edge.
namespace {
uint64_t no_edge(void*, uint32_t) { return 0; }
const BoardBotFns no_bot_fns = {no_edge};
const BoardBotFns* const no_bot = &no_bot_fns;
}  // namespace

extern "C" void* botsim_bot_new(const char* path) {
    Board* b = current;
    void* bot = b && b->host && b->host->bot_new ? b->host->bot_new(b->host->ctx, path) : nullptr;
    if (bot) return bot;
    Verilated::threadContextp()->gotFinish(true);
    if (b && b->fatal.empty()) b->fatal = std::string("no model for the bot ") + path;
    return (void*)&no_bot;
}

extern "C" long long botsim_bot_edge(void* bot, int pins) {
    return (long long)(*(const BoardBotFns* const*)bot)->edge(bot, (uint32_t)pins);
}

extern "C" long long botsim_iss_state(void* cpu) {
    return (long long)(*(const BoardCpuFns* const*)cpu)->state(cpu);
}

// Bit 63 of the state: the model hit a breakpoint; the run stops after this evaluation.
extern "C" long long botsim_iss_tick(void* cpu, long long pins) {
    uint64_t state = (*(const BoardCpuFns* const*)cpu)->tick(cpu, (uint64_t)pins);
    if (state >> 63) Verilated::threadContextp()->gotFinish(true);
    return (long long)(state & ~(1ull << 63));
}

// Debug builds (--vcd): the text of an instruction word, packed for `output bit [159:0]`
// with the first character in the top byte, as Verilog holds a string.
extern "C" void botsim_disasm(int word, svBitVecVal* text) {
    Board* b = current;
    botsim_disasm_pack(word, text, [b](uint32_t w, char* s) {
        if (!b || !b->host || !b->host->disasm) return false;
        b->host->disasm(w, s);
        return true;
    });
}

extern "C" void botsim_iss_debug(void* cpu, svBitVecVal* regs, int* flags) {
    uint32_t f = 0;
    (*(const BoardCpuFns* const*)cpu)->debug(cpu, regs, &f);
    *flags = (int)f;
}

// The lock-step build (rtl/board/kcpsm6_probe.v): every cycle's ports of each RTL KCPSM6.
namespace {
void no_record(void*, uint64_t, uint64_t, uint64_t) {}
const BoardProbeFns no_probe_fns = {no_record};
const BoardProbeFns* const no_probe = &no_probe_fns;
}  // namespace

extern "C" void* botsim_probe_new(const char* path) {
    Board* b = current;
    void* p = b && b->host ? b->host->probe_new(b->host->ctx, path) : nullptr;
    if (p) return p;
    Verilated::threadContextp()->gotFinish(true);
    if (b && b->fatal.empty()) b->fatal = std::string("no probe for the KCPSM6 ") + path;
    return (void*)&no_probe;
}

extern "C" void botsim_probe(void* probe, long long pins, long long state) {
    (*(const BoardProbeFns* const*)probe)->record(probe, (uint64_t)pins, (uint64_t)state, current->now);
}

// How the design's run ends, and what it prints. The runtime is built with VL_USER_FINISH,
// VL_USER_FATAL, VL_USER_STOP and VL_USER_WARN, and with VL_PRINTF/VL_VPRINTF as the
// functions below (botsim_print.h).
//
// $finish ends the run at the end of its evaluation. A fatal runtime error ($fatal, a model
// that does not settle: Verilator's "did not converge"), $stop and a $readmem file that cannot
// be read stop it at once: the harness unwinds out of the evaluation to its entry point
// (returning would let Verilator's convergence loop go round forever), keeping the message for
// the board that raised it.
void vl_finish(const char* filename, int linenum, const char* hier) VL_MT_UNSAFE {
    (void)hier;
    Verilated::threadContextp()->gotFinish(true);
    if (current && current->finish.empty())
        current->finish = std::string(filename ? filename : "") + ":" + std::to_string(linenum);
}

namespace {
[[noreturn]] void stop(const char* filename, int linenum, const std::string& msg) {
    Verilated::threadContextp()->gotFinish(true);
    if (current && current->fatal.empty()) {
        current->fatal = filename && filename[0] ? std::string(filename) + ":" + std::to_string(linenum) + ": " + msg : msg;
    }
    throw Stopped{};
}
}  // namespace

void vl_fatal(const char* filename, int linenum, const char* hier, const char* msg) VL_MT_UNSAFE {
    (void)hier;
    stop(filename, linenum, msg ? msg : "fatal error");
}

void vl_stop(const char* filename, int linenum, const char* hier) VL_MT_UNSAFE {
    (void)hier;
    // $error and $fatal print their message (as an %Error line) and then stop.
    std::string said = current ? current->error_said : std::string();
    if (said.empty()) stop(filename, linenum, "the design called $stop");
    stop(filename, linenum, "the design reported an error: " + said + " (botsim stops at a design's first $error or $fatal, as Verilator does)");
}

void vl_warn(const char* filename, int linenum, const char* hier, const char* msg) VL_MT_UNSAFE {
    (void)hier;
    std::string m = msg ? msg : "";
    if (m.find("$readmem") != std::string::npos) stop(filename, linenum, m);
    botsim_printf("%%Warning: %s:%d: %s\n", filename ? filename : "", linenum, m.c_str());
}

// The design's printing ($display, $write, runtime warnings): to a log file when one is set
// (board_output), and to standard error up to a number of lines, then one line saying how
// much more there is. The caller learns how many lines there were and whether the last one
// is unfinished, so that its own summary starts on a line of its own.
namespace {
struct DesignOutput {
    FILE* log = nullptr;
    uint64_t limit = 200;
    uint64_t lines = 0;
    bool mid_line = false;  // what stderr shows ends without a newline
    bool cut = false;
};
DesignOutput g_out;

void design_output(const char* text, size_t len) {
    if (g_out.log) fwrite(text, 1, len, g_out.log);
    // The message of a $error or $fatal ("[time] %Error: file:line: Assertion failed in
    // scope: message"), for the line that says why the run stopped.
    if (current) {
        std::string t(text, len);
        size_t e = t.find("%Error: ");
        if (e != std::string::npos) {
            size_t m = t.find("Assertion failed in ", e);
            m = m == std::string::npos ? e + 8 : t.find(": ", m);
            std::string said = m == std::string::npos ? std::string() : t.substr(m + (t[m] == ':' ? 2 : 0));
            while (!said.empty() && (said.back() == '\n' || said.back() == '\r')) said.pop_back();
            current->error_said = said.empty() ? "(no message)" : said;
        }
    }
    for (size_t i = 0; i < len;) {
        const char* nl = (const char*)memchr(text + i, '\n', len - i);
        size_t end = nl ? (size_t)(nl - text) + 1 : len;
        if (g_out.lines < g_out.limit) {
            fwrite(text + i, 1, end - i, stderr);
            g_out.mid_line = !nl;
        } else if (!g_out.cut) {
            g_out.cut = true;
            fputs(g_out.mid_line ? "\n" : "", stderr);
            fprintf(stderr, "botsim board: the design prints more than %llu lines; the rest is not shown (--design-log FILE keeps it all)\n",
                    (unsigned long long)g_out.limit);
            g_out.mid_line = false;
        }
        if (nl) g_out.lines++;
        i = end;
    }
}
}  // namespace

extern "C" int botsim_vprintf(const char* format, va_list ap) {
    char small[512];
    va_list again;
    va_copy(again, ap);
    int n = vsnprintf(small, sizeof small, format, ap);
    if (n < 0) {
        va_end(again);
        return n;
    }
    if ((size_t)n < sizeof small) {
        design_output(small, (size_t)n);
    } else {
        std::string big((size_t)n + 1, '\0');
        vsnprintf(&big[0], big.size(), format, again);
        design_output(big.data(), (size_t)n);
    }
    va_end(again);
    return n;
}

extern "C" int botsim_printf(const char* format, ...) {
    va_list ap;
    va_start(ap, format);
    int n = botsim_vprintf(format, ap);
    va_end(ap);
    return n;
}

extern "C" {

// Where the design's printing goes: `log` (a file, or null) and at most `limit` lines on
// standard error. Returns 0 when the log cannot be opened.
int board_output(const char* log, uint64_t limit) {
    g_out.limit = limit;
    if (log) {
        g_out.log = fopen(log, "wb");
        if (!g_out.log) return 0;
    }
    return 1;
}

// How many lines the design printed, and whether standard error ends in the middle of one;
// closes the log.
uint64_t board_output_done(int* mid_line) {
    fflush(stderr);
    if (g_out.log) {
        fclose(g_out.log);
        g_out.log = nullptr;
    }
    *mid_line = g_out.mid_line;
    return g_out.lines;
}

const char* board_finish(Board* b) { return b->finish.c_str(); }

}  // extern "C"
