//! `botsim board --cpu lockstep`: the all-RTL board and the ISS board side by side, stopped at
//! the first difference in any board pin the harness watches (display, LEDs, VGA, the bot's
//! registers and upd_sysregs: every change with its time) or in any port of any KCPSM6 in any
//! cycle (the RTL cores through kcpsm6_probe.v, the models through their own record).

use botsim_core::frontend::BoardError;

use botsim_core::frontend::plan::BOT_CPU_INSTANCE;

use super::iss::{Host, Recorded};
use super::model::{expand, BoardModel, Event, Lines, RawEvent, Stop, RECORDS};

/// The most simulated time the two boards run apart between comparisons (1 ms: 100,000
/// cycles of 100 MHz, a few MB of recorded ports).
const STRIDE_PS: u64 = 1_000_000_000;

/// Two boards in lock-step.
pub struct Lockstep {
    pub rtl: BoardModel,
    pub iss: BoardModel,
    buf: Vec<RawEvent>,
    /// Cycles compared so far, per KCPSM6 (in the hosts' order).
    cycles: Vec<u64>,
}

/// Where the two boards first differ.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Divergence {
    pub time_ps: u64,
    pub what: String,
}

impl std::fmt::Display for Divergence {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "--cpu lockstep: the RTL and ISS boards differ at {:.6} ms: {}", self.time_ps as f64 / 1e9, self.what)
    }
}

/// The fields of a KCPSM6's packed (pins, outputs), as kcpsm6_iss.v packs them.
fn fields(pins: u64, state: u64) -> [(&'static str, u64); 14] {
    let bits = |v: u64, lo: u32, n: u32| v >> lo & ((1 << n) - 1);
    [
        ("instruction", bits(pins, 0, 18)),
        ("in_port", bits(pins, 18, 8)),
        ("interrupt", bits(pins, 26, 1)),
        ("sleep", bits(pins, 27, 1)),
        ("reset", bits(pins, 28, 1)),
        ("address", bits(state, 0, 12)),
        ("bram_enable", bits(state, 12, 1)),
        ("out_port", bits(state, 13, 8)),
        ("port_id", bits(state, 21, 8)),
        ("write_strobe", bits(state, 29, 1)),
        ("k_write_strobe", bits(state, 30, 1)),
        ("read_strobe", bits(state, 31, 1)),
        ("interrupt_ack", bits(state, 32, 1)),
        ("(unused)", state >> 33),
    ]
}

impl Lockstep {
    /// Two models of one design: `rtl` built with [`super::build::CpuModel::RtlProbed`] and
    /// `iss` with [`super::build::CpuModel::Iss`], each with a recording [`Host`].
    pub fn new(mut rtl: BoardModel, mut iss: BoardModel) -> Lockstep {
        rtl.record_bot(true);
        iss.record_bot(true);
        Lockstep { rtl, iss, buf: vec![RawEvent::default(); RECORDS], cycles: Vec::new() }
    }

    /// Both boards' inputs.
    pub fn set_inputs(&mut self, reset_pressed: bool, buttons: u8, switches: u16) {
        self.rtl.set_inputs(reset_pressed, buttons, switches);
        self.iss.set_inputs(reset_pressed, buttons, switches);
    }

    /// Run as [`BoardModel::run`] does (the records are the RTL board's), at most 1 ms at a
    /// time, then compare.
    pub fn run(
        &mut self,
        until_ps: u64,
        stop_after_samples: u64,
        buf: &mut [RawEvent],
    ) -> Result<(Stop, usize), Divergence> {
        let until = until_ps.min(self.rtl.time_ps().saturating_add(STRIDE_PS));
        let (stop, n) = self.rtl.run(until, stop_after_samples, buf);
        let t = self.rtl.time_ps();
        let mut theirs = Vec::with_capacity(n);
        loop {
            let (s, m) = self.iss.run(t, stop_after_samples, &mut self.buf);
            let events: Vec<Event> = self.buf[..m].iter().filter_map(Event::of).collect();
            theirs.extend(expand(&events));
            if s != Stop::BufferFull || self.iss.time_ps() >= t {
                break;
            }
        }
        // The CPUs first: a difference in their ports comes before what it causes.
        self.compare_ports()?;
        let ours: Vec<Event> = expand(&buf[..n].iter().filter_map(Event::of).collect::<Vec<_>>());
        if let Some(k) = (0..ours.len().max(theirs.len())).find(|&k| ours.get(k) != theirs.get(k)) {
            let time_ps = [ours.get(k), theirs.get(k)].into_iter().flatten().map(Event::time_ps).min().unwrap_or(t);
            return Err(Divergence {
                time_ps,
                what: format!(
                    "the board showed {} on the RTL board, {} on the ISS board",
                    show(ours.get(k)),
                    show(theirs.get(k))
                ),
            });
        }
        if self.iss.time_ps() != t {
            return Err(Divergence { time_ps: t, what: format!("the ISS board stopped at {} ps", self.iss.time_ps()) });
        }
        Ok((stop, n))
    }

    /// The KCPSM6 ports of the cycles since the last comparison.
    fn compare_ports(&mut self) -> Result<(), Divergence> {
        let ours = self.rtl.host_mut().map(Host::take).unwrap_or_default();
        let theirs = self.iss.host_mut().map(Host::take).unwrap_or_default();
        // With --bot model the ISS board's bot has no KCPSM6 of its own: its outputs are
        // compared as board events instead.
        let modelled = self.iss.host().is_some_and(Host::models_bot);
        let ours: Vec<Recorded> =
            ours.into_iter().filter(|r| !(modelled && r.path.rsplit('.').next() == Some(BOT_CPU_INSTANCE))).collect();
        self.cycles.resize(ours.len().max(theirs.len()), 0);
        let now = self.rtl.time_ps();
        for (i, (x, y)) in ours.iter().zip(&theirs).enumerate() {
            let (path, a, b) = (&x.path, &x.cycles, &y.cycles);
            if let Some(k) = (0..a.len().max(b.len())).find(|&k| a.get(k) != b.get(k)) {
                let time_ps = x.times.get(k).copied().unwrap_or(now);
                let cycle = self.cycles[i] + k as u64;
                let what = match (a.get(k), b.get(k)) {
                    (Some(&(pa, sa)), Some(&(pb, sb))) => {
                        let diffs: Vec<String> = fields(pa, sa)
                            .iter()
                            .zip(fields(pb, sb))
                            .filter(|(x, y)| x.1 != y.1)
                            .map(|(x, y)| format!("{} {:X} on the RTL, {:X} on the ISS", x.0, x.1, y.1))
                            .collect();
                        format!("KCPSM6 `{path}` in its cycle {cycle}: {}", diffs.join(", "))
                    }
                    _ => format!("KCPSM6 `{path}`: {} cycles on the RTL, {} on the ISS", a.len(), b.len()),
                };
                return Err(Divergence { time_ps, what });
            }
            self.cycles[i] += a.len() as u64;
        }
        if ours.len() != theirs.len() {
            return Err(Divergence {
                time_ps: now,
                what: format!("{} KCPSM6 instances on the RTL board, {} on the ISS board", ours.len(), theirs.len()),
            });
        }
        Ok(())
    }

    /// The first model error of either board.
    pub fn check(&self) -> Result<(), BoardError> {
        for m in [&self.rtl, &self.iss] {
            if let Some(h) = m.host() {
                h.check().map_err(BoardError::plain)?;
            }
        }
        Ok(())
    }
}

fn show(e: Option<&Event>) -> String {
    match e {
        None => "nothing".into(),
        Some(Event::Display { an, seg, dp, .. }) => format!("display an={an:08b} seg={seg:07b} dp={}", *dp as u8),
        Some(Event::Leds { leds, .. }) => format!("LEDs {leds:016b}"),
        Some(Event::Sample { snapshot, motctl, .. }) => {
            format!("bot sample {} {:?} MotCtl {:02X}", snapshot.sample, snapshot.regs, motctl.0)
        }
        Some(Event::OtherSample { bot, snapshot, motctl, .. }) => {
            format!("bot {bot}'s sample {} {:?} MotCtl {:02X}", snapshot.sample, snapshot.regs, motctl.0)
        }
        Some(Event::Vga { pins, .. }) => format!("VGA pins {pins:04X}"),
        Some(Event::Bot { upd, regs, .. }) => {
            format!("the bot's outputs upd_sysregs {} registers {regs:012X} (RMDist..LocX)", *upd as u8)
        }
        Some(Event::Repeat { events, count, .. }) => format!("the last {events} records repeated {count} times"),
        Some(Event::Lines { lines, .. }) => {
            let each: Vec<String> =
                Lines::NAMES.iter().enumerate().map(|(k, n)| format!("{n} {}", lines.bit(k) as u8)).collect();
            format!("the peripherals' lines {}", each.join(" "))
        }
    }
}
