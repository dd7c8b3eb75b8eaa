//! BotSim on the instruction-set simulator: the same firmware image on [`kcpsm6::iss::Cpu`],
//! with Rust models of `world_if` and `map` that follow the RTL's cycle timing, so every
//! snapshot (and its cycle) equals the RTL's.
//!
//! Timing reproduced (spec §8, §9): world_if's read mux is a register (an INPUT whose strobe
//! is in cycle t reads the state of cycle t-1); the map registers its address and its output
//! (a map value read in cycle t comes from MapX/MapY of cycle t-3); writes land at the end of
//! their strobe cycle; ports 0C/0D/0E toggle their flags, the visible registers copy the holding
//! registers every cycle while a flag is high, and upd_sysregs is high from the cycle after a
//! rising toggle.
//!
//! The `botsim` crate's lock-step compares every snapshot and every port access (with its
//! cycle) with the RTL, on the firmware and on random programs that read every port at every distance
//! after writing it. Port strobes come in the second cycle of an instruction, so two strobes
//! are always an even number of cycles apart: a bus-to-bus latency that is one clock off is
//! invisible to every program (the lock-step cannot fail on it, and no user can see it),
//! while two clocks off fails it. MotCtl, set from outside at any cycle, is pinned to the
//! clock.
//!
//! ```
//! use botsim_core::sim::iss::IssBot;
//! use botsim_core::{Firmware, MotCtl, Timing, World};
//! let fw = Firmware { timing: Timing::Fast, ..Firmware::default() };
//! let mut bot = IssBot::new(&fw.assemble().unwrap(), World::builtin()).unwrap();
//! assert_eq!(bot.wait_update_within(10_000).unwrap().location(), (64, 64));
//! bot.set_motors(MotCtl::FORWARD);
//! let s: Vec<_> = (0..16).map(|_| bot.wait_update_within(10_000).unwrap()).collect();
//! assert_eq!(s[15].location(), (65, 64));
//! ```

use kcpsm6::iss::{Bus, Config, Cpu, Routines};
use kcpsm6::Image;

use super::{check_program_size, Backend, CpuAt, Error, PortEvent, PortKind, BOT_ROM_WORDS};
use crate::firmware::Timing;
use crate::ports;
use crate::regs::{MotCtl, Registers, Snapshot};
use crate::world::World;

/// A register written through the port bus: its value before and after the last write.
#[derive(Clone, Copy, Debug, Default)]
struct Timed {
    before: u8,
    after: u8,
    /// The strobe cycle of the last write (the new value holds from the next cycle).
    written: u64,
}

impl Timed {
    fn write(&mut self, v: u8, cycle: u64) {
        self.before = self.value_at(cycle);
        self.after = v;
        self.written = cycle;
    }

    /// The value during `cycle`.
    fn value_at(&self, cycle: u64) -> u8 {
        if cycle > self.written {
            self.after
        } else {
            self.before
        }
    }
}

/// world_if and map as the CPU's bus sees them.
struct WorldIf {
    world: World,
    motctl: Timed,
    map_x: Timed,
    map_y: Timed,
    holding: [u8; 7],
    visible: Registers,
    load_sys: bool,
    load_dist: bool,
    upd: bool,
    /// Set when upd_sysregs rises: the first cycle it is high.
    pulse: Option<u64>,
    /// Every port access, when recording (lock-step runs).
    events: Option<Vec<PortEvent>>,
    /// The cycle of the first write since it was cleared that changes the outputs
    /// ([`IssBot::next_write`]).
    written: Option<u64>,
}

impl WorldIf {
    fn record(&mut self, cycle: u64, kind: PortKind, port: u8, value: u8) {
        if let Some(v) = self.events.as_mut() {
            v.push(PortEvent { kind, port, value, cycle });
        }
    }
}

impl WorldIf {
    /// Bring the visible registers up to the start of `cycle`: while a load flag is high they
    /// copy the holding registers every cycle, and the holding registers only change at the
    /// end of write strobes, which are at least two cycles apart.
    fn catch_up(&mut self) {
        let h = |p: u8| self.holding[p as usize];
        if self.load_sys {
            self.visible.loc_x = h(ports::PWR_LOCX);
            self.visible.loc_y = h(ports::PWR_LOCY);
            self.visible.bot_info = h(ports::PWR_BOTINFO);
            self.visible.sensors = h(ports::PWR_SENSORS);
        }
        if self.load_dist {
            self.visible.lm_dist = h(ports::PWR_LMDIST);
            self.visible.rm_dist = h(ports::PWR_RMDIST);
        }
    }
}

impl Bus for WorldIf {
    fn input(&mut self, port: u8, cycle: u64) -> u8 {
        let v = self.read(port, cycle);
        self.record(cycle, PortKind::Read, port, v);
        v
    }

    fn output(&mut self, port: u8, value: u8, cycle: u64) {
        self.record(cycle, PortKind::Write, port, value);
        if self.shows(port) {
            self.written.get_or_insert(cycle);
        }
        self.write(port, value, cycle);
    }

    fn output_k(&mut self, port: u8, value: u8, cycle: u64) {
        self.record(cycle, PortKind::KWrite, port, value);
    }
}

impl WorldIf {
    /// world_if's reset at an edge: the holding and visible registers, the toggles and
    /// upd_sysregs clear (the map address registers do not).
    fn reset(&mut self) {
        self.holding = [0; 7];
        self.visible = Registers::default();
        (self.load_sys, self.load_dist, self.upd) = (false, false, false);
    }

    /// Would a write to `port` now change world_if's outputs (a toggle, or a holding register
    /// while its visible register copies it)? The map's address registers only change what
    /// the firmware reads.
    fn shows(&self, port: u8) -> bool {
        match port & 15 {
            ports::PRW_LOADREGS | ports::PRW_LDMOTDIST | ports::PRW_UPDSYSREGS => true,
            ports::PWR_LOCX..=ports::PWR_SENSORS => self.load_sys,
            ports::PWR_LMDIST | ports::PWR_RMDIST => self.load_dist,
            _ => false,
        }
    }

    /// A copy to run ahead on (no recording).
    fn probe(&self) -> WorldIf {
        WorldIf {
            world: self.world.clone(),
            motctl: self.motctl,
            map_x: self.map_x,
            map_y: self.map_y,
            holding: self.holding,
            visible: self.visible,
            load_sys: self.load_sys,
            load_dist: self.load_dist,
            upd: self.upd,
            pulse: None,
            events: None,
            written: None,
        }
    }

    /// in_port during `cycle`.
    fn read(&self, port: u8, cycle: u64) -> u8 {
        // The read mux registered at the end of cycle - 1.
        let t = cycle - 1;
        match port & 15 {
            ports::PRD_MOTCTL_IN => self.motctl.value_at(t),
            p @ ports::PWR_LOCX..=ports::PWR_RMDIST => self.holding[p as usize],
            ports::PWR_COLADR => self.map_x.value_at(t),
            ports::PWR_ROWADR => self.map_y.value_at(t),
            // The map's address register and output register: two more cycles.
            ports::PRD_LOCINFO => self.world.get(self.map_x.value_at(t - 2), self.map_y.value_at(t - 2)).bits(),
            _ => 0,
        }
    }

    fn write(&mut self, port: u8, value: u8, cycle: u64) {
        self.catch_up();
        match port & 15 {
            p @ ports::PWR_LOCX..=ports::PWR_RMDIST => self.holding[p as usize] = value,
            ports::PWR_COLADR => self.map_x.write(value, cycle),
            ports::PWR_ROWADR => self.map_y.write(value, cycle),
            // The flags are registers: a toggle takes effect from the next cycle.
            ports::PRW_LOADREGS => self.load_sys = !self.load_sys,
            ports::PRW_LDMOTDIST => self.load_dist = !self.load_dist,
            ports::PRW_UPDSYSREGS => {
                self.upd = !self.upd;
                if self.upd {
                    self.pulse = Some(cycle + 1);
                }
            }
            _ => {}
        }
    }
}

/// The outputs of `bot` in a board (`--bot model`): LocX | LocY << 8 | BotInfo << 16 |
/// Sensors << 24 | LMDist << 32 | RMDist << 40 | upd_sysregs << 48, as
/// rtl/board/bot_model.v unpacks them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BotPins(pub u64);

/// The bot of a board design (`--bot model`), stepped edge by edge like [`IssBot::edge`] but
/// simulated only when something can change: while its inputs are held and before the next
/// write that shows (found by running ahead on a copy), an edge only counts. The outputs of
/// every edge are [`IssBot::edge`]'s (tested).
pub struct LazyBot {
    bot: IssBot,
    /// Edges seen: the next edge ends cycle `edges`.
    edges: u64,
    /// The inputs of the last edge, and the outputs after it.
    reset: bool,
    motctl: u8,
    out: BotPins,
    /// Edges before this one keep the outputs with the inputs held; the end of the last
    /// run-ahead (the horizon when it found no write).
    horizon: u64,
    looked: u64,
    /// The edge at which the inputs last changed.
    changed: u64,
    /// A write that shows, at the last edge.
    wrote: bool,
}

impl LazyBot {
    /// How far a run-ahead looks for the next write that shows: as far as the inputs have
    /// been held, from 1,024 edges (below that every edge is simulated: inputs that change
    /// often would make running ahead cost more than it saves) to 8 M (longer than a sample
    /// at hw timing).
    const HELD_BEFORE_RUN_AHEAD: u64 = 1 << 10;
    const RUN_AHEAD: u64 = 1 << 23;

    pub fn new(bot: IssBot) -> LazyBot {
        let (edges, out) = (bot.cycle(), bot.pins());
        LazyBot {
            bot,
            edges,
            reset: false,
            motctl: 0,
            out,
            horizon: edges,
            looked: edges,
            changed: edges,
            wrote: false,
        }
    }

    /// One rising edge (as [`IssBot::edge`]).
    #[inline]
    pub fn edge(&mut self, reset: bool, motctl: u8) -> BotPins {
        let e = self.edges;
        self.edges += 1;
        self.wrote = false;
        if reset == self.reset && motctl == self.motctl && e < self.horizon {
            return self.out;
        }
        self.sync(e);
        self.out = self.bot.edge(reset, motctl);
        self.wrote = self.bot.wrote();
        if (reset, motctl) != (self.reset, self.motctl) {
            (self.reset, self.motctl, self.changed) = (reset, motctl, e);
        }
        let held = self.edges - self.changed;
        if held < Self::HELD_BEFORE_RUN_AHEAD {
            (self.horizon, self.looked) = (self.edges, self.edges);
        } else {
            self.run_ahead(held.min(Self::RUN_AHEAD));
        }
        self.out
    }

    /// Look `edges` ahead (from the bot simulated up to now) for the next write that shows.
    fn run_ahead(&mut self, edges: u64) {
        self.sync(self.edges);
        self.looked = self.edges + edges;
        self.horizon = self.bot.next_write(self.looked, self.reset);
    }

    /// Simulate the edges counted but not run, with the inputs held, up to cycle `cycle`.
    fn sync(&mut self, cycle: u64) {
        let c = self.bot.cycle();
        if cycle > c {
            self.bot.skip(cycle - c, self.reset);
        }
    }

    /// The edges so far.
    pub fn edges(&self) -> u64 {
        self.edges
    }

    /// The inputs of the last edge changed them, or its firmware wrote what shows.
    pub fn wrote(&self) -> bool {
        self.wrote
    }

    /// How many edges from now the outputs stay as they are with the inputs held: at least
    /// `wanted` (up to 8 M) if they do, looking further ahead if need be; otherwise up to the
    /// next write that shows.
    pub fn quiet_for(&mut self, wanted: u64) -> u64 {
        let found_write = self.horizon < self.looked;
        if !found_write
            && self.horizon < self.edges + wanted
            && self.edges - self.changed >= Self::HELD_BEFORE_RUN_AHEAD
        {
            self.run_ahead(wanted.min(Self::RUN_AHEAD));
        }
        self.horizon.saturating_sub(self.edges)
    }

    /// Count `edges` edges with the inputs held, fewer than [`LazyBot::quiet_for`]: a
    /// board's fast-forward (they are simulated when something next changes).
    pub fn skip(&mut self, edges: u64) {
        debug_assert!(self.edges + edges <= self.horizon);
        self.edges += edges;
    }
}

/// A BotSim whose CPU is the ISS.
pub struct IssBot {
    cpu: Cpu,
    bus: WorldIf,
    next_sample: u64,
    budget: u64,
    /// The firmware's delay subroutines, replayed after their first call.
    routines: Routines,
}

impl IssBot {
    /// The bot with `program` (bot_pgm's 1K) in `world`, at configuration (cycle 0); a program
    /// past the 1K ROM is refused, as by the RTL backend.
    pub fn new(program: &Image, world: World) -> Result<IssBot, Error> {
        check_program_size(&program.words[..])?;
        let config = Config::default();
        Ok(IssBot {
            cpu: Cpu::new(config, &program.words[..BOT_ROM_WORDS]),
            bus: WorldIf {
                world,
                motctl: Timed::default(),
                map_x: Timed::default(),
                map_y: Timed::default(),
                holding: [0; 7],
                visible: Registers::default(),
                load_sys: false,
                load_dist: false,
                upd: false,
                pulse: None,
                events: None,
                written: None,
            },
            next_sample: 0,
            budget: Timing::Hw.update_budget(),
            routines: Routines::default(),
        })
    }

    /// MotCtl_in from the current cycle on.
    pub fn set_motors(&mut self, m: MotCtl) {
        let c = self.cpu.cycle();
        self.bus.motctl.write(m.0, c.saturating_sub(1));
    }

    /// The next cycle to simulate.
    pub fn cycle(&self) -> u64 {
        self.cpu.cycle()
    }

    /// Record every port access from now on ([`IssBot::take_events`]), or stop recording.
    pub fn record_ports(&mut self, on: bool) {
        self.bus.events = on.then(Vec::new);
    }

    /// The port accesses recorded since the last call.
    pub fn take_events(&mut self) -> Vec<PortEvent> {
        self.bus.events.as_mut().map(std::mem::take).unwrap_or_default()
    }

    /// Run exactly `cycles` cycles (upd_sysregs pulses in them are not reported as samples).
    pub fn run(&mut self, cycles: u64) {
        let end = self.cpu.cycle() + cycles;
        // Whole instructions to just before the end, then single cycles.
        self.cpu.run_with(&mut self.bus, end.saturating_sub(2), |_| false, &mut self.routines);
        while self.cpu.cycle() < end {
            self.cpu.tick(kcpsm6::iss::Pins::default(), &mut self.bus);
        }
        self.bus.pulse = None;
        self.bus.catch_up();
    }

    /// Run to the next upd_sysregs pulse within `budget` cycles; stops at the start of the
    /// pulse's first cycle, as the RTL backend does.
    pub fn wait_update_within(&mut self, budget: u64) -> Result<Snapshot, Error> {
        let end = self.cpu.cycle() + budget;
        // Whole instructions at a time (and busy-wait loops at once), stopping right after the
        // write strobe that raises upd_sysregs: that is the start of the pulse's first cycle.
        self.cpu.run_with(&mut self.bus, end, |bus| bus.pulse.is_some(), &mut self.routines);
        if let Some(p) = self.bus.pulse.take() {
            debug_assert_eq!(self.cpu.cycle(), p);
            self.bus.catch_up();
            let s = Snapshot { sample: self.next_sample, cycle: p, regs: self.bus.visible };
            self.next_sample += 1;
            return Ok(s);
        }
        Err(Error::no_update(budget, self.cpu.cycle(), self.cpu_at()))
    }

    /// As [`IssBot::wait_update_within`], one instruction at a time: each instruction the CPU
    /// retires goes to `watch` with the cycle after it (for a source-level trace, or a
    /// breakpoint); when `watch` says stop, the run stops right after that instruction and
    /// this returns `None`.
    pub fn wait_update_watched(
        &mut self,
        budget: u64,
        mut watch: impl FnMut(&kcpsm6::iss::Retired, u64) -> bool,
    ) -> Result<Option<Snapshot>, Error> {
        let end = self.cpu.cycle() + budget;
        while self.cpu.cycle() < end {
            let Ok(r) = self.cpu.step(&mut self.bus, end - self.cpu.cycle()) else { break };
            if watch(&r, self.cpu.cycle()) {
                return Ok(None);
            }
            if let Some(p) = self.bus.pulse.take() {
                self.bus.catch_up();
                let s = Snapshot { sample: self.next_sample, cycle: p, regs: self.bus.visible };
                self.next_sample += 1;
                return Ok(Some(s));
            }
        }
        Err(Error::no_update(budget, self.cpu.cycle(), self.cpu_at()))
    }

    /// The samples taken so far.
    pub fn samples(&self) -> u64 {
        self.next_sample
    }

    /// One rising edge of the bot's clock inside a board design (`--bot model`):
    /// `reset` and `motctl` as they were in the cycle the edge ends; returns what world_if
    /// holds after it, packed as [`BotPins`]. Equal to rtl/bot.v at every edge (the board's
    /// lock-step compares them).
    pub fn edge(&mut self, reset: bool, motctl: u8) -> BotPins {
        let c = self.cpu.cycle();
        if self.bus.motctl.value_at(c) != motctl {
            self.bus.motctl.write(motctl, c.saturating_sub(1));
        }
        // The visible registers copy the holding registers at this edge with the values of
        // the cycle it ends, before that cycle's writes land.
        self.bus.catch_up();
        self.cpu.tick(kcpsm6::iss::Pins { reset, ..Default::default() }, &mut self.bus);
        if reset {
            self.bus.reset();
        }
        self.bus.pulse = None;
        self.pins()
    }

    /// Whether the firmware wrote a port since the last call in a way that changes the outputs.
    fn wrote(&mut self) -> bool {
        self.bus.written.take().is_some()
    }

    /// What world_if holds now.
    pub fn pins(&self) -> BotPins {
        let v = &self.bus.visible;
        BotPins(
            u64::from_le_bytes([v.loc_x, v.loc_y, v.bot_info, v.sensors, v.lm_dist, v.rm_dist, 0, 0])
                | (self.bus.upd as u64) << 48,
        )
    }

    /// The first cycle before `limit` in which the firmware writes a port in a way that
    /// changes world_if's outputs (the only way they change with the inputs held), or `limit`:
    /// run on a copy. `reset`: the reset input held (nothing is written in reset).
    fn next_write(&mut self, limit: u64, reset: bool) -> u64 {
        if reset {
            return limit;
        }
        // A copy into the visible registers still to come changes the outputs too.
        let mut settled = self.bus.probe();
        settled.catch_up();
        if settled.visible != self.bus.visible {
            return self.cpu.cycle();
        }
        let (mut cpu, mut bus) = (self.cpu.clone(), self.bus.probe());
        cpu.run_with(&mut bus, limit, |bus| bus.written.is_some(), &mut self.routines);
        bus.written.unwrap_or(limit).min(limit)
    }

    /// Run `cycles` cycles with the inputs held, none of which writes a port
    /// ([`IssBot::next_write`] says how far that is): what a board's fast-forward does.
    fn skip(&mut self, cycles: u64, reset: bool) {
        let end = self.cpu.cycle() + cycles;
        if reset {
            // Held in reset: the core's reset sequence, world_if cleared at every edge.
            while self.cpu.cycle() < end {
                self.cpu.tick(kcpsm6::iss::Pins { reset: true, ..Default::default() }, &mut self.bus);
            }
            self.bus.reset();
            return;
        }
        self.cpu.run_with(&mut self.bus, end.saturating_sub(2), |_| false, &mut self.routines);
        while self.cpu.cycle() < end {
            self.cpu.tick(kcpsm6::iss::Pins::default(), &mut self.bus);
        }
        self.bus.pulse = None;
    }

    /// Where the CPU is now.
    pub fn cpu_at(&self) -> CpuAt {
        if self.cpu.in_reset() {
            CpuAt::Reset
        } else {
            CpuAt::Address(self.cpu.pc())
        }
    }
}

impl Backend for IssBot {
    fn wait_update_within(&mut self, budget: u64) -> Result<Snapshot, Error> {
        IssBot::wait_update_within(self, budget)
    }
    fn update_budget(&self) -> u64 {
        self.budget
    }
    fn set_update_budget(&mut self, cycles: u64) {
        self.budget = cycles;
    }
    fn set_motors(&mut self, m: MotCtl) {
        IssBot::set_motors(self, m)
    }
    fn cycle(&self) -> u64 {
        IssBot::cycle(self)
    }
    fn cpu_at(&self) -> CpuAt {
        IssBot::cpu_at(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_lazy_bot_shows_at_every_edge_what_the_edge_by_edge_bot_shows() {
        // hw timing: a sample every 5.3 M cycles; MotCtl changes at odd times, a reset in the
        // middle (held for a while), then MotCtl again.
        let fw = crate::Firmware { timing: Timing::Hw, ..crate::Firmware::default() };
        let image = fw.assemble().unwrap();
        let mut eager = IssBot::new(&image, World::builtin()).unwrap();
        let mut lazy = LazyBot::new(IssBot::new(&image, World::builtin()).unwrap());
        let changes: [(u64, bool, u8); 7] = [
            (3, true, 0x00),
            (40, false, 0x00),
            (1_234_567, false, MotCtl::FORWARD.0),
            (6_000_001, false, 0x7A),
            (11_500_000, true, 0x7A),
            (11_500_300, false, 0x7A),
            (12_345_679, false, MotCtl::FORWARD.0),
        ];
        let (mut reset, mut motctl, mut samples, mut upd) = (false, 0u8, 0, false);
        for c in 0..17_000_000u64 {
            if let Some(&(_, r, m)) = changes.iter().find(|(at, _, _)| *at == c) {
                (reset, motctl) = (r, m);
            }
            // A stretch where MotCtl changes every few clocks (every edge is simulated).
            if (8_000_000..8_200_000).contains(&c) && c % 7 == 0 {
                motctl ^= 0x11;
            }
            let (a, b) = (eager.edge(reset, motctl), lazy.edge(reset, motctl));
            assert_eq!(a, b, "edge {c}");
            samples += (a.0 >> 48 & 1 == 1 && !upd) as u64;
            upd = a.0 >> 48 & 1 == 1;
        }
        assert!(samples >= 3, "{samples} samples");
        // The last edges were only counted.
        assert!(lazy.bot.cycle() < lazy.edges());
    }

    #[test]
    fn a_program_past_the_1k_rom_is_refused_as_by_the_rtl() {
        let mut image = kcpsm6::Image::zeroed();
        image.words[0x400] = 0x22400;
        assert!(matches!(IssBot::new(&image, World::builtin()), Err(Error::ProgramTooLarge(0x400))));
        image.words[0x400] = 0;
        image.words[0x3FF] = 0x223FF;
        assert!(IssBot::new(&image, World::builtin()).is_ok());
    }
}
