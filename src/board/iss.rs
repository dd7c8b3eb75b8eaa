//! `botsim board --cpu iss`: every KCPSM6 of a board design on the instruction-set
//! simulator. The design is built with rtl/board/kcpsm6_iss.v in place of the RTL core; each
//! of its instances asks the host for a model at power-up (`botsim_iss_new`, by its
//! hierarchical name) and calls it once per rising edge of its clock (`botsim_iss_tick`).
//! The host is the [`Host`] here, handed to the harness through `board_abi.h`'s `BoardHost`.
//!
//! The per-edge call is the only traffic: the inputs before the edge packed into one word,
//! the outputs of the next cycle packed into another (the layouts are kcpsm6_iss.v's), no
//! allocation, no lookup; the model pointer carries its own function table, so the harness
//! reaches it without thread-local state.

use std::ffi::{c_char, c_int, c_void, CStr};

use std::collections::BTreeMap;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use kcpsm6::iss::{Bus, Config, Cpu, Phase, Pins, PortKind, ScratchPad};
use kcpsm6::source::SourceMap;
use kcpsm6::trace::Tracer;
use kcpsm6::Image;

use super::replay::{DebugWords, Replay};
use crate::fastforward::apart::Ports;
use crate::fastforward::counts::{Same, Watch};
use crate::fastforward::solo::Solo;

use botsim_core::sim::iss::{IssBot, LazyBot};
use botsim_core::World;

/// The functions a model pointer starts with (`BoardCpuFns` in board_abi.h).
#[repr(C)]
struct CpuFns {
    tick: unsafe extern "C" fn(*mut IssCpu, u64) -> u64,
    state: unsafe extern "C" fn(*mut IssCpu) -> u64,
    debug: unsafe extern "C" fn(*mut IssCpu, *mut u32, *mut u32),
    out_port_free: unsafe extern "C" fn(*mut IssCpu),
    apart_capable: unsafe extern "C" fn(*mut IssCpu, *const c_char),
    apart: unsafe extern "C" fn(*mut IssCpu) -> c_int,
}

static FNS: CpuFns = CpuFns {
    tick: tick_ffi,
    state: state_ffi,
    debug: debug_ffi,
    out_port_free: out_port_free_ffi,
    apart_capable: apart_capable_ffi,
    apart: apart_ffi,
};

unsafe extern "C" fn apart_capable_ffi(cpu: *mut IssCpu, entry: *const c_char) {
    // SAFETY: the model pointer is one `Host::create` made; the entry is null or a string of
    // botsim_observed.h.
    let (cpu, entry) = unsafe { (&mut *cpu, (!entry.is_null()).then(|| CStr::from_ptr(entry).to_string_lossy())) };
    cpu.apart.capable = entry.is_some_and(|e| cpu.inputs_written(&e));
    cpu.apart.on &= cpu.apart.capable;
}

unsafe extern "C" fn apart_ffi(cpu: *mut IssCpu) -> c_int {
    // SAFETY: as for apart_capable_ffi.
    unsafe { (*cpu).apart.on as c_int }
}

/// A core that may run apart from the board (crate::fastforward::apart: the design reads what it shows
/// between port accesses only under a strobe or into its followers). While it only computes
/// with its reset, sleep and interrupt low, the fast-forward leaves it out of the period it
/// looks for and runs it on its own over a skip, up to just before its next port access,
/// found by running ahead on a copy ([`Solo`]: its delays skipped).
#[derive(Default)]
struct Apart {
    capable: bool,
    /// Apart since the last mark.
    on: bool,
    /// The core's cycles before `until` touch no port with its pins low (`known`: found since
    /// they were last raised).
    known: bool,
    until: u64,
    /// The run-ahead found the access at `until` (not only looked that far).
    found: bool,
    /// The instruction word at the pins is not checked before this cycle: the ROM's output,
    /// a follower, is stale for a cycle after a skip.
    unchecked_until: u64,
    solo: Solo,
    /// The reset, sleep and interrupt pins of the last cycle.
    control: u64,
}

impl Apart {
    /// Run a copy of `cpu` ahead with its pins low to its next port access (or as far as
    /// [`Apart::AHEAD`]): `until`.
    fn look_ahead(&mut self, cpu: &Cpu) {
        let mut ahead = cpu.clone();
        let at = self.solo.run(&mut ahead, cpu.cycle() + Apart::AHEAD, &mut kcpsm6::iss::NullBus::default());
        // The access's strobe cycle; its instruction began a cycle before.
        self.until = at.map_or(ahead.cycle(), |c| c.saturating_sub(1 + Apart::MARGIN));
        self.found = at.is_some();
        self.known = true;
    }

    /// The pins the core runs apart with held low: reset, sleep, interrupt (kcpsm6_iss.v's
    /// bits 28, 27, 26).
    const CONTROL: u64 = 7 << 26;
    /// A core that comes back to its state within this many cycles repeats with the board:
    /// it is compared, not run apart (a poll of the scratch pad).
    const LOOP: u64 = 64;
    /// How far a run-ahead looks (its loops skipped: a second of the board costs it little), the least
    /// run apart worth it, and the cycles a skip ends before the next port access (its
    /// `port_id` shown a cycle before the strobe, the followers a cycle behind).
    const AHEAD: u64 = 1 << 30;
    const LEAST: u64 = 1 << 12;
    const MARGIN: u64 = 8;
}

/// A bus that notes the first port access.
#[derive(Default)]
struct Access {
    at: Option<u64>,
}

impl Bus for Access {
    fn input(&mut self, _port: u8, cycle: u64) -> u8 {
        self.at.get_or_insert(cycle);
        0
    }
    fn output(&mut self, _port: u8, _value: u8, cycle: u64) {
        self.at.get_or_insert(cycle);
    }
    fn output_k(&mut self, _port: u8, _value: u8, cycle: u64) {
        self.at.get_or_insert(cycle);
    }
}

unsafe extern "C" fn out_port_free_ffi(cpu: *mut IssCpu) {
    // SAFETY: the model pointer is one `Host::create` made.
    unsafe { (*cpu).watch.out_port_free = true };
}

unsafe extern "C" fn debug_ffi(cpu: *mut IssCpu, regs: *mut u32, flags: *mut u32) {
    // SAFETY: the model pointer is one `Host::create` made; regs holds four words, flags one.
    let (cpu, regs, flags) = unsafe { (&mut *cpu, std::slice::from_raw_parts_mut(regs, 4), &mut *flags) };
    let words = cpu.debug_now();
    regs.copy_from_slice(&words[..4]);
    *flags = words[4];
}

/// What a debug build shows of a core (board_abi.h's `debug`): the active bank's s0..sF in
/// four words (s0 in the low byte of the first), then the flags.
fn debug_words(c: &Cpu) -> DebugWords {
    let mut words = [0; 5];
    for (w, word) in words[..4].iter_mut().enumerate() {
        *word = (0..4).map(|b| (c.reg(c.bank(), (4 * w + b) as u8) as u32) << (8 * b)).sum();
    }
    words[4] = c.bank() as u32
        | (c.zero() as u32) << 1
        | (c.carry() as u32) << 2
        | (c.interrupt_enabled() as u32) << 3
        | ((c.in_reset() || !c.running()) as u32) << 4
        | ((c.phase() == Phase::Idle) as u32) << 5
        | (c.interrupt_entry() as u32) << 6;
    words
}

/// The bus of a pin-level core: `in_port` as the design drives it.
#[derive(Default)]
struct Pinned {
    in_port: u8,
}

impl Bus for Pinned {
    fn input(&mut self, _port: u8, _cycle: u64) -> u8 {
        self.in_port
    }
    fn output(&mut self, _port: u8, _value: u8, _cycle: u64) {}
    fn output_k(&mut self, _port: u8, _value: u8, _cycle: u64) {}
}

/// The reset, sleep and interrupt pins of kcpsm6_iss.v's packed inputs.
#[inline(always)]
fn unpack(pins: u64) -> Pins {
    Pins { interrupt: pins >> 26 & 1 == 1, sleep: pins >> 27 & 1 == 1, reset: pins >> 28 & 1 == 1 }
}

/// A decoded word that was not the one on the `instruction` port.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RomMismatch {
    pub cycle: u64,
    pub address: u16,
    /// The program's word, and the word the design's ROM gave.
    pub expected: u32,
    pub found: u32,
}

/// One KCPSM6 instance's model.
#[repr(C)]
pub struct IssCpu {
    fns: &'static CpuFns,
    cpu: Cpu,
    bus: Pinned,
    mismatch: Option<RomMismatch>,
    /// Every cycle's (pins, outputs), in a lock-step run.
    record: Option<Vec<(u64, u64)>>,
    /// The source-level trace and profile (`--cpu-trace`).
    trace: Option<Box<CpuTrace>>,
    /// Breakpoints, and the first one hit.
    breaks: Option<Box<(Breaks, *const u64)>>,
    hit: Option<Hit>,
    path: String,
    /// The host's activity count (interrupts bump it), and the state at the fast-forward's
    /// mark.
    activity: *mut u64,
    mark: Option<Box<Cpu>>,
    /// The state at each of the fast-forward's phase snapshots since the mark.
    phases: Vec<Cpu>,
    /// A debug build (its waveform shows the registers): the replay keeps them too.
    debug: bool,
    /// Loops played back instead of simulated (not while the core is traced, has
    /// breakpoints or is recorded): bring the core up to date ([`IssCpu::core`]) before
    /// reading or changing it.
    replay: Replay,
    /// The outputs of the current cycle (the last tick's), and what the fast-forward of
    /// firmware that counts records since its mark.
    out: u64,
    watch: Watch,
    apart: Apart,
}

pub use botsim_core::debug::Breaks;

/// A breakpoint that stopped the run: which CPU, what, and when.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Hit {
    pub cpu: String,
    /// The breakpoint as given.
    pub what: String,
    pub pc: u16,
    /// The D cycle of the instruction (the CPU's own cycles), and the time its last cycle ended.
    pub cycle: u64,
    pub time_ps: u64,
}

/// The state bit that tells the harness a breakpoint was hit (kcpsm6_iss.v uses 32:0).
const BREAK_BIT: u64 = 1 << 63;

/// One CPU's `--cpu-trace` files, written under temporary names until [`Host::finish`].
struct CpuTrace {
    tracer: Tracer,
    out: BufWriter<std::fs::File>,
    tmp: PathBuf,
    file: PathBuf,
    profile: PathBuf,
    /// The board's time (the harness's), and the window of times traced.
    now: *const u64,
    window: (u64, u64),
    error: Option<std::io::Error>,
}

impl CpuTrace {
    fn retired(&mut self, r: &kcpsm6::iss::Retired, end: u64) {
        // SAFETY: `now` points into the board, which outlives its CPUs' models.
        let t = unsafe { *self.now };
        let write = (self.window.0..self.window.1).contains(&t);
        let result = if write {
            self.tracer.retired(r, end, Some(t), &mut self.out)
        } else {
            self.tracer.retired(r, end, Some(t), &mut std::io::sink())
        };
        if let Err(e) = result {
            self.error.get_or_insert(e);
        }
    }
}

impl IssCpu {
    fn new(config: Config, program: &Image, record: bool) -> IssCpu {
        let cpu = Cpu::new(config, &program.words[..]);
        IssCpu {
            fns: &FNS,
            replay: Replay::new(&cpu),
            debug: false,
            cpu,
            bus: Pinned::default(),
            mismatch: None,
            record: record.then(Vec::new),
            trace: None,
            breaks: None,
            hit: None,
            path: String::new(),
            activity: std::ptr::null_mut(),
            mark: None,
            phases: Vec::new(),
            out: 0,
            watch: Watch::new(),
            apart: Apart::default(),
        }
    }

    /// Every INPUT of the program reads a port at which the followers of the entry `entry`
    /// (crate::fastforward::apart's, as botsim_observed.h lists it) written for some ports only are
    /// written: a constant port, one of theirs.
    fn inputs_written(&self, entry: &str) -> bool {
        let ports: Option<Vec<Ports>> =
            entry.split(' ').filter_map(|w| w.strip_prefix('@')).map(Ports::parse).collect();
        let Some(ports) = ports else { return false };
        ports.is_empty()
            || self.cpu.rom().iter().all(|&w| {
                kcpsm6::isa::Opcode::of(w) != kcpsm6::isa::Opcode::Input
                    || (w & 1 << 12 != 0 && ports.iter().all(|p| p.has(w as u8)))
            })
    }

    /// At a mark: whether the core runs apart until the next (see [`Apart`]).
    fn decide_apart(&mut self) {
        if !self.apart.capable || !self.watch.enabled {
            self.apart.on = false;
            return;
        }
        let cpu = self.core().clone();
        let now = cpu.cycle();
        let a = &mut self.apart;
        a.on = false;
        if a.control != 0 || cpu.in_reset() || !cpu.running() {
            a.known = false;
            return;
        }
        if !a.known || a.until < now + Apart::LEAST {
            // A loop that comes back to the same flops: compared with the board.
            let mut probe = cpu.clone();
            let mut bus = Access::default();
            for _ in 0..Apart::LOOP {
                probe.tick(Pins::default(), &mut bus);
                if bus.at.is_some() {
                    break;
                }
                if probe.pc() == cpu.pc() && probe.phase() == cpu.phase() && probe.same_state_as(&cpu) {
                    a.known = false;
                    return;
                }
            }
            a.look_ahead(&cpu);
        }
        a.on = a.until >= now + Apart::LEAST;
    }

    /// The core's cycles, apart, from now: at least `wanted` if it stays quiet that long
    /// (looking further ahead than the last run-ahead if need be), else up to its access.
    fn apart_room(&mut self, wanted: u64) -> u64 {
        let now = self.core().cycle();
        let a = &mut self.apart;
        if !a.found && a.until < now.saturating_add(wanted) {
            a.look_ahead(&self.cpu);
        }
        a.until.saturating_sub(now)
    }

    /// The core's cycle now, and its cycles per period since the mark.
    fn apart_period(&mut self) -> (u64, u64) {
        let now = self.core().cycle();
        (now, now - self.mark.as_ref().map_or(now, |m| m.cycle()))
    }

    /// Run the core, apart, `cycles` on with its pins low (fewer than its quiet horizon).
    fn run_apart(&mut self, cycles: u64) {
        let end = self.core().cycle() + cycles;
        debug_assert!(end <= self.apart.until);
        let (cpu, bus, a) = (&mut self.cpu, &mut self.bus, &mut self.apart);
        let access = a.solo.run(cpu, end, bus);
        debug_assert!(access.is_none());
        a.unchecked_until = end + 3;
        self.out = self.state();
    }

    /// What a debug build's waveform shows of the core now. The first call makes this a
    /// debug build: from then on the replay keeps these words with each cycle it records.
    fn debug_now(&mut self) -> DebugWords {
        if !self.debug {
            self.debug = true;
            self.watch.enabled = false; // the waveform shows the registers
            self.core(); // a trip recorded without them is not replayed
        }
        self.replay.debug().unwrap_or_else(|| debug_words(&self.cpu))
    }

    /// The core, brought up to date with the cycles played back since it was last simulated.
    fn core(&mut self) -> &mut Cpu {
        let bus = &mut self.bus;
        self.replay.catch_up(&mut self.cpu, |cpu, pins| {
            bus.in_port = (pins >> 18) as u8;
            cpu.tick(unpack(pins), bus);
        });
        &mut self.cpu
    }

    /// A breakpoint of this CPU that `r` hits.
    fn check_breaks(&mut self, r: &kcpsm6::iss::Retired) -> bool {
        let Some(b) = &self.breaks else { return false };
        let (breaks, now) = (&b.0, b.1);
        let Some(what) = breaks.hit(r).map(str::to_string) else { return false };
        // SAFETY: `now` points into the board, which outlives its CPUs' models.
        let time_ps = unsafe { *now };
        self.hit.get_or_insert(Hit { cpu: self.path.clone(), what, pc: r.pc, cycle: r.cycle, time_ps });
        true
    }

    /// The outputs in the current cycle, packed as kcpsm6_iss.v unpacks them.
    #[inline]
    fn state(&self) -> u64 {
        let c = &self.cpu;
        let strobe = c.strobe();
        c.pc() as u64
            | (c.bram_enable() as u64) << 12
            | (c.out_port() as u64) << 13
            | (c.port_id() as u64) << 21
            | ((strobe == Some(PortKind::Write)) as u64) << 29
            | ((strobe == Some(PortKind::KWrite)) as u64) << 30
            | ((strobe == Some(PortKind::Read)) as u64) << 31
            | (c.interrupt_ack() as u64) << 32
    }

    /// Reset, sleep or interrupt changed: a core apart no longer runs as it did ahead.
    #[cold]
    fn control_changed(&mut self, control: u64) {
        self.apart.control = control;
        self.apart.known = false;
        if std::mem::take(&mut self.apart.on) && !self.activity.is_null() {
            // SAFETY: the host outlives its models.
            unsafe { *self.activity += 1 };
        }
    }

    /// One cycle with the inputs `pins` (kcpsm6_iss.v's packing); the next cycle's outputs.
    #[inline]
    fn tick(&mut self, pins: u64) -> u64 {
        if pins & Apart::CONTROL != self.apart.control {
            self.control_changed(pins & Apart::CONTROL);
        }
        self.watch.cycle(pins, self.out);
        self.out = self.tick_core(pins);
        self.out
    }

    #[inline(always)]
    fn tick_core(&mut self, pins: u64) -> u64 {
        if self.replay.active() {
            let before = self.record.is_some().then(|| self.replay.current());
            if let Some(out) = self.replay.next(pins) {
                if let (Some(r), Some(before)) = (&mut self.record, before) {
                    r.push((pins, before));
                }
                return out;
            }
            self.core();
        }
        if self.record.is_some() {
            let state = self.state();
            if let Some(r) = &mut self.record {
                r.push((pins, state));
            }
        }
        let word = pins as u32 & 0x3FFFF;
        if self.cpu.phase() == Phase::Decode
            && word != self.cpu.instruction()
            && self.mismatch.is_none()
            && self.cpu.cycle() >= self.apart.unchecked_until
        {
            self.mismatch = Some(RomMismatch {
                cycle: self.cpu.cycle(),
                address: self.cpu.pc(),
                expected: self.cpu.instruction(),
                found: word,
            });
        }
        self.bus.in_port = (pins >> 18) as u8;
        let p = unpack(pins);
        // Two copies of the inlined tick: the plain one builds no record.
        if self.trace.is_none() && self.breaks.is_none() {
            self.cpu.tick(p, &mut self.bus);
            let state = self.state();
            // An interrupt: the fast-forward looks for a new period once the firmware is done.
            if state & 1 << 32 != 0 && !self.activity.is_null() {
                // SAFETY: the host outlives its models.
                unsafe { *self.activity += 1 };
            }
            let words = self.debug.then(|| debug_words(&self.cpu));
            self.replay.observe(&self.cpu, pins, state, words);
            return state;
        }
        let mut hit = false;
        if let Some(r) = self.cpu.tick(p, &mut self.bus) {
            if let Some(t) = &mut self.trace {
                t.retired(&r, self.cpu.cycle());
            }
            hit = self.check_breaks(&r);
        }
        self.state() | if hit { BREAK_BIT } else { 0 }
    }
}

unsafe extern "C" fn tick_ffi(cpu: *mut IssCpu, pins: u64) -> u64 {
    // SAFETY: the pointer is one `Host::create` made; the host outlives the model.
    unsafe { (*cpu).tick(pins) }
}

unsafe extern "C" fn state_ffi(cpu: *mut IssCpu) -> u64 {
    // SAFETY: as for tick_ffi.
    let cpu = unsafe { &mut *cpu };
    cpu.core();
    cpu.state()
}

/// The function a probe pointer starts with (`BoardProbeFns` in board_abi.h).
#[repr(C)]
struct ProbeFns {
    record: unsafe extern "C" fn(*mut Probe, u64, u64, u64),
}

static PROBE_FNS: ProbeFns = ProbeFns { record: record_ffi };

/// A probe on an RTL KCPSM6: every cycle's (pins, outputs) since the last [`Host::take`],
/// and the time each ended.
#[repr(C)]
pub struct Probe {
    fns: &'static ProbeFns,
    cycles: Vec<(u64, u64)>,
    times: Vec<u64>,
}

unsafe extern "C" fn record_ffi(probe: *mut Probe, pins: u64, state: u64, time_ps: u64) {
    // SAFETY: the pointer is one `Host::probe` made; the host outlives the model.
    let p = unsafe { &mut *probe };
    p.cycles.push((pins, state));
    p.times.push(time_ps);
}

/// One KCPSM6's recorded cycles: (pins, outputs) each, and, from a probe, the time each
/// cycle ended.
#[derive(Clone, Debug, Default)]
pub struct Recorded {
    pub path: String,
    pub cycles: Vec<(u64, u64)>,
    pub times: Vec<u64>,
}

/// What `--cpu-trace` asks for: the folder, the window of board time traced (ps), and the
/// source of each instance's program (by path; an instance without one shows disassembly).
pub struct TraceRequest {
    pub dir: PathBuf,
    pub window: (u64, u64),
    pub sources: BTreeMap<String, SourceMap>,
}

/// The `BoardHost` of board_abi.h.
#[repr(C)]
pub struct RawHost {
    ctx: *mut c_void,
    cpu_new: unsafe extern "C" fn(*mut c_void, *const c_char, u32, u32, u32, *const u64) -> *mut c_void,
    probe_new: unsafe extern "C" fn(*mut c_void, *const c_char) -> *mut c_void,
    bot_new: unsafe extern "C" fn(*mut c_void, *const c_char) -> *mut c_void,
    disasm: unsafe extern "C" fn(u32, *mut u8),
    activity: u64,
    ff_mark: unsafe extern "C" fn(*mut c_void),
    ff_snap: unsafe extern "C" fn(*mut c_void),
    ff_same: unsafe extern "C" fn(*mut c_void) -> c_int,
    ff_room: unsafe extern "C" fn(*mut c_void, u64) -> u64,
    ff_fits: unsafe extern "C" fn(*mut c_void, u64, u32) -> c_int,
    ff_skip: unsafe extern "C" fn(*mut c_void, u64, u32) -> u64,
}

/// The function a bot model's pointer starts with (`BoardBotFns` in board_abi.h).
#[repr(C)]
struct BotFns {
    edge: unsafe extern "C" fn(*mut BotModel, u32) -> u64,
}

static BOT_FNS: BotFns = BotFns { edge: edge_ffi };

/// The bot of a `--bot model` build: botsim's bot on the ISS with Rust models of world_if
/// and the map, simulated when something can change ([`LazyBot`]).
#[repr(C)]
pub struct BotModel {
    fns: &'static BotFns,
    bot: LazyBot,
    /// The inputs of the last edge.
    pins: u32,
    /// The host's activity count.
    activity: *mut u64,
    /// The bot's edges at the fast-forward's mark, and at each phase snapshot since.
    mark: u64,
    phases: Vec<u64>,
}

unsafe extern "C" fn edge_ffi(model: *mut BotModel, pins: u32) -> u64 {
    // SAFETY: the pointer is one `Host::bot` made; the harness calls from one thread.
    let m = unsafe { &mut *model };
    let out = m.bot.edge(pins >> 8 & 1 == 1, pins as u8).0;
    if pins != m.pins || m.bot.wrote() {
        m.pins = pins;
        // SAFETY: the host outlives its models.
        unsafe { *m.activity += 1 };
    }
    out
}

unsafe extern "C" fn bot_new_ffi(ctx: *mut c_void, path: *const c_char) -> *mut c_void {
    // SAFETY: as for cpu_new_ffi.
    let (host, path) = unsafe { (&mut *(ctx as *mut Host), CStr::from_ptr(path).to_string_lossy()) };
    host.bot(&path) as *mut c_void
}

/// The programs of a design's KCPSM6 instances, and their models once the design has made
/// them. Keep it alive (and at the same address: it is boxed) as long as the model.
pub struct Host {
    /// (path from the top, as `Plan::cpus` gives it; program).
    programs: Vec<(String, Image)>,
    cpus: Vec<(String, Box<IssCpu>)>,
    probes: Vec<(String, Box<Probe>)>,
    /// Record every cycle's ports (a lock-step run).
    recording: bool,
    trace: Option<TraceRequest>,
    /// The first instance the host had no program for.
    pub unknown: Option<String>,
    /// Breakpoints by instance path.
    breaks: BTreeMap<String, Breaks>,
    /// The first trace file that could not be written.
    trace_error: Option<String>,
    /// `--bot model`: the bot's firmware and world, and the model once made.
    bot_spec: Option<(Image, World)>,
    /// Boxed: the design holds pointers to them while the vector grows.
    #[allow(clippy::vec_box)]
    bots: Vec<Box<BotModel>>,
    /// No bot model (a board without a bot, or a team's own bot all in RTL): nothing of a
    /// bot bounds a skip.
    board_alone: bool,
    raw: RawHost,
}

impl Host {
    /// A host for the instances at `programs` (paths from the design's top); `recording`:
    /// keep every cycle's ports for [`Host::take`] (a lock-step run).
    pub fn new(programs: Vec<(String, Image)>, recording: bool) -> Box<Host> {
        let mut h = Box::new(Host {
            programs,
            cpus: Vec::new(),
            probes: Vec::new(),
            recording,
            trace: None,
            unknown: None,
            breaks: BTreeMap::new(),
            trace_error: None,
            bot_spec: None,
            bots: Vec::new(),
            board_alone: false,
            raw: RawHost {
                ctx: std::ptr::null_mut(),
                cpu_new: cpu_new_ffi,
                probe_new: probe_new_ffi,
                bot_new: bot_new_ffi,
                disasm: crate::sim::rtl::botsim_disasm_text,
                activity: 0,
                ff_mark: ff_mark_ffi,
                ff_snap: ff_snap_ffi,
                ff_same: ff_same_ffi,
                ff_room: ff_room_ffi,
                ff_fits: ff_fits_ffi,
                ff_skip: ff_skip_ffi,
            },
        });
        h.raw.ctx = &mut *h as *mut Host as *mut c_void;
        h
    }

    /// The pointer to hand to `board_new_hosted`.
    pub fn raw(&self) -> *const RawHost {
        &self.raw
    }

    /// The path from the design's top of the instance Verilator names `scope`
    /// (`TOP.botsim_board.user.SYS.APPCPU`), if the host knows it.
    fn known(&mut self, scope: &str) -> Option<usize> {
        let path = scope.split_once(".user.").map_or(scope, |(_, p)| p);
        let k = self.programs.iter().position(|(p, _)| p == path);
        if k.is_none() {
            self.unknown.get_or_insert_with(|| path.to_string());
        }
        k
    }

    /// `--bot model`: the bot runs `firmware` in `world` (before the model is made).
    pub fn model_bot(&mut self, firmware: Image, world: World) {
        self.bot_spec = Some((firmware, world));
    }

    /// The model for the bot instance Verilator names `scope` (null without
    /// [`Host::model_bot`], or for a firmware the bot's 1K ROM cannot hold).
    fn bot(&mut self, scope: &str) -> *mut BotModel {
        let Some((image, world)) = &self.bot_spec else {
            let path = scope.split_once(".user.").map_or(scope, |(_, p)| p);
            self.unknown.get_or_insert_with(|| path.to_string());
            return std::ptr::null_mut();
        };
        let Ok(bot) = IssBot::new(image, world.clone()) else { return std::ptr::null_mut() };
        let activity = &mut self.raw.activity as *mut u64;
        let mut m = Box::new(BotModel {
            fns: &BOT_FNS,
            bot: LazyBot::new(bot),
            pins: 0,
            activity,
            mark: 0,
            phases: Vec::new(),
        });
        let ptr = &mut *m as *mut BotModel;
        self.bots.push(m);
        ptr
    }

    /// True when the bot is a model ([`Host::model_bot`]).
    pub fn models_bot(&self) -> bool {
        self.bot_spec.is_some()
    }

    /// Stop the run at these breakpoints, by instance path (before the model is made).
    pub fn break_at(&mut self, breaks: BTreeMap<String, Breaks>) {
        self.breaks = breaks;
    }

    /// The first breakpoint hit, if any.
    pub fn hit(&self) -> Option<&Hit> {
        self.cpus.iter().filter_map(|(_, c)| c.hit.as_ref()).min_by_key(|h| h.time_ps)
    }

    /// Trace every instance's instructions and profile them (before the model is made).
    pub fn trace(&mut self, request: TraceRequest) {
        self.trace = Some(request);
    }

    /// The model for the instance Verilator names `scope`.
    fn create(&mut self, scope: &str, config: Config, now: *const u64) -> *mut IssCpu {
        let Some(k) = self.known(scope) else { return std::ptr::null_mut() };
        let (path, image) = &self.programs[k];
        let mut cpu = Box::new(IssCpu::new(config, image, self.recording));
        cpu.path = path.clone();
        cpu.activity = &mut self.raw.activity;
        if let Some(b) = self.breaks.get(path) {
            cpu.breaks = Some(Box::new((b.clone(), now)));
        }
        if let Some(req) = &self.trace {
            let file = req.dir.join(format!("{path}.trace.txt"));
            let tmp = req.dir.join(format!(".{path}.trace.txt.part"));
            match std::fs::File::create(&tmp) {
                Ok(f) => {
                    let map = req.sources.get(path).cloned().unwrap_or_default();
                    cpu.trace = Some(Box::new(CpuTrace {
                        tracer: Tracer::new(map, 0, u64::MAX),
                        out: BufWriter::with_capacity(1 << 20, f),
                        tmp,
                        file,
                        profile: req.dir.join(format!("{path}.profile.txt")),
                        now,
                        window: req.window,
                        error: None,
                    }));
                }
                Err(e) => {
                    self.trace_error.get_or_insert(format!("{}: error: cannot write: {e}", tmp.display()));
                }
            }
        }
        // A core that is traced, stops at breakpoints or is recorded runs every cycle.
        cpu.watch.enabled = cpu.trace.is_none() && cpu.breaks.is_none() && cpu.record.is_none();
        cpu.out = cpu.state();
        let ptr = &mut *cpu as *mut IssCpu;
        self.cpus.push((path.clone(), cpu));
        ptr
    }

    /// The fast-forward's mark: every model's state now (the phase snapshots of the last
    /// mark are dropped).
    fn ff_mark(&mut self) {
        for (_, c) in &mut self.cpus {
            c.decide_apart();
            c.mark = Some(Box::new(c.core().clone()));
            c.phases.clear();
            c.watch.mark();
        }
        for b in &mut self.bots {
            b.mark = b.bot.edges();
            b.phases.clear();
        }
    }

    /// A phase snapshot: every model's state now, between the mark and its period's end.
    fn ff_snap(&mut self) {
        for (_, c) in &mut self.cpus {
            let now = c.core().clone();
            c.phases.push(now);
        }
        for b in &mut self.bots {
            b.phases.push(b.bot.edges());
        }
    }

    /// Every KCPSM6 model is in its marked state (its cycle count aside), or in it but for a
    /// count (firmware that counts, proven: [`crate::fastforward::counts`]).
    fn ff_same(&mut self) -> Same {
        let mut all = Same::Yes;
        for (_, c) in &mut self.cpus {
            if c.apart.on {
                continue; // (run on its own over a skip)
            }
            c.core();
            let Some(m) = c.mark.as_deref() else { return Same::No };
            match c.watch.same(m, &c.cpu) {
                Same::No => return Same::No,
                Same::Counting => all = Same::Counting,
                Same::Yes => {}
            }
        }
        all
    }

    /// How many periods (each as long as the time since the mark), at most `periods`, every
    /// bot's outputs stay as they are with its inputs held; none without a bot model, all
    /// on a board without a bot.
    fn ff_room(&mut self, periods: u64) -> u64 {
        let mut n = periods;
        for (_, c) in &mut self.cpus {
            if c.apart.on {
                let (_, per) = c.apart_period();
                // (0: it came to its port access; no cycles: its clock does not run)
                if let Some(k) = c.apart_room(n.saturating_mul(per).saturating_add(per)).checked_div(per) {
                    n = n.min(k);
                }
            } else if let Some(room) = c.watch.room() {
                n = n.min(room);
            }
        }
        if self.bots.is_empty() {
            return if self.board_alone { n } else { 0 };
        }
        for b in &mut self.bots {
            let per = b.bot.edges() - b.mark;
            if per == 0 {
                continue; // its clock does not run
            }
            let wanted = n.saturating_mul(per).saturating_add(Self::MARGIN);
            n = n.min(b.bot.quiet_for(wanted).saturating_sub(Self::MARGIN) / per);
        }
        n
    }

    /// Every bot's outputs stay as they are for `periods` periods and then up to phase
    /// snapshot `phase` (1-based) of the next.
    fn ff_fits(&mut self, periods: u64, phase: usize) -> bool {
        // A core that counts is moved on by whole periods only.
        if self.cpus.iter().any(|(_, c)| c.watch.counting()) {
            return false;
        }
        for (_, c) in &mut self.cpus {
            if c.apart.on {
                let (_, per) = c.apart_period();
                let part = c.phases[phase - 1].cycle() - c.mark.as_ref().map_or(0, |m| m.cycle());
                if c.apart_room(periods * per + part) < periods * per + part {
                    return false;
                }
            }
        }
        if self.bots.is_empty() {
            return self.board_alone;
        }
        self.bots.iter_mut().all(|b| {
            let wanted = periods * (b.bot.edges() - b.mark) + (b.phases[phase - 1] - b.mark) + Self::MARGIN;
            b.bot.quiet_for(wanted) >= wanted
        })
    }

    /// The fast-forward ends this many cycles before the bot's next write.
    const MARGIN: u64 = 4;

    /// Run every model `periods` periods on, then to phase snapshot `phase` (1-based; 0:
    /// none) of the next; the bot's clock edges in all. Called at the end of the mark's first
    /// period: the mark and the snapshots move on to the start of the period the models are
    /// then in.
    fn ff_skip(&mut self, periods: u64, phase: usize) -> u64 {
        for (_, c) in &mut self.cpus {
            let now = c.core().cycle();
            if let Some(end) = c.watch.skip(periods) {
                // Where the proof says the periods leave it; the mark is the start of the next.
                c.mark = Some(Box::new(end.clone()));
                c.phases.clear();
                c.cpu = end;
                c.out = c.state();
                continue;
            }
            let Some(mark) = c.mark.as_mut() else { continue };
            let per = now - mark.cycle();
            let moved = (periods + 1) * per;
            let part = phase.checked_sub(1).map_or(0, |j| c.phases[j].cycle() - mark.cycle());
            mark.skip_period(moved);
            for p in &mut c.phases {
                p.skip_period(moved);
            }
            if c.apart.on {
                c.run_apart(periods * per + part);
                continue;
            }
            match phase.checked_sub(1) {
                Some(j) => c.cpu = c.phases[j].clone(),
                None => c.cpu.skip_period(periods * per),
            }
        }
        let mut edges = 0;
        for b in &mut self.bots {
            let per = b.bot.edges() - b.mark;
            let part = phase.checked_sub(1).map_or(0, |j| b.phases[j] - b.mark);
            let moved = (periods + 1) * per;
            b.mark += moved;
            for p in &mut b.phases {
                *p += moved;
            }
            edges = periods * per + part;
            b.bot.skip(edges);
        }
        edges
    }

    /// A probe for the RTL instance Verilator names `scope`.
    fn probe(&mut self, scope: &str) -> *mut Probe {
        let Some(k) = self.known(scope) else { return std::ptr::null_mut() };
        let mut probe = Box::new(Probe { fns: &PROBE_FNS, cycles: Vec::new(), times: Vec::new() });
        let ptr = &mut *probe as *mut Probe;
        self.probes.push((self.programs[k].0.clone(), probe));
        ptr
    }

    /// The ports recorded since the last call, per instance in the order of the host's
    /// programs: every cycle's (pins, outputs), packed as kcpsm6_iss.v packs them.
    pub fn take(&mut self) -> Vec<Recorded> {
        let mut out: Vec<Recorded> = Vec::new();
        for (p, c) in &mut self.cpus {
            let cycles = c.record.as_mut().map(std::mem::take).unwrap_or_default();
            out.push(Recorded { path: p.clone(), cycles, times: Vec::new() });
        }
        for (p, probe) in &mut self.probes {
            let (cycles, times) = (std::mem::take(&mut probe.cycles), std::mem::take(&mut probe.times));
            out.push(Recorded { path: p.clone(), cycles, times });
        }
        let order = |p: &String| self.programs.iter().position(|(q, _)| q == p);
        out.sort_by_key(|r| order(&r.path));
        out
    }

    /// The first ROM mismatch of any instance: (its path, what).
    pub fn mismatch(&self) -> Option<(&str, RomMismatch)> {
        self.cpus.iter().find_map(|(p, c)| c.mismatch.map(|m| (p.as_str(), m)))
    }

    /// The models, by path.
    pub fn cpus(&mut self) -> impl Iterator<Item = (&str, &Cpu)> {
        self.cpus.iter_mut().map(|(p, c)| (p.as_str(), &*c.core()))
    }
}

/// How [`Host::check`]'s errors start: the ISS cannot stand for a KCPSM6 of the design.
pub const ISS_CANNOT: &str = "--cpu iss";

unsafe extern "C" fn ff_mark_ffi(ctx: *mut c_void) {
    // SAFETY: ctx is the Host that made the RawHost; the harness calls from one thread.
    unsafe { (*(ctx as *mut Host)).ff_mark() }
}

/// 0: not as marked; 1: as marked; 2: as marked but for a count (board_abi.h).
unsafe extern "C" fn ff_same_ffi(ctx: *mut c_void) -> c_int {
    // SAFETY: as for ff_mark_ffi.
    match unsafe { (*(ctx as *mut Host)).ff_same() } {
        Same::No => 0,
        Same::Yes => 1,
        Same::Counting => 2,
    }
}

unsafe extern "C" fn ff_snap_ffi(ctx: *mut c_void) {
    // SAFETY: as for ff_mark_ffi.
    unsafe { (*(ctx as *mut Host)).ff_snap() }
}

unsafe extern "C" fn ff_room_ffi(ctx: *mut c_void, periods: u64) -> u64 {
    // SAFETY: as for ff_mark_ffi.
    unsafe { (*(ctx as *mut Host)).ff_room(periods) }
}

unsafe extern "C" fn ff_fits_ffi(ctx: *mut c_void, periods: u64, phase: u32) -> c_int {
    // SAFETY: as for ff_mark_ffi.
    unsafe { (*(ctx as *mut Host)).ff_fits(periods, phase as usize) as c_int }
}

unsafe extern "C" fn ff_skip_ffi(ctx: *mut c_void, periods: u64, phase: u32) -> u64 {
    // SAFETY: as for ff_mark_ffi.
    unsafe { (*(ctx as *mut Host)).ff_skip(periods, phase as usize) }
}

unsafe extern "C" fn probe_new_ffi(ctx: *mut c_void, path: *const c_char) -> *mut c_void {
    // SAFETY: as for cpu_new_ffi.
    let (host, path) = unsafe { (&mut *(ctx as *mut Host), CStr::from_ptr(path).to_string_lossy()) };
    host.probe(&path) as *mut c_void
}

unsafe extern "C" fn cpu_new_ffi(
    ctx: *mut c_void,
    path: *const c_char,
    hwbuild: u32,
    vector: u32,
    spm: u32,
    now: *const u64,
) -> *mut c_void {
    // SAFETY: ctx is the Host that made the RawHost; path is a NUL-terminated string.
    let (host, path) = unsafe { (&mut *(ctx as *mut Host), CStr::from_ptr(path).to_string_lossy()) };
    let config = Config {
        hwbuild: hwbuild as u8,
        interrupt_vector: vector as u16 & 0xFFF,
        scratch_pad_size: ScratchPad::from_bytes(spm as usize).unwrap_or(ScratchPad::B64),
    };
    host.create(&path, config, now) as *mut c_void
}

impl Host {
    /// The host for `plan`'s KCPSM6 instances, each with the program of the ROM wired to it;
    /// an instance whose ROM botsim cannot tell is an error (it can still run with the RTL core).
    pub fn for_plan(
        plan: &botsim_core::frontend::plan::Plan,
        recording: bool,
    ) -> Result<Box<Host>, botsim_core::frontend::BoardError> {
        use botsim_core::frontend::BoardError;
        let mut programs = Vec::new();
        for site in &plan.cpus {
            let rom = site.rom.as_ref().map_err(|why| {
                BoardError::plain(format!(
                    "{}: --cpu iss: cannot tell which program the KCPSM6 `{}` runs: {why} (run it with --cpu rtl)",
                    site.at, site.path
                ))
            })?;
            let Some(r) = plan.roms.iter().find(|r| &r.module == rom) else {
                return Err(BoardError::plain(format!(
                    "{}: --cpu iss: the KCPSM6 `{}` is fed by `{rom}`, which is not a program ROM botsim models (run it with --cpu rtl)",
                    site.at, site.path
                )));
            };
            programs.push((site.path.clone(), r.image.clone()));
        }
        let mut h = Host::new(programs, recording);
        // No bot model bounds a skip: a board without a bot, or one whose bot is the team's
        // own RTL (BotSim 3.1: its state is Verilator's, its KCPSM6 one of the models above).
        h.board_alone = plan.bot_path.is_none() || plan.team_bot.is_some();
        Ok(h)
    }

    /// Close the traces: every trace file under its name, and each CPU's profile beside it.
    /// Returns the files written.
    pub fn finish(&mut self) -> Result<Vec<PathBuf>, String> {
        if let Some(e) = self.trace_error.take() {
            return Err(e);
        }
        let mut written = Vec::new();
        for (_, cpu) in &mut self.cpus {
            let Some(mut t) = cpu.trace.take() else { continue };
            let fail = |p: &Path, e: std::io::Error| format!("{}: error: cannot write: {e}", p.display());
            if let Some(e) = t.error.take() {
                let _ = std::fs::remove_file(&t.tmp);
                return Err(fail(&t.file, e));
            }
            t.out.flush().map_err(|e| fail(&t.file, e))?;
            std::fs::rename(&t.tmp, &t.file).map_err(|e| fail(&t.file, e))?;
            crate::files::write_atomic(&t.profile, t.tracer.profile().as_bytes())?;
            written.extend([t.file.clone(), t.profile.clone()]);
        }
        Ok(written)
    }

    /// What went wrong in a run, if anything: an instance with no model, or a decoded word
    /// that the design's ROM did not give.
    pub fn check(&self) -> Result<(), String> {
        if let Some(p) = &self.unknown {
            return Err(format!(
                "{ISS_CANNOT}: the design has a KCPSM6 at `{p}` that botsim did not find in its sources"
            ));
        }
        if let Some((p, m)) = self.mismatch() {
            return Err(format!(
                "{ISS_CANNOT}: the KCPSM6 `{p}` decoded {:05X} at address {:03X} in its cycle {}, but its ROM gave {:05X}: the ROM is not wired or loaded as botsim read it (run it with --cpu rtl)",
                m.expected, m.address, m.cycle, m.found
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A team firmware's shape: wait for the interrupt routine's semaphore, then read a port,
    /// write it and the count of interrupts out, and wait again; a loop that writes a port
    /// on every trip; a countdown (its flops change on every trip: never replayed).
    const FIRMWARE: &str = "
        main:   LOAD sE, 00
                LOAD sA, 5A
                ENABLE INTERRUPT
        wait:   COMPARE sE, 00
                JUMP Z, wait
                LOAD sE, 00
                INPUT s1, 05
                OUTPUT s1, 06
                ADD s2, 01
                OUTPUT s2, 07
                LOAD s3, 20
        count:  SUB s3, 01
                JUMP NZ, count
                COMPARE s1, 80
                JUMP C, wait
        spin:   OUTPUT s1, 08
                COMPARE sE, 00
                JUMP Z, spin
                JUMP wait
        isr:    LOAD sE, 01
                RETURNI ENABLE
                ADDRESS 3FF
                JUMP isr
    ";

    /// A little generator for the test's stimulus.
    struct Rng(u64);
    impl Rng {
        fn below(&mut self, n: u64) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0 % n
        }
    }

    /// Two models of one core on the same design: one plays loops back, the other (with an
    /// empty breakpoint list, which keeps every cycle simulated) does not. The design around
    /// them: the program ROM (the word at the address of the cycle before, as a block RAM
    /// gives it), an interrupt raised at random times and held until acknowledged, an input
    /// port that changes at random, and a reset now and then.
    #[test]
    fn a_core_that_plays_loops_back_gives_the_outputs_of_one_simulated_every_cycle() {
        let program = kcpsm6::asm::assemble_str(FIRMWARE).unwrap().image;
        let now = 0u64;
        let mut fast = IssCpu::new(Config::default(), &program, false);
        let mut slow = IssCpu::new(Config::default(), &program, false);
        slow.breaks = Some(Box::new((Breaks::default(), &now as *const u64)));
        let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
        let (mut out, mut rom_out, mut irq, mut in_port, mut reset) = (fast.state(), 0u32, false, 0u8, 0u32);
        let mut acks = 0;
        for cycle in 0..400_000u64 {
            if !irq && rng.below(3_000) == 0 {
                irq = true;
            }
            if rng.below(5_000) == 0 {
                in_port = rng.below(256) as u8;
            }
            if reset == 0 && rng.below(100_000) == 0 {
                reset = 1 + rng.below(4) as u32;
            }
            let pins = rom_out as u64 | (in_port as u64) << 18 | (irq as u64) << 26 | ((reset > 0) as u64) << 28;
            reset = reset.saturating_sub(1);
            let next = fast.tick(pins);
            assert_eq!(next, slow.tick(pins), "cycle {cycle}");
            // What a debug build's waveform shows after the cycle (registers and flags).
            assert_eq!(fast.debug_now(), slow.debug_now(), "cycle {cycle}");
            // The block RAM's register takes the word at this cycle's address.
            if out >> 12 & 1 == 1 {
                rom_out = program.words[(out & 0xFFF) as usize];
            }
            if next >> 32 & 1 == 1 {
                irq = false;
                acks += 1;
            }
            out = next;
        }
        assert!(acks > 50, "{acks} interrupts");
        assert!(fast.replay.total > 200_000, "{} cycles played back", fast.replay.total);
        assert!(fast.core().same_state_as(slow.core()));
        assert_eq!(fast.core().cycle(), slow.core().cycle());
    }
}
