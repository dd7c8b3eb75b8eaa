//! `botsim board --live`: the board runs until the page or Ctrl-C stops it, paced against
//! the wall clock, with its inputs from the pages (botsim_live's server) and what it shows
//! published to them. Inputs take effect at the next cycle boundary of the board's clock and
//! are kept as a [`Stimulus`], so a session replays exactly with `--stimulus` (`--record`
//! writes it; the page's Save downloads it).
//!
//! VGA: simulating a frame costs about 420,000 pixel clocks, so the board runs with its VGA
//! part parked (as a run that records no frames does: only what the page shows is simulated,
//! and the fast-forward skips what repeats) and simulates the pixel path only for the frames
//! it shows: when an input or the bot (its place or heading, at a sample) may have changed
//! what the design draws, or while the picture changes by itself (an animation: the last
//! frame differed from the one before), at most [`FRAME_EVERY`] of wall time apart while the
//! board keeps its pace (a frame costs about one frame period of all-RTL simulation, 0.1 s on
//! the VGA example, 0.5 s on a Project 2 design with its 100 MHz system); a still picture, or
//! a board that cannot keep its pace, gets one every [`REFRESH_EVERY`]. At `--speed max`,
//! where a board is always on its pace, a frame also waits at least as long as the last one
//! took, so frames take at most half the wall time and a board that runs ahead of real time
//! between frames stays ahead. The pixel path is parked between frames in its vertical back
//! porch, so each frame goes on from there.

use std::time::{Duration, Instant};

use botsim::board::build::{BotKind, CpuModel};
use botsim::board::model::Device;
use botsim::board::model::{BoardModel, Event, FastForward, Printing, RawEvent, RECORDS};
use botsim::files::write_atomic;
use botsim::PS_PER_CYCLE;
use botsim_core::board::audio::RATE;
use botsim_core::board::display::Display;
use botsim_core::board::keyboard::{self, Key};
use botsim_core::board::stimulus::{parse_tilt, KeyPress, Press, Stimulus, FLAT, POWER_ON_RESET_PS};
use botsim_core::board::vga::Capture;
use botsim_core::frontend::pins::{Peripheral, Role};
use botsim_live::protocol::{BoardView, BotView, Button, Command};
use serde_json::json;

use super::devices::{Feeder, Heard};
use super::prepare::Prepared;
use super::session::load;
use super::Args;
use crate::cli::live::{bot_view, sample_entry, world_json, Pace, Rate};

/// The most board time one call into the model covers (then commands are looked at).
const CHUNK_PS: u64 = 20_000_000_000;
/// How often the pages get the state, at most (wall time).
const STATE_EVERY: Duration = Duration::from_millis(40);
/// The first line of a session's stimulus file.
const HEADER: &str = "botsim board --live: the inputs of a session (botsim board --stimulus FILE replays it)";
/// The least wall time between two VGA frames.
pub const FRAME_EVERY: Duration = Duration::from_millis(120);
/// The longest wall time between two frames when nothing the board knows of changed (what
/// a design draws from its own counters: a blinking cursor, an animation).
const REFRESH_EVERY: Duration = Duration::from_secs(1);
/// How much board time a Step covers on a board without a bot (which steps to the bot's
/// next sample): about one main-loop iteration of the course's firmware.
const STEP_PS: u64 = 50_000_000_000;
/// How much board time a frame may take to come (three frames at 60 Hz).
const FRAME_BUDGET_PS: u64 = 50_000_000_000;
/// How far a frame's simulation runs at a time: a frame ends at most this long before the
/// pixel path is parked again, well within the 35 lines of vertical sync and back porch
/// (0.72 ms at 1024 x 768, 1.1 ms at 640 x 480).
const FRAME_STEP_PS: u64 = 200_000_000;

/// What the live run keeps of the board.
struct Board {
    model: BoardModel,
    buf: Vec<RawEvent>,
    display: Display,
    leds: u16,
    samples: u64,
    /// When the bot's last sample came.
    sample_ps: u64,
    bot: Option<BotView>,
    /// The design's other bots: path and last sample.
    others: Vec<(String, Option<BotView>)>,
    vga: Capture,
    /// Inputs so far, as a stimulus; buttons held now have `to` = u64::MAX.
    inputs: Stimulus,
    /// Something the design may draw changed since the last frame: an input, or the bot
    /// since `drawn` (its registers at the last frame).
    dirty: bool,
    drawn: Option<BotView>,
    /// The last frame's pixels, and whether it differed from the one before (the design
    /// animates its picture by itself).
    last_pixels: Option<Vec<u16>>,
    animated: bool,
    /// Samples not yet in the pages' log.
    fresh: Vec<serde_json::Value>,
    /// The bytes waiting for the design's UART and keyboard, and when to try again.
    feeder: Feeder,
    feed_at: Option<u64>,
    /// What the design sent the host, and how much of it the pages have.
    heard: Heard,
    uart_told: usize,
}

/// An input the board cannot take, in one line for the page that sent it (the run goes on).
struct Refused(String);

/// Whether a live run keeps the pace asked for: how long it has been behind, and the VGA
/// frames of the last seconds (their wall time).
#[derive(Default)]
struct Lag {
    slow_since: Option<Instant>,
    frames: Vec<(Instant, Duration)>,
}

impl Lag {
    /// How long a run must stay behind before the page is told.
    const SAID_AFTER: Duration = Duration::from_secs(2);
    /// The wall time over which the frames' share is taken.
    const WINDOW: Duration = Duration::from_secs(3);

    /// The line for the page while the run, at `rate` x real time, has been under 90 % of
    /// `speed` for a while (`why` the rest of it); `None` on pace, paused or at full speed.
    fn behind(&mut self, speed: Option<f64>, rate: f64, why: impl FnOnce() -> String) -> Option<String> {
        let speed = speed?;
        if rate >= 0.9 * speed {
            self.slow_since = None;
            return None;
        }
        let since = *self.slow_since.get_or_insert_with(Instant::now);
        if since.elapsed() < Self::SAID_AFTER {
            return None;
        }
        self.frames.retain(|(at, _)| at.elapsed() < Self::WINDOW);
        let in_frames: Duration = self.frames.iter().map(|(_, d)| *d).sum();
        let reason = if !self.frames.is_empty() && in_frames.as_secs_f64() > 0.3 * Self::WINDOW.as_secs_f64() {
            format!(
                "its VGA frames take {:.2} s of wall time each (a frame is simulated edge by edge)",
                in_frames.as_secs_f64() / self.frames.len() as f64
            )
        } else {
            why()
        };
        Some(format!("{rate:.2} x real time, not the {speed} x asked: {reason}"))
    }
}

/// Why a board runs slower than real time, its frames aside: the fast-forward off, or what
/// kept it from skipping.
fn why_behind(a: &Args, p: &Prepared, model: &BoardModel, mode: FastForward) -> String {
    if mode == FastForward::Off {
        return match model.fast_forward_blocker() {
            Some(why) => format!("no fast-forward ({why})"),
            None if a.no_fast_forward => "no fast-forward (--no-fast-forward)".into(),
            None => "no fast-forward (it needs --cpu iss and the bot as a model, the defaults)".into(),
        };
    }
    match super::report::busy_of(p, &model.fast_forward_busy(), &model.fast_forward_cut()) {
        Some(b) => format!("{} keeps it from skipping ({})", b.describe(), b.why()),
        None => "what it runs does not repeat within reach".into(),
    }
}

/// Round `t` up to a cycle boundary.
fn aligned(t: u64) -> u64 {
    t.div_ceil(PS_PER_CYCLE) * PS_PER_CYCLE
}

pub fn run(a: &Args, p: &Prepared) -> Result<(), String> {
    if p.lockstep {
        return Err("--live runs one board: --cpu iss (the default) or rtl".into());
    }
    if a.stimulus.is_some() || !a.press.is_empty() {
        return Err("--live takes its inputs from the page (--switches sets where they start)".into());
    }
    let has_vga = p.plan.pins.iter().any(|(_, r)| *r == Role::Vsync);
    let hello = hello(a, p, has_vga);
    let server = a.live.serve(hello)?;
    let printing = Printing { log: a.design_log.clone(), lines: if a.quiet { 0 } else { 200 } };
    let mut model = load(&p.built.library, &p.world, &p.plan.roms, p.main_host()?, &printing)?;
    let skips = p.cpu == CpuModel::Iss && p.main_bot == BotKind::Model && !a.no_fast_forward;
    let skip_mode =
        if skips && model.fast_forward_blocker().is_none() { FastForward::Recorded } else { FastForward::Off };
    model.fast_forward(skip_mode);
    let mut b = new_board(a, p, model)?;
    let mut running = !a.live.paused;
    let mut pace = Pace::new(a.live.speed.0, 0);
    // A Step: to the bot's next sample (its count), or on a board without a bot to a time.
    let mut step_to: Option<u64> = None;
    let mut step_until: Option<u64> = None;
    let alone = p.plan.bot_path.is_none();
    let mut last_state = Instant::now() - STATE_EVERY;
    let mut last_frame: Option<Instant> = None;
    let mut frame_cost = Duration::ZERO;
    let mut frames: Vec<Instant> = Vec::new();
    let mut frames_shown = 0u64;
    let mut rate = Rate::new(0);
    let mut lag = Lag::default();
    let started = Instant::now();
    let mut stopped = false;
    while !stopped && !crate::cli::interrupted() {
        // The pages' commands, each at the next cycle boundary.
        let wait = if running { Duration::ZERO } else { Duration::from_millis(20) };
        let mut next = if wait.is_zero() { server.try_command() } else { server.command_within(wait) };
        while let Some((client, command)) = next.take() {
            let pages = Pages { server: &server, client };
            let at = b.model.time_ps();
            match command {
                Command::Run => {
                    running = true;
                    (step_to, step_until) = (None, None);
                    pace.restart(at);
                }
                Command::Pause => running = false,
                Command::Step => {
                    running = true;
                    if alone {
                        step_until = Some(aligned(at + STEP_PS));
                    } else {
                        step_to = Some(b.samples + 1);
                    }
                    pace.restart(at);
                }
                Command::Speed(f) => pace.set_speed(f, at),
                Command::Stop => stopped = true,
                other => b.answer(&pages, other),
            }
            next = server.try_command();
        }
        if stopped {
            break;
        }
        let now = b.model.time_ps();
        if running {
            // How far: to the pace's target (or a chunk at full speed), stopping at the
            // power-on reset's release and at the end of a step.
            let (target, on_pace) = pace.target(now, CHUNK_PS);
            // Bytes waiting for a device: the board stops when it may take more.
            let until = aligned(target).min(step_until.unwrap_or(u64::MAX)).min(b.feed_at.unwrap_or(u64::MAX));
            if until > now {
                let limit = step_to.unwrap_or(u64::MAX);
                b.run_to(until, limit)?;
            } else {
                std::thread::sleep(Duration::from_millis(2));
            }
            // (A frame may have taken the board past a step's end.)
            if step_to.is_some_and(|s| b.samples >= s) || step_until.is_some_and(|t| b.model.time_ps() >= t) {
                (running, step_to, step_until) = (false, None, None);
            }
            // A frame for the page when what it shows may have changed. Frames wait while
            // the board catches up with its pace (the pace first), but a board that cannot
            // keep it still shows one every REFRESH_EVERY.
            // At `--speed max` (no pace to keep: always on it) a frame also waits at least as
            // long as the last one took, so frames take at most half the wall time and a board
            // that outruns real time between frames keeps doing so with frames.
            let gap = if pace.speed().is_none() { frame_cost } else { Duration::ZERO };
            let due = last_frame.map_or(true, |f| {
                let changed = b.dirty || b.animated;
                let since = f.elapsed();
                (on_pace && since >= FRAME_EVERY.max(gap) && changed) || since >= REFRESH_EVERY.max(gap)
            });
            if has_vga && due {
                let (t0, s0) = (b.model.time_ps(), b.bot.as_ref().map(|v| v.sample));
                let began = Instant::now();
                let made = b.frame(skip_mode)?;
                frame_cost = began.elapsed();
                lag.frames.push((began, frame_cost));
                if let Some(frame) = made {
                    // The bot's last sample when the frame began and when it ended: equal,
                    // the frame shows the bot as that sample left it, unless the CPU reset
                    // was held since that sample (the bot's registers reset, no sample yet
                    // of the bot after it): then the frame shows no sample's bot.
                    let s1 = b.bot.as_ref().map(|v| v.sample);
                    let s0 = s0.filter(|_| !b.reset_since_sample());
                    server.frame(
                        frame,
                        json!({"from_ps": t0, "time_ps": b.model.time_ps(), "sample_from": s0, "sample": s1}),
                    );
                    let now = Instant::now();
                    frames.push(now);
                    frames_shown += 1;
                    frames.retain(|f| now.duration_since(*f) < Duration::from_secs(3));
                    last_frame = Some(now);
                }
            }
        }
        b.feed();
        b.tell_heard();
        for entry in b.fresh.drain(..) {
            server.log(entry);
        }
        if last_state.elapsed() >= STATE_EVERY {
            let t = b.model.time_ps();
            let frame_rate = if frames.len() < 2 {
                0.0
            } else {
                (frames.len() - 1) as f64 / frames[frames.len() - 1].duration_since(frames[0]).as_secs_f64().max(1e-3)
            };
            let now_rate = rate.at(t);
            let behind = lag
                .behind(running.then_some(pace.speed()).flatten(), now_rate, || why_behind(a, p, &b.model, skip_mode));
            let mut view = b.view(running, pace.speed(), now_rate, frame_rate);
            view.behind = behind;
            server.state(view);
            last_state = Instant::now();
        }
    }
    let t = b.model.time_ps();
    server.state(b.view(false, pace.speed(), 0.0, 0.0));
    server.close();
    if let Some(f) = &a.live.record {
        write_atomic(f, b.inputs.text(t, HEADER).as_bytes())?;
    }
    if !a.quiet {
        eprintln!("{}", summary(a, &b, has_vga, alone, frames_shown, started.elapsed().as_secs_f64()));
    }
    // Give the pages a moment to hear that the run ended.
    std::thread::sleep(Duration::from_millis(100));
    Ok(())
}

/// The `hello` every page gets first: the design, its board, its world and peripherals.
fn hello(a: &Args, p: &Prepared, has_vga: bool) -> serde_json::Value {
    let sources: Vec<String> = a.sources.iter().map(|s| s.display().to_string()).collect();
    let has = |x: Peripheral| p.plan.pins.iter().any(|(_, r)| r.peripheral() == Some(x));
    // (prepare checked it.)
    let tilt = a.tilt.as_deref().and_then(|t| parse_tilt(t).ok());
    json!({
        "vga": has_vga,
        "peripherals": {
            "uart": has(Peripheral::Uart),
            "keyboard": has(Peripheral::Keyboard),
            "accelerometer": has(Peripheral::Accelerometer),
            "audio": has(Peripheral::Audio),
        },
        "tilt": tilt.unwrap_or(FLAT).map(|mg| mg as f64 / 1000.0),
        "design": {"top": p.plan.top, "sources": sources.join(" ")},
        "board": face(&p.plan),
        "world": p.plan.bot_path.as_ref().map(|_| world_json(&p.world)),
        "mode": "board",
        "protocol": 1,
    })
}

/// The board at power-up: the loaded model with the inputs the arguments start it with.
fn new_board(a: &Args, p: &Prepared, model: BoardModel) -> Result<Board, String> {
    let has_audio = p.plan.pins.iter().any(|(_, r)| r.peripheral() == Some(Peripheral::Audio));
    let mut inputs = Stimulus::default();
    if let Some(h) = &a.switches {
        inputs.initial_switches = u16::from_str_radix(h.trim_start_matches("0x"), 16)
            .map_err(|_| format!("--switches {h}: expected up to four hexadecimal digits"))?;
    }
    // (prepare checked it.)
    if let Some(t) = a.tilt.as_deref().and_then(|t| parse_tilt(t).ok()) {
        inputs.tilts.push((0, t));
    }
    let mut b = Board {
        model,
        buf: vec![RawEvent::default(); RECORDS],
        display: Display::default(),
        leds: 0,
        samples: 0,
        sample_ps: 0,
        bot: None,
        others: p.plan.other_bots.iter().map(|b| (format!("{}.{}", p.plan.top, b.path), None)).collect(),
        vga: Capture::default(),
        inputs,
        dirty: true,
        drawn: None,
        last_pixels: None,
        animated: false,
        fresh: Vec::new(),
        feeder: Feeder::default(),
        feed_at: None,
        heard: Heard::new(a.uart_baud, has_audio),
        uart_told: 0,
    };
    let (r, btn, sw) = b.inputs.inputs_at(0);
    b.model.set_inputs(r, btn, sw);
    b.model.set_uart_div(b.heard.uart_div);
    let [x, y, z] = b.inputs.tilt_at(0);
    b.model.set_tilt(x, y, z);
    Ok(b)
}

/// The page a command came from, to answer it alone.
struct Pages<'a> {
    server: &'a botsim_live::server::Server,
    client: botsim_live::server::ClientId,
}

/// The run's last line: how far it ran, how fast, what it showed and kept.
fn summary(a: &Args, b: &Board, has_vga: bool, alone: bool, frames_shown: u64, wall: f64) -> String {
    let t = b.model.time_ps();
    let recorded = a.live.record.as_ref().map_or(String::new(), |f| format!("; its inputs in {}", f.display()));
    let shown = if has_vga {
        format!(", {frames_shown} VGA frames ({:.1}/s)", frames_shown as f64 / wall)
    } else {
        String::new()
    };
    let samples = if alone { String::new() } else { format!(", {} samples", b.samples) };
    format!(
        "botsim board --live: ran {:.3} s of board time in {wall:.1} s ({:.2} x real time){samples}{shown}{recorded}",
        t as f64 / 1e12,
        t as f64 / 1e12 / wall,
    )
}

impl Board {
    /// Run the board to `until` (or the `limit`-th sample), taking what it shows; the
    /// power-on reset is released on the way, as in a run.
    fn run_to(&mut self, until: u64, limit: u64) -> Result<(), String> {
        if self.model.time_ps() < POWER_ON_RESET_PS && until > POWER_ON_RESET_PS {
            self.run_to(POWER_ON_RESET_PS, limit)?;
            if self.model.time_ps() < POWER_ON_RESET_PS {
                return Ok(()); // the limit came first
            }
        }
        let released = self.model.time_ps() < POWER_ON_RESET_PS && until == POWER_ON_RESET_PS;
        loop {
            let (stop, n) = self.model.run(until, limit, &mut self.buf);
            let events: Vec<Event> = self.buf[..n].iter().filter_map(Event::of).collect();
            for (i, &e) in events.iter().enumerate() {
                match e {
                    Event::Repeat { events: per, period_ps, count, .. } => {
                        self.repeat(&events[i - per..i], period_ps, count)
                    }
                    e => self.take(e),
                }
            }
            match stop {
                botsim::board::model::Stop::BufferFull => continue,
                botsim::board::model::Stop::Finished => {
                    return Err(match self.model.fatal() {
                        Some(f) => format!("{f} (the design stopped at {:.6} ms)", self.model.time_ps() as f64 / 1e9),
                        None => format!("the design called $finish at {:.6} ms", self.model.time_ps() as f64 / 1e9),
                    })
                }
                _ => {
                    if released && self.model.time_ps() == POWER_ON_RESET_PS {
                        let (r, b, s) = self.inputs.inputs_at(POWER_ON_RESET_PS);
                        self.model.set_inputs(r, b, s);
                    }
                    return self.model.host().map_or(Ok(()), |h| h.check());
                }
            }
        }
    }

    /// Whether the CPU reset was held at some time from the bot's last sample to now.
    fn reset_since_sample(&self) -> bool {
        let now = self.model.time_ps();
        self.inputs.presses.iter().any(|p| p.button.is_none() && p.to > self.sample_ps && p.from <= now)
    }

    fn take(&mut self, e: Event) {
        match e {
            Event::Display { time_ps, an, seg, dp } => self.display.pins(time_ps, an, seg, dp),
            Event::Leds { leds, .. } => self.leds = leds,
            Event::Sample { time_ps, snapshot, motctl } => {
                self.samples += 1;
                self.sample_ps = time_ps;
                let view = bot_view(&snapshot, motctl.0);
                self.fresh.push(sample_entry(time_ps, &snapshot, &view));
                // What a design draws of the bot: where it is and where it heads.
                let moved = |b: &BotView| (b.x, b.y, b.info) != (view.x, view.y, view.info);
                self.dirty |= self.drawn.as_ref().map_or(true, moved);
                self.bot = Some(view);
            }
            Event::Vga { time_ps, pins } => self.vga.pins(time_ps, pins),
            Event::Lines { time_ps, lines } => self.heard.lines(time_ps, lines),
            Event::OtherSample { bot, snapshot, motctl, .. } => {
                let view = bot_view(&snapshot, motctl.0);
                if let Some(o) = self.others.get_mut(bot - 1) {
                    self.dirty |= o.1.as_ref().map_or(true, |b| (b.x, b.y, b.info) != (view.x, view.y, view.info));
                    o.1 = Some(view);
                }
            }
            Event::Bot { .. } | Event::Repeat { .. } => {}
        }
    }

    /// One period's events (`period`, already taken) happen `count` more times, each
    /// `period_ps` after the last: the display decoder takes them whole, the LEDs end as
    /// the period ends.
    fn repeat(&mut self, period: &[Event], period_ps: u64, count: u64) {
        let mut pins = Vec::new();
        for e in period {
            match *e {
                Event::Display { time_ps, an, seg, dp } => pins.push((time_ps, an, seg, dp)),
                Event::Leds { leds, .. } => self.leds = leds,
                e => {
                    for j in 1..=count {
                        self.take(e.later(j * period_ps));
                    }
                }
            }
        }
        self.display.repeat(&pins, period_ps, count);
    }

    /// Run on to the next cycle boundary (a step may have stopped between two): the time at
    /// which an input takes effect.
    fn align(&mut self) -> Result<u64, String> {
        let t = aligned(self.model.time_ps());
        if t > self.model.time_ps() {
            self.run_to(t, u64::MAX)?;
        }
        Ok(self.model.time_ps())
    }

    /// Push what the devices take now; what the design sent the host since, for the pages
    /// (the UART's rate, once measured, is the host's too).
    fn feed(&mut self) {
        let t = self.model.time_ps();
        if self.feed_at.map_or(true, |f| f <= t) {
            let model = &mut self.model;
            self.feed_at = self.feeder.feed(t, |d, bytes| model.push(d, bytes));
        }
    }

    /// What the design sent the host since the pages were last told: its UART's bytes, and
    /// its sound (48 kHz samples of the line's average, 0 to 255).
    fn tell_heard(&mut self) {
        let t = self.model.time_ps();
        self.heard.uart.flush(t);
        if let Some(div) = self.heard.new_uart_div() {
            self.model.set_uart_div(div);
        }
        let got = &self.heard.uart.received;
        if got.len() > self.uart_told {
            let text = botsim_core::board::uart::text(got[self.uart_told..].iter().map(|r| r.byte));
            let baud = self.heard.uart.baud().map(|b| b.0);
            self.fresh
                .push(json!({"kind": "uart", "time_ps": got[self.uart_told].time_ps, "text": text, "baud": baud}));
            self.uart_told = got.len();
        }
        if let Some(audio) = &mut self.heard.audio {
            audio.finish(t);
            let (first, samples) = audio.take();
            if !samples.is_empty() && audio.heard() {
                let pcm: Vec<u8> = samples.iter().map(|&v| (v * 255.0).round() as u8).collect();
                self.fresh.push(json!({"kind": "audio", "first": first, "rate": RATE, "samples": pcm}));
            }
        }
    }

    /// A page's command that is not about running: an input (applied, and logged for every
    /// page, or refused to that page), the inputs so far, or the motors a board does not take.
    fn answer(&mut self, pages: &Pages, command: Command) {
        let reply = |message: serde_json::Value| pages.server.reply(pages.client, message);
        match command {
            Command::Save => reply(json!({"type": "stimulus", "text": self.inputs.text(self.model.time_ps(), HEADER)})),
            Command::Motors(_) => reply(
                json!({"type": "error", "message": "the board's motors are its design's: use the switches and buttons"}),
            ),
            command => match self.input(&command) {
                Ok(entry) => pages.server.log(entry),
                Err(Refused(message)) => reply(json!({"type": "error", "message": message})),
            },
        }
    }

    /// Apply an input from a page at the next cycle boundary (a release one cycle after its
    /// press, at the least); the log entry that says so.
    fn input(&mut self, command: &Command) -> Result<serde_json::Value, Refused> {
        // The peripherals' inputs first: checked, then at the next cycle boundary.
        let key = match command {
            Command::Key { code, .. } => Some(Key::named(code).ok_or_else(|| Refused(keyboard::unknown(code)))?),
            _ => None,
        };
        let mut t = self.align().map_err(Refused)?;
        match command {
            Command::Key { down, .. } => {
                let key = key.expect("checked above");
                let held = self.inputs.keys.iter_mut().find(|k| k.key == key && k.to == u64::MAX);
                match (held, *down) {
                    (None, true) => self.inputs.keys.push(KeyPress { key, from: t, to: u64::MAX }),
                    (Some(k), false) => k.to = t,
                    // A key held down repeats nothing (typematic repeat is optional); a release of
                    // a key not held sends nothing.
                    _ => {
                        return Ok(json!({"kind": "input", "time_ps": t, "key": key.name, "down": down, "sent": false}))
                    }
                }
                self.feeder.send(Device::Keyboard, &keyboard::codes(key, *down));
                self.feed_at = Some(t);
                self.dirty = true;
                return Ok(json!({"kind": "input", "time_ps": t, "key": key.name, "down": down}));
            }
            Command::Uart(bytes) => {
                self.inputs.uart.push((t, bytes.clone()));
                self.feeder.send(Device::Uart, bytes);
                self.feed_at = Some(t);
                self.dirty = true;
                return Ok(json!({"kind": "input", "time_ps": t, "uart": String::from_utf8_lossy(bytes)}));
            }
            Command::Tilt(g) => {
                let tilt = g.map(|v| (v * 1000.0).round() as i32);
                self.inputs.tilts.push((t, tilt));
                self.model.set_tilt(tilt[0], tilt[1], tilt[2]);
                self.dirty = true;
                return Ok(json!({"kind": "input", "time_ps": t, "tilt": g}));
            }
            _ => {}
        }
        if let Command::Button { button, down: false } = *command {
            let bit = botsim_core::board::stimulus::button_bit(button.name());
            if self.inputs.presses.iter().any(|p| p.button == bit && p.to == u64::MAX && p.from == t) {
                self.run_to(t + PS_PER_CYCLE, u64::MAX).map_err(Refused)?;
                t = self.model.time_ps();
            }
        }
        let (_, _, switches) = self.inputs.inputs_at(t);
        let entry = match *command {
            Command::Switch { index, on } => {
                let v = if on { switches | 1 << index } else { switches & !(1 << index) };
                self.inputs.switches.push((t, v));
                json!({"kind": "input", "time_ps": t, "switches": v})
            }
            Command::Switches(v) => {
                self.inputs.switches.push((t, v));
                json!({"kind": "input", "time_ps": t, "switches": v})
            }
            Command::Button { button, down } => {
                let bit = match button {
                    Button::CpuReset => None,
                    b => botsim_core::board::stimulus::button_bit(b.name()),
                };
                let held = self.inputs.presses.iter_mut().find(|p| p.button == bit && p.to == u64::MAX);
                match (held, down) {
                    (None, true) => self.inputs.presses.push(Press { button: bit, from: t, to: u64::MAX }),
                    (Some(p), false) => p.to = t,
                    _ => {}
                }
                json!({"kind": "input", "time_ps": t, "button": button.name(), "down": down})
            }
            _ => json!({}),
        };
        let (r, b, s) = self.inputs.inputs_at(t);
        self.model.set_inputs(r, b, s);
        self.dirty = true;
        Ok(entry)
    }

    /// Simulate the VGA part until it completes a frame: the fast-forward off and the pixel
    /// path running from where it was parked, the frame taken, then back as it was. A frame
    /// runs from one vertical sync to the next; the pixel path is parked again within
    /// [`FRAME_STEP_PS`] of the sync that ended it (in the sync and back porch, before the
    /// next frame's picture), so the next frame goes on from there: about one frame period of
    /// simulation per frame shown, where starting afresh costs up to two. (When the pixel
    /// path runs on while parked, on the board's own clock, the capture loses that frame and
    /// takes the next.)
    fn frame(&mut self, skip_mode: FastForward) -> Result<Option<Vec<u8>>, String> {
        self.model.fast_forward(FastForward::Off);
        self.model.record_vga(true);
        let end = aligned(self.model.time_ps() + FRAME_BUDGET_PS);
        let mut frame = None;
        while frame.is_none() && self.model.time_ps() < end {
            let until = aligned(self.model.time_ps() + FRAME_STEP_PS).min(end);
            self.run_to(until, u64::MAX)?;
            frame = self.vga.take().pop();
        }
        self.model.record_vga(false);
        self.model.fast_forward(skip_mode);
        self.dirty = false;
        self.drawn = self.bot.clone();
        Ok(frame.map(|f| {
            self.animated = self.last_pixels.as_ref().is_some_and(|p| *p != f.pixels);
            let png = f.png();
            self.last_pixels = Some(f.pixels);
            png
        }))
    }

    fn view(&self, running: bool, speed: Option<f64>, rate: f64, frame_rate: f64) -> BoardView {
        let t = self.model.time_ps();
        let (reset, buttons, switches) = self.inputs.inputs_at(t);
        let mut pressed = 0u8;
        for b in Button::ALL {
            let on = match b {
                Button::CpuReset => reset && t >= POWER_ON_RESET_PS,
                b => botsim_core::board::stimulus::button_bit(b.name()).is_some_and(|bit| buttons >> bit & 1 == 1),
            };
            if on {
                pressed |= b.bit();
            }
        }
        let line = self.display.lines().last();
        BoardView {
            time_ps: t,
            rate,
            running,
            speed,
            leds: self.leds,
            switches,
            buttons: pressed,
            digits: line.map_or([0; 8], |l| l.lit),
            text: line.map_or(String::new(), |l| l.text.clone()),
            samples: self.samples,
            bot: self.bot.clone(),
            others: self.others.clone(),
            frame_rate,
            motors: None,
            behind: None,
        }
    }
}

/// The board the page draws: the one the design's constraint file places its pins on, else
/// the one its pins are shaped for (a Nexys3's four digits and eight switches and LEDs, the
/// Nexys4 DDR's upper-case names); its controls' counts, its buttons (botsim's names, which the
/// commands use, with the board's labels: a Nexys3's centre button `BTNS` is its reset) and
/// its name.
fn face(plan: &botsim_core::frontend::plan::Plan) -> serde_json::Value {
    use botsim_core::frontend::constraints::Board;
    let width = |role: Role| {
        plan.pins.iter().find(|(_, r)| *r == role).and_then(|(n, _)| plan.widths.get(n)).copied().unwrap_or(0)
    };
    let upper = plan
        .pins
        .iter()
        .any(|(n, r)| matches!(r, Role::Button(_) | Role::Reset { .. }) && n.chars().all(|c| !c.is_ascii_lowercase()));
    let board =
        plan.board.unwrap_or(if width(Role::Anodes) == 4 || (width(Role::Switches) == 8 && width(Role::Leds) <= 8) {
            Board::Nexys3
        } else if upper {
            Board::Nexys4Ddr
        } else {
            Board::Nexys4
        });
    match board {
        Board::Nexys3 => json!({
            "name": "NEXYS3", "digits": 4, "leds": 8, "switches": 8,
            "buttons": [["btnCpuReset", "BTNS"], ["btnU", "BTNU"], ["btnL", "BTNL"], ["btnR", "BTNR"], ["btnD", "BTND"]],
        }),
        Board::Nexys4 | Board::Nexys4Ddr => json!({
            "name": if board == Board::Nexys4 { "NEXYS4" } else { "NEXYS4 DDR" },
            "digits": 8, "leds": 16, "switches": 16,
            "buttons": [["btnCpuReset", "CPU RESET"], ["btnU", "BTNU"], ["btnL", "BTNL"], ["btnC", "BTNC"], ["btnR", "BTNR"], ["btnD", "BTND"]],
        }),
    }
}
