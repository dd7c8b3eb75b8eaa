//! A run of the board: the model loaded (or the RTL and ISS boards in lock-step), driven
//! to its end through the inputs over time and the waveform's window, and what it shows
//! recorded ([`Records`]): the display, the LEDs, the bot's samples, the VGA frames.

use std::collections::BTreeSet;
use std::fmt::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use botsim::board::build::{BotKind, CpuModel};
use botsim::board::iss::Host;
use botsim::board::lockstep::Lockstep;
use botsim::board::model::{BoardModel, Device, Event, FastForward, Lines, Printing, Pushed, RawEvent, Stop, RECORDS};
use botsim::files::write_atomic;
use botsim::{Snapshot, World};
use botsim_core::board::display::Display;
use botsim_core::board::vga::Capture;
use botsim_core::debug::{describe_pc, sample_state};
use botsim_core::frontend::plan::Rom;
use botsim_core::frontend::wrapper;

use super::breaks::{save_file_view, write_save_file, BreakStop, Mark};
use super::devices::{Feeder, Heard};
use super::prepare::Prepared;
use super::progress::Progress;
use super::Args;
use crate::cli::rows::json_row;
use crate::cli::size::{parse_size, VCD_MAX};

/// How many lines of the design's own printing standard error shows.
const DESIGN_LINES: u64 = 200;

/// The most board time one call into the model covers: between two calls the run checks
/// Ctrl-C, the waveform's size and its progress line.
const CHUNK_PS: u64 = 50_000_000_000;

/// How long a run counted in samples (--samples without --seconds) waits for the bot's next
/// sample: 1 s of board time, about 19 samples at hw timing.
const NO_SAMPLE_PS: u64 = 1_000_000_000_000;

/// A row of --pins: the time and the display's and the LEDs' pins after a change, as
/// `"{time_ps},{an:02X},{seg:02X},{dp},{led:04X}"` writes it. Written digit by digit: a design
/// whose LEDs change at every clock writes millions of rows, and the formatter was most of
/// such a run's time.
fn pins_row(csv: &mut String, time_ps: u64, (an, seg, dp, led): (u8, u8, u8, u16)) {
    csv.push_str(itoa::Buffer::new().format(time_ps));
    csv.push(',');
    push_hex(csv, an.into(), 2);
    csv.push(',');
    push_hex(csv, seg.into(), 2);
    csv.push(',');
    csv.push_str(itoa::Buffer::new().format(dp));
    csv.push(',');
    push_hex(csv, led.into(), 4);
    csv.push('\n');
}

/// A row of --display for the LEDs, as `"{:>12.3} ms  leds    {leds:016b}"` writes it.
fn leds_row(log: &mut String, time_ps: u64, leds: u16) {
    push_ms(log, time_ps);
    log.push_str(" ms  leds    ");
    for k in (0..16).rev() {
        log.push(if leds >> k & 1 == 1 { '1' } else { '0' });
    }
    log.push('\n');
}

/// The low `digits` hex digits of `v`, upper case.
fn push_hex(s: &mut String, v: u64, digits: u32) {
    for k in (0..digits).rev() {
        s.push(char::from(b"0123456789ABCDEF"[(v >> (4 * k)) as usize & 15]));
    }
}

/// A time in ms to the microsecond, right-aligned in 12 characters: what `{:>12.3}` writes
/// for `time_ps as f64 / 1e9` (the nearest microsecond; a time exactly half way between two
/// goes through that formatting itself).
fn push_ms(s: &mut String, time_ps: u64) {
    if time_ps % 1_000_000 == 500_000 {
        let _ = write!(s, "{:>12.3}", time_ps as f64 / 1e9);
        return;
    }
    let us = (time_ps + 500_000) / 1_000_000;
    let mut b = itoa::Buffer::new();
    let ms = b.format(us / 1000);
    for _ in ms.len() + 4..12 {
        s.push(' ');
    }
    s.push_str(ms);
    s.push('.');
    let frac = us % 1000;
    for d in [frac / 100, frac / 10 % 10, frac % 10] {
        s.push(char::from(b'0' + d as u8));
    }
}

/// What a run recorded of the board, event by event.
pub struct Records {
    /// The seven-segment display as a person sees it.
    pub display: Display,
    /// `--display`: the display's and the LEDs' changes, a line each (kept only when asked
    /// for).
    pub display_log: Option<String>,
    /// `--pins`: every change of the display's and the LEDs' pins (kept only when asked for).
    pub pins_csv: Option<String>,
    pins_now: (u8, u8, u8, u16),
    pub last_led: u16,
    /// The bot's samples, and their JSON lines (`--trace-json`).
    pub snapshots: Vec<Snapshot>,
    pub json: String,
    pub last_sample_ps: u64,
    /// The design's other bots' samples (`Plan::other_bots`' order), as `snapshots` and
    /// `json` are the first's.
    pub others: Vec<BotTrace>,
    /// The VGA output (with `frames`, its frames are written there).
    pub vga: Capture,
    frames: Option<PathBuf>,
    frame_every: u64,
    pub frames_seen: u64,
    pub frames_written: u64,
    /// What the design sent the host: the UART's bytes, the sound.
    pub heard: Heard,
    /// `--lines`: every change of the peripherals' lines (kept only when asked for).
    pub lines_csv: Option<String>,
}

/// Another bot's samples: its snapshots and their JSON rows.
#[derive(Default)]
pub struct BotTrace {
    pub snapshots: Vec<Snapshot>,
    pub json: String,
}

impl Records {
    pub fn new(frames: Option<PathBuf>, frame_every: u64, pins: bool, display_log: bool, heard: Heard) -> Records {
        Records {
            display: Display::default(),
            display_log: display_log.then(String::new),
            pins_csv: pins.then(|| String::from("time_ps,an,seg,dp,led\n")),
            pins_now: (0xFF, 0x7F, 1, 0),
            last_led: 0,
            snapshots: Vec::new(),
            json: String::new(),
            last_sample_ps: 0,
            others: Vec::new(),
            vga: Capture::default(),
            frames,
            frame_every: frame_every.max(1),
            frames_seen: 0,
            frames_written: 0,
            heard,
            lines_csv: None,
        }
    }

    /// Record one event of the board.
    pub fn event(&mut self, e: Event) {
        match e {
            Event::Display { time_ps, an, seg, dp } => {
                self.pins_now = (an, seg, dp as u8, self.pins_now.3);
                if let Some(csv) = &mut self.pins_csv {
                    pins_row(csv, time_ps, self.pins_now);
                }
                let before = self.display.lines().len();
                self.display.pins(time_ps, an, seg, dp);
                self.log_display_lines(before);
            }
            Event::Leds { time_ps, leds } => {
                self.pins_now.3 = leds;
                if let Some(csv) = &mut self.pins_csv {
                    pins_row(csv, time_ps, self.pins_now);
                }
                self.last_led = leds;
                if let Some(log) = &mut self.display_log {
                    leds_row(log, time_ps, leds);
                }
            }
            Event::Sample { time_ps, snapshot, motctl } => {
                self.last_sample_ps = time_ps;
                self.json.push_str(&json_row(&snapshot, motctl));
                self.snapshots.push(snapshot);
            }
            Event::OtherSample { bot, snapshot, motctl, .. } => {
                if self.others.len() < bot {
                    self.others.resize_with(bot, BotTrace::default);
                }
                let t = &mut self.others[bot - 1];
                t.json.push_str(&json_row(&snapshot, motctl));
                t.snapshots.push(snapshot);
            }
            Event::Vga { time_ps, pins } => self.vga.pins(time_ps, pins),
            Event::Lines { time_ps, lines } => {
                self.heard.lines(time_ps, lines);
                if let Some(csv) = &mut self.lines_csv {
                    let _ = write!(csv, "{time_ps}");
                    for k in 0..Lines::NAMES.len() {
                        let _ = write!(csv, ",{}", lines.bit(k) as u8);
                    }
                    csv.push('\n');
                }
            }
            // Recorded for the lock-step's comparison only.
            Event::Bot { .. } => {}
            // Taken whole by `repeat`; here, written out is all that can be done.
            Event::Repeat { .. } => {}
        }
    }

    /// The events of one period (`period`, already recorded) happen `count` more times, each
    /// `period_ps` after the last: as if each were recorded, but a period that only
    /// multiplexes the display (the course's sevensegment at SIMULATE = 1 shows eight digits
    /// every 48 clocks) costs the decoder a few periods, not all of them.
    pub fn repeat(&mut self, period: &[Event], period_ps: u64, count: u64) {
        let display_only = period.iter().all(|e| matches!(e, Event::Display { .. }));
        if !display_only || self.pins_csv.is_some() {
            for j in 1..=count {
                for e in period {
                    self.event(e.later(j * period_ps));
                }
            }
            return;
        }
        let pins: Vec<(u64, u8, u8, bool)> = period
            .iter()
            .filter_map(|e| match *e {
                Event::Display { time_ps, an, seg, dp } => Some((time_ps, an, seg, dp)),
                _ => None,
            })
            .collect();
        let before = self.display.lines().len();
        self.display.repeat(&pins, period_ps, count);
        self.log_display_lines(before);
        if let Some(&(_, an, seg, dp)) = pins.last() {
            self.pins_now = (an, seg, dp as u8, self.pins_now.3);
        }
    }

    /// The display's lines from `before` on into `--display`'s log.
    fn log_display_lines(&mut self, before: usize) {
        let Some(log) = &mut self.display_log else { return };
        for l in &self.display.lines()[before..] {
            push_ms(log, l.time_ps);
            log.push_str(" ms  display ");
            log.push_str(&l.text);
            log.push('\n');
        }
    }

    /// Write the VGA frames completed so far (every `frame_every`-th).
    pub fn write_frames(&mut self) -> Result<(), String> {
        let Some(dir) = &self.frames else { return Ok(()) };
        for f in self.vga.take() {
            if self.frames_seen % self.frame_every == 0 {
                write_atomic(&dir.join(format!("frame_{:05}.png", self.frames_seen)), &f.png())?;
                self.frames_written += 1;
            }
            self.frames_seen += 1;
        }
        Ok(())
    }
}

/// How a run ended, and what it recorded.
pub struct Outcome {
    pub rec: Records,
    /// What stopped it: time, samples, line-end, blocked, break, finish, interrupt.
    pub stopped_by: &'static str,
    /// The breakpoint that stopped it.
    pub stopped: Option<BreakStop>,
    pub wall_seconds: f64,
    pub sim_ps: u64,
    /// The fast-forward: how many skips, how much board time they covered, and why a run
    /// that could skip did not.
    pub skips: u64,
    pub skipped_ps: u64,
    pub fast_forward_off: Option<String>,
    pub evaluations: u64,
    pub vcd_x_signals: usize,
    pub traces: Vec<PathBuf>,
    pub design_lines: u64,
    /// The variable (Verilator's name) that most often kept the fast-forward from a period,
    /// and how often.
    pub busy: Option<(String, u64)>,
    /// The counter (Verilator's name) whose next compared value most often ended a skip, and
    /// how often.
    pub cut: Option<(String, u64)>,
}

/// Run the prepared board as the arguments say: the session opens (models loaded, the
/// fast-forward chosen, the first inputs set), runs chunk by chunk until something stops it,
/// and closes (traces, breakpoints, the design's own end, the waveform).
pub fn simulate(a: &Args, p: &Prepared) -> Result<Outcome, String> {
    let mut session = Session::open(a, p)?;
    let t0 = Instant::now();
    let stopped_by = loop {
        if crate::cli::interrupted() {
            break None;
        }
        if let Some(why) = session.step()? {
            break Some(why);
        }
    };
    session.close(stopped_by, t0.elapsed().as_secs_f64())
}

/// The waveform's window: open or not, done, and the time it closes at when its end is
/// given in samples.
struct Window {
    open: bool,
    done: bool,
    close_at: Option<u64>,
}

/// A run of the board, phase by phase.
struct Session<'a> {
    a: &'a Args,
    p: &'a Prepared,
    model: Sim,
    rec: Records,
    vcd: Window,
    /// Why a run that could fast-forward does not (the design, not the options).
    fast_forward_off: Option<String>,
    end_ps: u64,
    /// As botsim run: sample 0 is the dump after reset, --samples N stops after sample N.
    sample_limit: u64,
    /// Times at which the run stops to change something: the inputs, the waveform window.
    stops: BTreeSet<u64>,
    vcd_max: u64,
    progress: Progress,
    buf: Vec<RawEvent>,
    at_end: bool,
    blocked_now: bool,
    bot_stop: Option<BreakStop>,
    /// The bytes waiting for the design's UART and keyboard.
    feeder: Feeder,
    /// When the stimulus changes an input (`stops` also holds the waveform's marks and the
    /// feeder's retries).
    input_times: BTreeSet<u64>,
}

impl<'a> Session<'a> {
    /// Load the models, open a waveform that starts at once, choose the fast-forward, and
    /// set the first inputs.
    fn open(a: &'a Args, p: &'a Prepared) -> Result<Session<'a>, String> {
        let printing = Printing { log: a.design_log.clone(), lines: if a.quiet { 0 } else { DESIGN_LINES } };
        let mut first = load(&p.built.library, &p.world, &p.plan.roms, p.main_host()?, &printing)?;
        if a.every_edge {
            first.every_edge();
        }
        let mut model = match &p.twin {
            Some(b) => {
                let mut iss =
                    load(&b.library, &p.world, &p.plan.roms, p.host(CpuModel::Iss, p.bot)?, &Printing::SILENT)?;
                if a.every_edge {
                    iss.every_edge();
                }
                Sim::Pair(Box::new(Lockstep::new(first, iss)))
            }
            None => Sim::One(Box::new(first)),
        };
        // The waveform: open from the start, or at its --trace-from mark.
        let mut vcd = Window { open: false, done: a.vcd.is_none(), close_at: None };
        if let (Some(v), Mark::Time(0) | Mark::Sample(0)) = (&a.vcd, p.vcd_from) {
            model.main().open_vcd(v).map_err(|e| e.to_string())?;
            vcd.open = true;
        }
        model.record_vga(a.frames.is_some());
        let fast_forward_off = choose_fast_forward(a, p, &mut model, vcd.open);
        let end_ps = match (a.seconds, a.samples) {
            (Some(s), _) => (s * 1e12) as u64,
            (None, Some(_)) => u64::MAX,
            (None, None) => 1_000_000_000_000,
        };
        let sample_limit = a.samples.map_or(u64::MAX, |n| n.saturating_add(1));
        let input_times: BTreeSet<u64> = p.stimulus.change_times().into_iter().collect();
        let mut stops = input_times.clone();
        if a.vcd.is_some() {
            for m in [Some(p.vcd_from), p.vcd_to].into_iter().flatten() {
                if let Mark::Time(t) = m {
                    stops.insert(t);
                }
            }
        }
        let (r, b, sw) = p.stimulus.inputs_at(0);
        model.set_inputs(r, b, sw);
        let heard = Heard::new(a.uart_baud, a.audio.is_some());
        let [x, y, z] = p.stimulus.tilt_at(0);
        let div = heard.uart_div;
        model.each(|m| {
            m.set_uart_div(div);
            m.set_tilt(x, y, z);
        });
        let mut feeder = Feeder::default();
        feeder.queue(&p.stimulus, 0);
        if let Some(t) = feeder.feed(0, |d, b| model.push(d, b)) {
            stops.insert(t);
        }
        Ok(Session {
            a,
            p,
            model,
            rec: Records {
                lines_csv: a.lines.as_ref().map(|_| format!("time_ps,{}\n", Lines::NAMES.join(","))),
                ..Records::new(a.frames.clone(), a.frame_every, a.pins.is_some(), a.display.is_some(), heard)
            },
            vcd,
            fast_forward_off,
            end_ps,
            sample_limit,
            stops,
            vcd_max: a.vcd_max.as_deref().map_or(Ok(VCD_MAX), parse_size)?,
            progress: Progress::new(!a.quiet && !a.json && !a.finding, end_ps, sample_limit),
            buf: vec![RawEvent::default(); RECORDS],
            at_end: false,
            blocked_now: false,
            bot_stop: None,
            feeder,
            input_times,
        })
    }

    /// Run one chunk: to the next stop, within a chunk's time, and take what the board
    /// showed. Returns what ended the run, if it ended.
    fn step(&mut self) -> Result<Option<&'static str>, String> {
        let (a, p) = (self.a, self.p);
        let now = self.model.main().time_ps();
        let mut until = self.stops.range(now + 1..).next().copied().unwrap_or(self.end_ps).min(self.end_ps);
        // A waveform grows fast: its size is looked at more often.
        until = until.min(now.saturating_add(if self.vcd.open { CHUNK_PS / 10 } else { CHUNK_PS }));
        self.progress.show(now, self.rec.snapshots.len() as u64);
        self.check_waveform_size(now)?;
        // A run counted in samples waits for the next one a bounded time.
        let counted_in_samples = a.seconds.is_none() && p.plan.bot_path.is_some();
        if counted_in_samples {
            until = until.min(self.rec.last_sample_ps.saturating_add(NO_SAMPLE_PS));
        }
        // A window given in samples: stop after sample s - 1 to open, after sample s to close.
        let window_limit = match (self.vcd.done, self.vcd.open, p.vcd_from, p.vcd_to) {
            (false, false, Mark::Sample(s), _) => Some(s),
            (false, true, _, Some(Mark::Sample(s))) if self.vcd.close_at.is_none() => Some(s + 1),
            _ => None,
        };
        let mut limit = window_limit.map_or(self.sample_limit, |w| w.min(self.sample_limit));
        if a.stop_at_line_end || a.stop_when_blocked || !p.bot_breaks.is_empty() {
            limit = limit.min(self.rec.snapshots.len() as u64 + 1);
        }
        let (stop, n) = self.model.run(until, limit, &mut self.buf)?;
        let events: Vec<Event> = self.buf[..n].iter().filter_map(Event::of).collect();
        self.take(&events);
        self.rec.write_frames()?;
        if self.at_end {
            return Ok(Some("line-end"));
        }
        if self.blocked_now {
            return Ok(Some("blocked"));
        }
        if self.bot_stop.is_some() {
            return Ok(Some("break"));
        }
        match stop {
            Stop::BufferFull => Ok(None),
            Stop::Samples if self.rec.snapshots.len() as u64 >= self.sample_limit => Ok(Some("samples")),
            // A stop after one more sample, to look for the end of the line.
            Stop::Samples if !window_limit.is_some_and(|w| self.rec.snapshots.len() as u64 >= w) => Ok(None),
            Stop::Samples => {
                // A window mark in samples.
                if let (false, Some(v)) = (self.vcd.open, &a.vcd) {
                    self.model.main().open_vcd(v).map_err(|e| e.to_string())?;
                    self.vcd.open = true;
                } else {
                    // Close with the whole 2-clock pulse in the window (3 clocks of 100 MHz).
                    let t = self.model.main().time_ps() + 30_000;
                    self.stops.insert(t);
                    self.vcd.close_at = Some(t);
                }
                Ok(None)
            }
            Stop::Finished => Ok(Some("finish")),
            Stop::Until => self.at_stop(counted_in_samples),
        }
    }

    /// The run reached the time it ran to: its end, a wait for a sample that does not come,
    /// or a stop where the inputs or the waveform window change.
    fn at_stop(&mut self, counted_in_samples: bool) -> Result<Option<&'static str>, String> {
        let (a, p) = (self.a, self.p);
        // A CPU the ISS cannot stand for stops the run here, not at its end.
        self.model.check()?;
        let t = self.model.main().time_ps();
        if t >= self.end_ps {
            return Ok(Some("time"));
        }
        let last = self.rec.last_sample_ps;
        if counted_in_samples && t >= last.saturating_add(NO_SAMPLE_PS) {
            let after = match self.rec.snapshots.last() {
                None => "from the start".to_string(),
                Some(s) => format!("after sample {} at {:.3} ms", s.sample, last as f64 / 1e9),
            };
            return Err(format!(
                "no bot sample in {} s of board time {after} (upd_sysregs never pulsed: is the bot held in reset, or its clock stopped?)",
                NO_SAMPLE_PS / 1_000_000_000_000
            ));
        }
        if self.stops.contains(&t) {
            if self.input_times.contains(&t) {
                let (r, b, sw) = p.stimulus.inputs_at(t);
                self.model.set_inputs(r, b, sw);
                let [x, y, z] = p.stimulus.tilt_at(t);
                self.model.each(|m| m.set_tilt(x, y, z));
                self.feeder.queue(&p.stimulus, t);
            }
            // The design's own UART rate, once measured, is the host's too.
            if let Some(div) = self.rec.heard.new_uart_div() {
                self.model.each(|m| m.set_uart_div(div));
            }
            let model = &mut self.model;
            if let Some(again) = self.feeder.feed(t, |d, b| model.push(d, b)) {
                self.stops.insert(again);
            }
            if let Some(v) = &a.vcd {
                if !self.vcd.open && !self.vcd.done && p.vcd_from == Mark::Time(t) {
                    self.model.main().open_vcd(v).map_err(|e| e.to_string())?;
                    self.vcd.open = true;
                } else if self.vcd.open && (p.vcd_to == Some(Mark::Time(t)) || self.vcd.close_at == Some(t)) {
                    self.model.main().close_vcd().map_err(|e| e.to_string())?;
                    (self.vcd.open, self.vcd.done) = (false, true);
                }
            }
        }
        Ok(None)
    }

    /// A waveform past its budget is removed, and the run asks for a window.
    fn check_waveform_size(&mut self, now: u64) -> Result<(), String> {
        let (Some(v), true) = (&self.a.vcd, self.vcd.open) else { return Ok(()) };
        let size = std::fs::metadata(v).map_or(0, |m| m.len());
        if size <= self.vcd_max {
            return Ok(());
        }
        // (The model, dropped with the session, closes the file it writes to.)
        let _ = std::fs::remove_file(v);
        Err(format!(
            "{}: the waveform passed {} MB at {:.3} ms of board time and was removed: ask for a window (--trace-from/--trace-to) or allow more (--vcd-max)",
            v.display(),
            self.vcd_max >> 20,
            now as f64 / 1e9
        ))
    }

    /// Take a chunk's events into the records: the samples checked for the stops asked for,
    /// a skip's repeated periods taken whole; a run repeated to a stop records up to it.
    fn take(&mut self, events: &[Event]) {
        let (a, p) = (self.a, self.p);
        let past_stop = |t: u64| a.stopped_at.as_ref().is_some_and(|s| t > s.time_ps);
        for (i, &e) in events.iter().enumerate() {
            if let Event::Repeat { events: per, period_ps, count, .. } = e {
                let period = &events[i - per..i];
                let end = period.last().map_or(0, Event::time_ps);
                let whole = match &a.stopped_at {
                    Some(s) => (1..=count).take_while(|j| end + j * period_ps <= s.time_ps).count() as u64,
                    None => count,
                };
                self.rec.repeat(period, period_ps, whole);
                if whole < count {
                    let next = period.iter().map(|p| p.later((whole + 1) * period_ps));
                    next.filter(|p| !past_stop(p.time_ps())).for_each(|p| self.rec.event(p));
                }
                continue;
            }
            if past_stop(e.time_ps()) {
                continue;
            }
            if let Event::Sample { time_ps, snapshot, .. } = &e {
                let before = self.rec.snapshots.last();
                self.at_end = self.at_end || (a.stop_at_line_end && at_line_end(snapshot));
                self.blocked_now = self.blocked_now
                    || (a.stop_when_blocked && before.is_some_and(|b| b.move_refused(snapshot, p.fw.threshold)));
                if self.bot_stop.is_none() {
                    if let Some(b) = p.bot_breaks.iter().find(|b| b.hit(before, snapshot, p.fw.threshold)) {
                        let at =
                            sample_state(snapshot).replacen(',', &format!(" at {:.6} ms,", *time_ps as f64 / 1e9), 1);
                        self.bot_stop = Some(BreakStop {
                            time_ps: *time_ps,
                            bot: true,
                            message: format!("stopped by --break {}: {at}", b.text),
                        });
                    }
                }
            }
            self.rec.event(e);
        }
    }

    /// The run has ended (`stopped_by`, or Ctrl-C): what stopped it and where, the design's
    /// own end, the traces and the waveform written.
    fn close(mut self, stopped_by: Option<&'static str>, wall: f64) -> Result<Outcome, String> {
        let (a, p) = (self.a, self.p);
        let (skips, skipped_ps) = self.model.main().fast_forwarded();
        let sim_ps = self.model.main().time_ps();
        self.rec.display.settle(sim_ps);
        self.model.check()?;
        let traces = self.model.finish_traces()?;
        // A breakpoint in a CPU stops the model like $finish.
        let cpu_stop = self.model.hit().map(|h| {
            let (path, at) = (h.cpu.clone(), describe_pc(p.maps.get(&h.cpu), h.pc));
            BreakStop {
                time_ps: h.time_ps,
                bot: false,
                message: format!(
                    "stopped by --break {}: {path} at {at} in its cycle {}, at {:.6} ms",
                    h.what,
                    h.cycle,
                    h.time_ps as f64 / 1e9
                ),
            }
        });
        self.progress.done();
        let stopped = cpu_stop.or(self.bot_stop.take()).or(a.stopped_at.clone());
        // The design's own printing ends here: botsim's lines start on lines of their own.
        let (design_lines, mid_line) = self.model.main().printed();
        if mid_line {
            eprintln!();
        }
        if let Some(s) = &stopped {
            if !a.json && !a.finding {
                eprintln!("{}", s.message);
            }
        } else if let Some(f) = self.model.main().fatal() {
            let at = format!("{:.6} ms", self.model.main().time_ps() as f64 / 1e9);
            if let (Some(v), Some(why)) = (&a.vcd, f.strip_prefix(":0: VerilatedVcd::bufferFlush: ")) {
                drop(self.model);
                let _ = std::fs::remove_file(v);
                return Err(format!(
                    "{}: the waveform could not be written ({why}) at {at}; the part written was removed",
                    v.display()
                ));
            }
            return Err(design_stopped(&p.built.user_paths(&f), &p.built, &at));
        }
        if let (Some(f), false) = (self.model.main().finish(), a.json || a.quiet || a.finding) {
            eprintln!(
                "botsim board: the design called $finish at {} ({:.6} ms)",
                p.built.user_paths(&f),
                self.model.main().time_ps() as f64 / 1e9
            );
        }
        let stopped_by = if stopped.is_some() { Some("break") } else { stopped_by };
        self.model.main().close_vcd().map_err(|e| e.to_string())?;
        if let (Some(v), Some((start, end))) = (&a.vcd, self.model.main().vcd_span()) {
            let view = save_file_view(start, end, stopped.as_ref());
            write_save_file(v, &p.plan, &p.maps, p.cpu == CpuModel::RtlProbed, p.main_bot == BotKind::Model, view)?;
        }
        Ok(Outcome {
            rec: self.rec,
            stopped_by: stopped_by.unwrap_or("interrupt"),
            stopped,
            wall_seconds: wall,
            sim_ps,
            skips,
            skipped_ps,
            fast_forward_off: self.fast_forward_off,
            evaluations: self.model.main().evals(),
            vcd_x_signals: self.model.main().vcd_unshown(),
            traces,
            design_lines,
            busy: self.model.main().fast_forward_busy(),
            cut: self.model.main().fast_forward_cut(),
        })
    }
}

/// Turn the fast-forward on where the run allows it: every KCPSM6 and the bot are models,
/// and nothing needs every edge (a waveform turns it off while it is written). Returns why
/// a run that could fast-forward does not (the design, not the options), and says so.
fn choose_fast_forward(a: &Args, p: &Prepared, model: &mut Sim, vcd_open: bool) -> Option<String> {
    let fast_forward = !a.no_fast_forward
        && p.cpu == CpuModel::Iss
        && p.main_bot == BotKind::Model
        && a.frames.is_none()
        && a.cpu_trace.is_none()
        && p.cpu_breaks.is_empty();
    let Sim::One(m) = model else { return None };
    if !fast_forward {
        m.fast_forward(FastForward::Off);
        return None;
    }
    // A waveform window later shows every variable: compare them all until then. A board
    // with another clock cannot; unless asked to, it skips as without a waveform, which then
    // shows what the run did not simulate as x.
    let mut mode = if a.vcd.is_some() { FastForward::Whole } else { FastForward::Recorded };
    let mut off = m.fast_forward_blocker().map(str::to_string);
    let mut on = off.is_none() && m.fast_forward(mode);
    if !on
        && off.is_none()
        && mode == FastForward::Whole
        && !vcd_open
        && !a.vcd_all_signals
        && m.unshown_unknown().is_none()
    {
        mode = FastForward::Recorded;
        on = m.fast_forward(mode);
        if on {
            a.say("note: the waveform shows x for the parts of the design the run does not record (another clock drives them, and they are not simulated before it); --vcd-all-signals simulates every edge to show them".into());
        }
    }
    if off.is_none() && !on {
        let why = match (mode, m.observed_unknown()) {
            (FastForward::Whole, _) => "a waveform later shows every variable".to_string(),
            (_, Some(unknown)) => format!("what a run observes of it is not known: {unknown}"),
            _ => "one besides the oscillator drives what the run records".to_string(),
        };
        off = Some(format!(
            "the board has {} clocks, and {why} (the fast-forward needs one clock, or others that drive only what the run does not record)",
            m.clocks().len()
        ));
    }
    if let Some(why) = &off {
        a.say(format!("note: no fast-forward: {why}; every clock edge is simulated"));
    }
    off
}

/// The board being run: one model, or the RTL and ISS boards in lock-step.
enum Sim {
    One(Box<BoardModel>),
    Pair(Box<Lockstep>),
}

impl Sim {
    fn main(&mut self) -> &mut BoardModel {
        match self {
            Sim::One(m) => m,
            Sim::Pair(p) => &mut p.rtl,
        }
    }
    fn run(&mut self, until: u64, samples: u64, buf: &mut [RawEvent]) -> Result<(Stop, usize), String> {
        match self {
            Sim::One(m) => Ok(m.run(until, samples, buf)),
            Sim::Pair(p) => p.run(until, samples, buf).map_err(|d| d.to_string()),
        }
    }
    fn set_inputs(&mut self, r: bool, b: u8, sw: u16) {
        match self {
            Sim::One(m) => m.set_inputs(r, b, sw),
            Sim::Pair(p) => p.set_inputs(r, b, sw),
        }
    }
    /// Do the same to every board (both of a lock-step run).
    fn each(&mut self, mut f: impl FnMut(&mut BoardModel)) {
        match self {
            Sim::One(m) => f(m),
            Sim::Pair(p) => {
                f(&mut p.rtl);
                f(&mut p.iss);
            }
        }
    }
    /// Send bytes to a device of every board (both take them alike).
    fn push(&mut self, device: Device, bytes: &[u8]) -> Pushed {
        match self {
            Sim::One(m) => m.push(device, bytes),
            Sim::Pair(p) => {
                let r = p.rtl.push(device, bytes);
                p.iss.push(device, bytes);
                r
            }
        }
    }
    fn record_vga(&mut self, on: bool) {
        match self {
            Sim::One(m) => m.record_vga(on),
            // Both boards' VGA pins are compared.
            Sim::Pair(p) => {
                p.rtl.record_vga(true);
                p.iss.record_vga(true);
            }
        }
    }
    /// Close the --cpu-trace files (the ISS board's).
    fn finish_traces(&mut self) -> Result<Vec<PathBuf>, String> {
        let m = match self {
            Sim::One(m) => m,
            Sim::Pair(p) => &mut p.iss,
        };
        m.host_mut().map_or(Ok(Vec::new()), Host::finish)
    }
    /// The breakpoint that stopped a CPU.
    fn hit(&self) -> Option<&botsim::board::iss::Hit> {
        match self {
            Sim::One(m) => m.host().and_then(Host::hit),
            Sim::Pair(p) => p.iss.host().and_then(Host::hit),
        }
    }
    /// A model error of a --cpu iss or lockstep run.
    fn check(&self) -> Result<(), String> {
        match self {
            Sim::One(m) => m.host().map_or(Ok(()), Host::check),
            Sim::Pair(p) => p.check().map_err(|e| e.to_string()),
        }
    }
}

/// The one line that says why a design stopped at `at` from its runtime's message `f` (the
/// user's paths already in it).
fn design_stopped(f: &str, built: &botsim::board::build::Built, at: &str) -> String {
    if f.contains("did not converge") {
        // Verilator names the loop when it builds the design (UNOPTFLAT).
        let looped = built.warnings.iter().find(|(code, _, _)| code == "UNOPTFLAT").map(|(_, _, first)| {
            let place = first.split(": ").next().unwrap_or("");
            let signal = first.rsplit('\'').nth(1).unwrap_or("").trim_start_matches("botsim_board.user.");
            format!("{place}: `{signal}` depends on itself (a combinational loop)")
        });
        return match looped {
            Some(l) => format!("{l}: the design never settles, stopped at {at}"),
            None => format!(
                "the design never settles (a combinational loop, or an always block with no event), stopped at {at}"
            ),
        };
    }
    if let Some(file) = f.strip_suffix(":0: $readmem file not found") {
        return format!("{file}: the design's $readmem cannot read this file (stopped at {at})");
    }
    format!("{f} (stopped at {at})")
}

/// Create the model of a built design on `world` with the programs of `roms`. The model reads
/// them from files as it starts: each is kept beside the build's library under a name its
/// contents give (`mem/<hash>.mem`), written once and read by every later run, so that a run
/// stopped while its model starts (a live page closed at once) leaves no file behind.
pub fn load(
    library: &Path,
    world: &World,
    roms: &[Rom],
    host: Option<Box<Host>>,
    printing: &Printing,
) -> Result<BoardModel, String> {
    let dir = library.parent().unwrap_or(Path::new(".")).join("mem");
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: error: cannot create folder: {e}", dir.display()))?;
    let mut files = vec![(world.to_mem(), "botsim_world".to_string())];
    for r in roms {
        files.push((r.image.to_mem(), wrapper::rom_plusarg(&r.module)));
    }
    let mut args = Vec::new();
    for (text, arg) in &files {
        let mut h = std::collections::hash_map::DefaultHasher::new();
        std::hash::Hash::hash(text, &mut h);
        let path = dir.join(format!("{:016x}.mem", std::hash::Hasher::finish(&h)));
        if std::fs::read(&path).ok().as_deref() != Some(text.as_bytes()) {
            write_atomic(&path, text.as_bytes())?;
        }
        args.push(format!("+{arg}={}", path.display()));
    }
    BoardModel::load(library, &args, host, printing).map_err(|e| e.to_string())
}

/// Stopped on the line with a wall straight ahead: the end of a course.
pub fn at_line_end(s: &Snapshot) -> bool {
    s.sensors().on_line()
        && s.sensors().prox_left()
        && s.sensors().prox_right()
        && s.movement() == botsim::Movement::Stopped
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn rows_written_by_hand_are_what_the_formatter_writes(
            time_ps in prop_oneof![0u64..10_000_000_000, any::<u64>().prop_map(|t| t >> 8), (0u64..100_000).prop_map(|k| k * 1_000_000 + 500_000)],
            an: u8, seg: u8, dp in 0u8..2, led: u16,
        ) {
            let mut row = String::new();
            pins_row(&mut row, time_ps, (an, seg, dp, led));
            prop_assert_eq!(row, format!("{time_ps},{an:02X},{seg:02X},{dp},{led:04X}\n"));
            let mut log = String::new();
            leds_row(&mut log, time_ps, led);
            prop_assert_eq!(log, format!("{:>12.3} ms  leds    {led:016b}\n", time_ps as f64 / 1e9));
        }
    }
}
