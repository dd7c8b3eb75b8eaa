//! A built board design, loaded at run time (libloading): the C interface of
//! `board_abi.h` behind a safe type that frees the model on drop.

use std::ffi::{c_char, c_int, CStr, CString};
use std::path::{Path, PathBuf};

use botsim_core::frontend::BoardError;
use botsim_core::{MotCtl, Registers, Snapshot};

use super::iss::{Host, RawHost};
use super::waveform;
use crate::fastforward::checks::{self, Verdicts};
use crate::fastforward::observed::Unshown;

/// One record of the harness's buffer, as `board_abi.h` lays it out; [`Event::of`] reads it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct RawEvent {
    time_ps: u64,
    kind: u32,
    a: u32,
    b: u64,
    c: u64,
}

/// One thing the board showed, at `time_ps`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Event {
    /// The seven-segment pins changed (all active low; `seg` = g..a).
    Display { time_ps: u64, an: u8, seg: u8, dp: bool },
    /// The LEDs changed.
    Leds { time_ps: u64, leds: u16 },
    /// upd_sysregs rose: the bot's registers (the cycle counted in the bot's clock from
    /// power-up) and the MotCtl it was given.
    Sample { time_ps: u64, snapshot: Snapshot, motctl: MotCtl },
    /// upd_sysregs of another of the design's bots (`bot` 1.., in `Plan::other_bots`' order):
    /// as `Sample` (the cycle counted in the first bot's clock).
    OtherSample { time_ps: u64, bot: usize, snapshot: Snapshot, motctl: MotCtl },
    /// The VGA pins changed (recorded only after [`BoardModel::record_vga`]):
    /// `r << 8 | g << 4 | b | hsync << 12 | vsync << 13`.
    Vga { time_ps: u64, pins: u16 },
    /// Any of the bot's outputs changed (recorded only after [`BoardModel::record_bot`]):
    /// upd_sysregs, and the registers packed as in `Sample` (LocX in the low byte).
    Bot { time_ps: u64, upd: bool, regs: u64 },
    /// The fast-forward skipped over periods in which the board showed something: the
    /// `events` records before this one (one period's) happen `count` more times, each
    /// `period_ps` after the last; the first repetition starts at `time_ps`. [`expand`]
    /// writes them out; a consumer that knows better (the display decoder) takes them whole.
    Repeat { time_ps: u64, events: usize, period_ps: u64, count: u64 },
    /// The lines between the FPGA and the board's peripherals changed (or are seen first).
    Lines { time_ps: u64, lines: Lines },
}

impl RawEvent {
    /// When the board showed it.
    pub fn time_ps(&self) -> u64 {
        self.time_ps
    }
}

impl Event {
    /// Decode a record (the packing is harness.cpp's `record` calls).
    pub fn of(e: &RawEvent) -> Option<Event> {
        let t = e.time_ps;
        Some(match e.kind {
            1 => Event::Display { time_ps: t, an: e.a as u8, seg: (e.a >> 8) as u8 & 0x7F, dp: e.a >> 15 & 1 == 1 },
            2 => Event::Leds { time_ps: t, leds: e.a as u16 },
            3 | 8 => {
                let byte = |k: u32| (e.b >> (8 * k)) as u8;
                let regs = Registers {
                    loc_x: byte(0),
                    loc_y: byte(1),
                    bot_info: byte(2),
                    sensors: byte(3),
                    lm_dist: byte(4),
                    rm_dist: byte(5),
                };
                let (sample, bot) = if e.kind == 3 { (e.a, 0) } else { (e.a & 0x0FFF_FFFF, (e.a >> 28) as usize) };
                let snapshot = Snapshot { sample: sample as u64, cycle: e.c, regs };
                match bot {
                    0 => Event::Sample { time_ps: t, snapshot, motctl: MotCtl(byte(6)) },
                    _ => Event::OtherSample { time_ps: t, bot, snapshot, motctl: MotCtl(byte(6)) },
                }
            }
            4 => Event::Vga { time_ps: t, pins: e.a as u16 },
            5 => Event::Bot { time_ps: t, upd: e.a & 1 == 1, regs: e.b },
            6 => Event::Repeat { time_ps: t, events: e.a as usize, period_ps: e.b, count: e.c },
            7 => Event::Lines { time_ps: t, lines: Lines(e.a as u16) },
            _ => return None,
        })
    }

    /// When it happened.
    pub fn time_ps(&self) -> u64 {
        match *self {
            Event::Display { time_ps, .. }
            | Event::Leds { time_ps, .. }
            | Event::Sample { time_ps, .. }
            | Event::OtherSample { time_ps, .. }
            | Event::Vga { time_ps, .. }
            | Event::Bot { time_ps, .. }
            | Event::Lines { time_ps, .. }
            | Event::Repeat { time_ps, .. } => time_ps,
        }
    }

    /// The same event `by` ps later.
    pub fn later(mut self, by: u64) -> Event {
        match &mut self {
            Event::Display { time_ps, .. }
            | Event::Leds { time_ps, .. }
            | Event::Sample { time_ps, .. }
            | Event::OtherSample { time_ps, .. }
            | Event::Vga { time_ps, .. }
            | Event::Bot { time_ps, .. }
            | Event::Lines { time_ps, .. }
            | Event::Repeat { time_ps, .. } => *time_ps += by,
        }
        self
    }
}

/// The records of a run, each [`Event::Repeat`] written out as the events it stands for:
/// what the board showed, in order, as if every edge had been simulated.
///
/// ```
/// use botsim::board::model::{expand, Event};
/// let led = |t, leds| Event::Leds { time_ps: t, leds };
/// let run = [led(10, 1), led(20, 0), Event::Repeat { time_ps: 40, events: 2, period_ps: 30, count: 2 }];
/// assert_eq!(expand(&run), [led(10, 1), led(20, 0), led(40, 1), led(50, 0), led(70, 1), led(80, 0)]);
/// ```
pub fn expand(events: &[Event]) -> Vec<Event> {
    let mut out = Vec::with_capacity(events.len());
    for (i, e) in events.iter().enumerate() {
        match *e {
            Event::Repeat { events: n, period_ps, count, .. } => {
                let period = &events[i.saturating_sub(n)..i];
                for j in 1..=count {
                    out.extend(period.iter().map(|p| p.later(j * period_ps)));
                }
            }
            e => out.push(e),
        }
    }
    out
}

/// The records a run's buffer holds: room for a skip over periods that show many changes
/// (harness.cpp keeps up to 2^16 of a period, and writes one period's and a phase's).
pub const RECORDS: usize = 1 << 18;

/// `RTLD_DEEPBIND` (glibc): the library resolves its symbols in itself first.
#[cfg(target_os = "linux")]
const RTLD_DEEPBIND: std::ffi::c_int = 0x8;
#[cfg(not(target_os = "linux"))]
const RTLD_DEEPBIND: std::ffi::c_int = 0;

/// Why a run stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// The time asked for was reached.
    Until,
    /// The event buffer is full; call again.
    BufferFull,
    /// The number of samples asked for was reached.
    Samples,
    /// `$finish` or a fatal error in the design.
    Finished,
}

type Opaque = std::ffi::c_void;

struct Api {
    new: unsafe extern "C" fn(c_int, *const *const c_char, *const RawHost) -> *mut Opaque,
    free: unsafe extern "C" fn(*mut Opaque),
    open_vcd: unsafe extern "C" fn(*mut Opaque, *const c_char) -> c_int,
    close_vcd: unsafe extern "C" fn(*mut Opaque),
    set_inputs: unsafe extern "C" fn(*mut Opaque, u32, u32, u32),
    record_vga: unsafe extern "C" fn(*mut Opaque, c_int),
    record_bot: unsafe extern "C" fn(*mut Opaque, c_int),
    run: unsafe extern "C" fn(*mut Opaque, u64, u64, *mut RawEvent, u32, *mut u32) -> u32,
    time_ps: unsafe extern "C" fn(*mut Opaque) -> u64,
    evals: unsafe extern "C" fn(*mut Opaque) -> u64,
    clock_count: unsafe extern "C" fn(*mut Opaque) -> usize,
    clock: unsafe extern "C" fn(*mut Opaque, usize, *mut u64, *mut u64),
    fatal: unsafe extern "C" fn(*mut Opaque) -> *const c_char,
    finish: unsafe extern "C" fn(*mut Opaque) -> *const c_char,
    output_done: unsafe extern "C" fn(*mut c_int) -> u64,
    bench_minimal: unsafe extern "C" fn(*mut Opaque, u64),
    fast_forward: unsafe extern "C" fn(*mut Opaque, c_int) -> c_int,
    rising_edges_only: unsafe extern "C" fn(*mut Opaque, c_int) -> c_int,
    fast_forwarded: unsafe extern "C" fn(*mut Opaque, *mut u64, *mut u64),
    fast_forward_busy: unsafe extern "C" fn(*mut Opaque, *mut *const c_char) -> u64,
    fast_forward_cut: unsafe extern "C" fn(*mut Opaque, *mut *const c_char) -> u64,
    push: unsafe extern "C" fn(*mut Opaque, u32, *const u8, u32) -> c_int,
    set_uart_div: unsafe extern "C" fn(*mut Opaque, u32),
    set_tilt: unsafe extern "C" fn(*mut Opaque, i32, i32, i32),
}

/// The lines between the FPGA and the board's peripherals, as on the board (a line the
/// design has no pin for idle): board_abi.h's packing.
///
/// ```
/// use botsim::board::model::Lines;
/// let l = Lines(0b10_0011_1001);
/// assert!(l.uart_tx() && l.uart_rx() && l.ps2_clk() && l.ps2_data() && l.acl_ss() && !l.pwm());
/// assert_eq!(Lines::NAMES[0], "RsTx");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Lines(pub u16);

impl Lines {
    /// The lines' names, bit 0 first.
    pub const NAMES: [&'static str; 10] =
        ["RsTx", "ampPWM", "ampSD", "RsRx", "PS2_CLK", "PS2_DATA", "aclSCK", "aclMOSI", "aclMISO", "aclSS"];
    pub fn bit(self, k: usize) -> bool {
        self.0 >> k & 1 == 1
    }
    pub fn uart_tx(self) -> bool {
        self.bit(0)
    }
    pub fn pwm(self) -> bool {
        self.bit(1)
    }
    pub fn amp_on(self) -> bool {
        self.bit(2)
    }
    pub fn uart_rx(self) -> bool {
        self.bit(3)
    }
    pub fn ps2_clk(self) -> bool {
        self.bit(4)
    }
    pub fn ps2_data(self) -> bool {
        self.bit(5)
    }
    pub fn acl_sck(self) -> bool {
        self.bit(6)
    }
    pub fn acl_mosi(self) -> bool {
        self.bit(7)
    }
    pub fn acl_miso(self) -> bool {
        self.bit(8)
    }
    pub fn acl_ss(self) -> bool {
        self.bit(9)
    }
}

/// What became of a push (bytes sent to a device).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pushed {
    Taken,
    /// An earlier push waits for its clock edge: try at the next.
    NextClock,
    /// The device's queue (64 bytes) has too little room: try when it has sent some. A
    /// design without the device has none.
    Full,
}

/// A device of the board the host sends bytes to (board_abi.h's `BOARD_UART`, `BOARD_KEYBOARD`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Device {
    /// The USB-UART bridge's line into the FPGA.
    Uart = 0,
    /// The keyboard (scan codes).
    Keyboard = 1,
}

/// Where a design's own printing (`$display`, `$write`, runtime warnings) goes: every line to
/// `log` when there is one, and the first `lines` lines to standard error.
#[derive(Clone, Debug)]
pub struct Printing {
    pub log: Option<PathBuf>,
    pub lines: u64,
}

impl Printing {
    /// Nothing shown, nothing kept (a second board of a lock-step run, a bench).
    pub const SILENT: Printing = Printing { log: None, lines: 0 };
}

impl Default for Printing {
    fn default() -> Printing {
        Printing { log: None, lines: 200 }
    }
}

/// What the fast-forward compares to find a period, and so what a run that uses it keeps
/// exact (harness.cpp).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub enum FastForward {
    /// Every clock edge simulated.
    Off = 0,
    /// The whole state (a run that opens a waveform later, which shows every variable).
    Whole = 1,
    /// What a run records (the display, the LEDs, the bot, the models): the parts nothing
    /// recorded reads (a VGA timing generator) are left as they are, and clocks that drive
    /// only such parts (its pixel clock) are not run (src/fastforward/observed.rs). For runs
    /// without a waveform or VGA frames.
    Recorded = 2,
}

/// A running board simulation.
pub struct BoardModel {
    api: Api,
    ptr: *mut Opaque,
    /// The KCPSM6 models of a `--cpu iss` build (freed after the model).
    host: Option<Box<Host>>,
    /// The waveform's start and, once closed, its end (ps).
    vcd_span: Option<(u64, Option<u64>)>,
    /// Why the build found this design cannot fast-forward (src/fastforward/checks.rs).
    fast_forward_blocker: Option<String>,
    observed_unknown: Option<String>,
    fast_forward_mode: FastForward,
    /// The waveform's signals a [`FastForward::Recorded`] run cannot show, or why they are
    /// not known (src/fastforward/observed.rs).
    unshown: Result<Vec<Unshown>, String>,
    /// A waveform opened in such a run: its file and the one Verilator writes.
    vcd_marking: Option<(PathBuf, PathBuf)>,
    /// How many signals of the last waveform closed read `x`.
    vcd_unshown: usize,
    // Dropped last: the functions above live in it.
    _lib: libloading::Library,
}

impl BoardModel {
    /// Load the library at `path` and create the model with the plusargs `args`
    /// (`+botsim_world=FILE`); a design built for `--cpu iss` takes its KCPSM6 models from
    /// `host`.
    pub fn load(
        path: &Path,
        args: &[String],
        host: Option<Box<Host>>,
        printing: &Printing,
    ) -> Result<BoardModel, BoardError> {
        // libloading's message names the file.
        let fail = |e: libloading::Error| BoardError::plain(format!("cannot load the built design: {e}"));
        // The library uses its own Verilator runtime, never one linked into botsim.
        let flags = libloading::os::unix::RTLD_NOW | libloading::os::unix::RTLD_LOCAL | RTLD_DEEPBIND;
        // SAFETY: the library is one botsim built from harness.cpp, with the ABI declared here.
        let lib: libloading::Library =
            unsafe { libloading::os::unix::Library::open(Some(path), flags) }.map_err(fail)?.into();
        macro_rules! sym {
            ($name:literal) => {
                // SAFETY: the symbol's type is the one board_abi.h and harness.cpp give it.
                *unsafe { lib.get($name) }.map_err(fail)?
            };
        }
        let api = Api {
            new: sym!(b"board_new_hosted"),
            free: sym!(b"board_free"),
            open_vcd: sym!(b"board_open_vcd"),
            close_vcd: sym!(b"board_close_vcd"),
            set_inputs: sym!(b"board_set_inputs"),
            record_vga: sym!(b"board_record_vga"),
            record_bot: sym!(b"board_record_bot"),
            fast_forward: sym!(b"board_fast_forward"),
            rising_edges_only: sym!(b"board_rising_edges_only"),
            fast_forwarded: sym!(b"board_fast_forwarded"),
            fast_forward_busy: sym!(b"board_fast_forward_busy"),
            fast_forward_cut: sym!(b"board_fast_forward_cut"),
            run: sym!(b"board_run"),
            time_ps: sym!(b"board_time_ps"),
            evals: sym!(b"board_evals"),
            clock_count: sym!(b"board_clock_count"),
            clock: sym!(b"board_clock"),
            fatal: sym!(b"board_fatal"),
            finish: sym!(b"board_finish"),
            output_done: sym!(b"board_output_done"),
            bench_minimal: sym!(b"board_bench_minimal"),
            push: sym!(b"board_push"),
            set_uart_div: sym!(b"board_set_uart_div"),
            set_tilt: sym!(b"board_set_tilt"),
        };
        // Where the design prints, before anything of it runs (its initial blocks print too).
        let output: unsafe extern "C" fn(*const c_char, u64) -> c_int = sym!(b"board_output");
        let log = printing.log.as_ref().map(|p| CString::new(p.to_string_lossy().into_owned()).unwrap_or_default());
        // SAFETY: the path is a NUL-terminated string that outlives the call.
        if unsafe { output(log.as_ref().map_or(std::ptr::null(), |c| c.as_ptr()), printing.lines) } == 0 {
            let p = printing.log.as_deref().unwrap_or(Path::new(""));
            return Err(BoardError::at(p, 0, 0, "cannot write the design's log"));
        }
        let cargs: Vec<CString> = std::iter::once("botsim".to_string())
            .chain(args.iter().cloned())
            .map(|a| CString::new(a).unwrap_or_default())
            .collect();
        let ptrs: Vec<*const c_char> = cargs.iter().map(|c| c.as_ptr()).collect();
        let raw = host.as_ref().map_or(std::ptr::null(), |h| h.raw());
        // SAFETY: argv outlives the call (the context copies the arguments); the host is
        // boxed and kept with the model.
        let ptr = unsafe { (api.new)(ptrs.len() as c_int, ptrs.as_ptr(), raw) };
        if ptr.is_null() {
            return Err(BoardError::at(path, 0, 0, "the built design could not be created"));
        }
        // What the build found the design allows (src/fastforward/checks.rs).
        let verdicts = Verdicts::load(path.parent().unwrap_or(Path::new(".")));
        // SAFETY: ptr is live.
        unsafe { (api.rising_edges_only)(ptr, verdicts.falling_edges.is_none() as c_int) };
        Ok(BoardModel {
            api,
            ptr,
            host,
            vcd_span: None,
            fast_forward_blocker: verdicts.fast_forward,
            observed_unknown: verdicts.observed,
            fast_forward_mode: FastForward::Off,
            unshown: checks::load_unshown(path.parent().unwrap_or(Path::new("."))),
            vcd_marking: None,
            vcd_unshown: 0,
            _lib: lib,
        })
    }

    /// Evaluate both clock edges, even where the build found the falling ones change nothing
    /// (models load evaluating rising edges only when it did).
    pub fn every_edge(&mut self) {
        // SAFETY: ptr is live.
        unsafe { (self.api.rising_edges_only)(self.ptr, 0) };
    }

    /// Why this design cannot fast-forward, or `None` when it can (one clock aside: see
    /// [`BoardModel::fast_forward`]).
    pub fn fast_forward_blocker(&self) -> Option<&str> {
        self.fast_forward_blocker.as_deref()
    }

    /// The KCPSM6 models (or probes), for a `--cpu iss` or lock-step build.
    pub fn host(&self) -> Option<&Host> {
        self.host.as_deref()
    }

    pub fn host_mut(&mut self) -> Option<&mut Host> {
        self.host.as_deref_mut()
    }

    /// Set the board's inputs (they act from the current time on).
    pub fn set_inputs(&mut self, reset_pressed: bool, buttons: u8, switches: u16) {
        // SAFETY: ptr is live until drop.
        unsafe { (self.api.set_inputs)(self.ptr, reset_pressed as u32, buttons as u32, switches as u32) }
    }

    /// Send up to 8 bytes to `device` (from the current time on, at the next clock edge).
    pub fn push(&mut self, device: Device, bytes: &[u8]) -> Pushed {
        let n = bytes.len().min(8);
        // SAFETY: ptr is live; the harness reads `n` bytes.
        match unsafe { (self.api.push)(self.ptr, device as u32, bytes.as_ptr(), n as u32) } {
            1 => Pushed::Taken,
            0 => Pushed::NextClock,
            _ => Pushed::Full,
        }
    }

    /// The USB-UART's rate into the FPGA, in clocks of the 100 MHz oscillator per bit.
    pub fn set_uart_div(&mut self, clocks_per_bit: u32) {
        // SAFETY: ptr is live.
        unsafe { (self.api.set_uart_div)(self.ptr, clocks_per_bit) }
    }

    /// The board's tilt: what its accelerometer measures on x, y and z, in mg (flat: 0, 0, 1000).
    pub fn set_tilt(&mut self, x: i32, y: i32, z: i32) {
        // SAFETY: ptr is live.
        unsafe { (self.api.set_tilt)(self.ptr, x, y, z) }
    }

    /// Skip the periods in which the board repeats itself (harness.cpp's fast-forward): for a
    /// board whose KCPSM6s and bot are models, and only while nothing needs every edge (a
    /// waveform is written edge by edge whatever this says; VGA capture, CPU traces,
    /// breakpoints and lock-step need it off). Returns whether it is on: with
    /// [`FastForward::Whole`] a board with one clock; with [`FastForward::Recorded`] also one
    /// whose other clocks drive nothing the run records (a VGA pixel clock).
    pub fn fast_forward(&mut self, mode: FastForward) -> bool {
        let mode = if self.fast_forward_blocker.is_some() { FastForward::Off } else { mode };
        // SAFETY: ptr is live.
        let on = unsafe { (self.api.fast_forward)(self.ptr, mode as c_int) != 0 };
        self.fast_forward_mode = if on { mode } else { FastForward::Off };
        on
    }

    /// Why the variables a run observes are not known for this design (the build's analysis of
    /// Verilator's output, src/fastforward/observed.rs), or `None`.
    pub fn observed_unknown(&self) -> Option<&str> {
        self.observed_unknown.as_deref()
    }

    /// The skips so far and the simulated time they covered (ps).
    pub fn fast_forwarded(&self) -> (u64, u64) {
        let (mut skips, mut ps) = (0, 0);
        // SAFETY: ptr is live.
        unsafe { (self.api.fast_forwarded)(self.ptr, &mut skips, &mut ps) };
        (skips, ps)
    }

    /// The variable of Verilator's root (its name there) that most often kept the
    /// fast-forward from finding a period, and how many times; `None` when none did.
    pub fn fast_forward_busy(&self) -> Option<(String, u64)> {
        self.most_often(self.api.fast_forward_busy)
    }

    /// The counter of Verilator's root that most often ended a skip (the next value the
    /// design compares it with came first), and how many times; `None` when none did.
    pub fn fast_forward_cut(&self) -> Option<(String, u64)> {
        self.most_often(self.api.fast_forward_cut)
    }

    fn most_often(&self, f: unsafe extern "C" fn(*mut Opaque, *mut *const c_char) -> u64) -> Option<(String, u64)> {
        let mut name: *const c_char = std::ptr::null();
        // SAFETY: ptr is live; the name is a string literal of the library, read at once.
        let n = unsafe { f(self.ptr, &mut name) };
        if n == 0 || name.is_null() {
            return None;
        }
        // SAFETY: as above.
        let name = unsafe { std::ffi::CStr::from_ptr(name) }.to_string_lossy().into_owned();
        Some((name, n))
    }

    /// Record every change of the bot's outputs from now on (a lock-step run compares them).
    pub fn record_bot(&mut self, on: bool) {
        // SAFETY: ptr is live.
        unsafe { (self.api.record_bot)(self.ptr, on as c_int) }
    }

    /// Record every change of the VGA pins from now on (for frame capture; it costs a
    /// comparison per evaluation and an event per change).
    pub fn record_vga(&mut self, on: bool) {
        // SAFETY: ptr is live.
        unsafe { (self.api.record_vga)(self.ptr, on as c_int) }
    }

    /// Run until `until_ps`, until `stop_after_samples` bot samples in all, or until `buf`
    /// is nearly full (the harness keeps room for one evaluation's records); returns why it
    /// stopped and how many records it wrote from the start of `buf`.
    pub fn run(&mut self, until_ps: u64, stop_after_samples: u64, buf: &mut [RawEvent]) -> (Stop, usize) {
        let cap = buf.len().min(u32::MAX as usize) as u32;
        let mut n = 0u32;
        // SAFETY: buf holds `cap` records; the harness writes at most that many.
        let r = unsafe { (self.api.run)(self.ptr, until_ps, stop_after_samples, buf.as_mut_ptr(), cap, &mut n) };
        let stop = match r {
            0 => Stop::Until,
            1 => Stop::BufferFull,
            2 => Stop::Samples,
            _ => Stop::Finished,
        };
        (stop, n as usize)
    }

    /// Simulated time in picoseconds.
    pub fn time_ps(&self) -> u64 {
        // SAFETY: ptr is live.
        unsafe { (self.api.time_ps)(self.ptr) }
    }

    /// Evaluations of the model so far (one per distinct edge time, plus input changes).
    pub fn evals(&self) -> u64 {
        // SAFETY: ptr is live.
        unsafe { (self.api.evals)(self.ptr) }
    }

    /// The clocks: the oscillator, then each generated clock, as periods `num / den` ps.
    pub fn clocks(&self) -> Vec<(u64, u64)> {
        // SAFETY: ptr is live; indices below the count.
        unsafe {
            (0..(self.api.clock_count)(self.ptr))
                .map(|i| {
                    let (mut n, mut d) = (0, 0);
                    (self.api.clock)(self.ptr, i, &mut n, &mut d);
                    (n, d)
                })
                .collect()
        }
    }

    /// Where the design called `$finish` (file:line), if it did.
    pub fn finish(&self) -> Option<String> {
        // SAFETY: the harness returns a NUL-terminated string owned by the model.
        let s = unsafe { CStr::from_ptr((self.api.finish)(self.ptr)) }.to_string_lossy().into_owned();
        (!s.is_empty()).then_some(s)
    }

    /// How many lines the design printed, and whether standard error now ends in the middle
    /// of one of them; closes the design's log.
    pub fn printed(&self) -> (u64, bool) {
        let mut mid = 0;
        // SAFETY: a plain call into the library.
        let lines = unsafe { (self.api.output_done)(&mut mid) };
        (lines, mid != 0)
    }

    /// The fatal error that stopped the design, if any.
    pub fn fatal(&self) -> Option<String> {
        // SAFETY: the harness returns a NUL-terminated string owned by the model.
        let s = unsafe { CStr::from_ptr((self.api.fatal)(self.ptr)) }.to_string_lossy().into_owned();
        (!s.is_empty()).then_some(s)
    }

    /// Run `cycles` of the 100 MHz oscillator with the minimal harness (two evaluations per
    /// cycle, no other clock, nothing recorded): the reference `botsim board --bench`
    /// measures the board harness against. Use a model of its own for it.
    pub fn bench_minimal(&mut self, cycles: u64) {
        // SAFETY: ptr is live.
        unsafe { (self.api.bench_minimal)(self.ptr, cycles) }
    }

    /// The time span of the waveform written so far (from its opening to its closing or to
    /// now), if one was opened.
    pub fn vcd_span(&self) -> Option<(u64, u64)> {
        self.vcd_span.map(|(a, b)| (a, b.unwrap_or_else(|| self.time_ps())))
    }

    /// Start a waveform of the whole design. In a [`FastForward::Recorded`] run, the signals
    /// that read what the run did not simulate are `x` in it (src/board/waveform.rs); Verilator
    /// writes it under a temporary name until [`BoardModel::close_vcd`].
    pub fn open_vcd(&mut self, path: &Path) -> Result<(), BoardError> {
        let mut target = path.to_path_buf();
        if self.fast_forward_mode == FastForward::Recorded {
            if let Err(why) = &self.unshown {
                return Err(BoardError::plain(format!(
                    "a waveform cannot begin in a run whose fast-forward keeps only what the run records: \
                     which of its signals such a run can show is not known ({why})"
                )));
            }
            let name = path.file_name().unwrap_or_default().to_string_lossy();
            target = path.with_file_name(format!(".{name}.part"));
        }
        let c = CString::new(target.as_os_str().as_encoded_bytes())
            .map_err(|_| BoardError::at(path, 0, 0, "bad file name"))?;
        // SAFETY: ptr is live; the path is copied.
        if unsafe { (self.api.open_vcd)(self.ptr, c.as_ptr()) } == 0 {
            return Err(BoardError::at(path, 0, 0, "cannot open the waveform file"));
        }
        if target != path {
            self.vcd_marking = Some((path.to_path_buf(), target));
        }
        self.vcd_span = Some((self.time_ps(), None));
        Ok(())
    }

    /// Stop the waveform (flushes and closes the file).
    pub fn close_vcd(&mut self) -> Result<(), BoardError> {
        let now = self.time_ps();
        if let Some((_, end @ None)) = &mut self.vcd_span {
            *end = Some(now);
        }
        // SAFETY: ptr is live.
        unsafe { (self.api.close_vcd)(self.ptr) }
        if let Some((path, part)) = self.vcd_marking.take() {
            let unshown = self.unshown.as_deref().unwrap_or_default();
            let marked = waveform::mark_unshown(&part, &path, unshown);
            let _ = std::fs::remove_file(&part);
            self.vcd_unshown = marked.map_err(|e| BoardError::at(&path, 0, 0, e))?;
        }
        Ok(())
    }

    /// Why a waveform in a [`FastForward::Recorded`] run cannot be written (which of its
    /// signals such a run can show is not known), or `None`.
    pub fn unshown_unknown(&self) -> Option<&str> {
        self.unshown.as_ref().err().map(String::as_str)
    }

    /// How many signals of the last waveform closed are `x` (they read what a
    /// [`FastForward::Recorded`] run did not simulate).
    pub fn vcd_unshown(&self) -> usize {
        self.vcd_unshown
    }
}

impl Drop for BoardModel {
    fn drop(&mut self) {
        // SAFETY: created by board_new, freed once.
        unsafe { (self.api.free)(self.ptr) }
        // A waveform never closed (an error ended the run) leaves no file.
        if let Some((_, part)) = self.vcd_marking.take() {
            let _ = std::fs::remove_file(part);
        }
    }
}
