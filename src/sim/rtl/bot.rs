//! The `bot` RTL under Verilator, driven from Rust: the testbench API.
//!
//! ```
//! use botsim::{MotCtl, Orientation, RtlBot, Timing};
//! let mut bot = RtlBot::builder().timing(Timing::Fast).build().unwrap();
//! let first = bot.wait_update().unwrap(); // sample 0: the register dump after start-up
//! assert_eq!((first.location(), first.orientation()), ((64, 64), Orientation::East));
//! bot.set_motors(MotCtl::FORWARD);
//! let s = bot.run_samples(16).unwrap();
//! assert_eq!(s[14].distances(), (15, 15)); // threshold reached on sample 15 ...
//! assert_eq!(s[15].location(), (65, 64)); // ... the move shows in sample 16
//! ```

use std::marker::PhantomData;
use std::path::{Path, PathBuf};
use std::ptr::NonNull;

use kcpsm6::Image;

use super::ffi;
use crate::firmware::{Compat, Firmware, Timing};
use crate::regs::{MotCtl, Registers, Snapshot};
use crate::sim::{check_program_size, Backend, CpuAt, Error, PortEvent, PortKind, BOT_ROM_WORDS};
use crate::world::{Cell, World};

/// The outputs of `bot` during one cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Outputs {
    pub regs: Registers,
    pub upd_sysregs: bool,
    pub vid_pixel_out: u8,
}

/// How to build an [`RtlBot`].
#[derive(Clone, Debug)]
pub struct Builder {
    firmware: Firmware,
    program: Option<Image>,
    world: Option<World>,
    motors: MotCtl,
    vcd: Option<PathBuf>,
    budget: Option<u64>,
    debug: bool,
}

impl Builder {
    /// Samples per move or 45-degree step (assembled into the built-in firmware).
    pub fn threshold(mut self, t: u8) -> Builder {
        self.firmware.threshold = t;
        self
    }
    pub fn timing(mut self, t: Timing) -> Builder {
        self.firmware.timing = t;
        self
    }
    pub fn compat(mut self, c: Compat) -> Builder {
        self.firmware.compat = c;
        self
    }
    /// All firmware constants at once.
    pub fn firmware(mut self, f: Firmware) -> Builder {
        self.firmware = f;
        self
    }
    /// Run this program instead of the built-in firmware.
    pub fn program(mut self, image: Image) -> Builder {
        self.program = Some(image);
        self
    }
    /// The world (the built-in one otherwise).
    pub fn world(mut self, w: World) -> Builder {
        self.world = Some(w);
        self
    }
    /// MotCtl_in from the start.
    pub fn motors(mut self, m: MotCtl) -> Builder {
        self.motors = m;
        self
    }
    /// The build of the model with the KCPSM6's debug signals (Xilinx's names: the
    /// instruction's text `kcpsm6_opcode`, `kcpsm6_status`, `sim_s0`..`sim_sF`) for waveforms;
    /// a fifth slower.
    pub fn debug(mut self, on: bool) -> Builder {
        self.debug = on;
        self
    }
    /// Write a VCD of the whole design.
    pub fn vcd(mut self, path: impl AsRef<Path>) -> Builder {
        self.vcd = Some(path.as_ref().to_path_buf());
        self
    }
    /// The cycle budget of [`RtlBot::wait_update`] (default: the firmware timing's
    /// [`Timing::update_budget`]).
    pub fn update_budget(mut self, cycles: u64) -> Builder {
        self.budget = Some(cycles);
        self
    }

    pub fn build(self) -> Result<RtlBot, Error> {
        let image = match self.program {
            Some(img) => img,
            None => self.firmware.assemble().map_err(Error::Program)?,
        };
        // SAFETY: bot_sim_new returns a new, live model.
        let sim = NonNull::new(unsafe { ffi::bot_sim_new(self.debug as i32) }).expect("model allocation");
        let mut bot = RtlBot {
            sim,
            budget: self.budget.unwrap_or(self.firmware.timing.update_budget()),
            next_sample: 0,
            _thread_bound: PhantomData,
        };
        bot.load_program(&image)?;
        bot.load_world(&self.world.unwrap_or_else(World::builtin));
        bot.set_motors(self.motors);
        if let Some(p) = self.vcd {
            bot.open_vcd(&p)?;
        }
        Ok(bot)
    }
}

/// The `bot` RTL as a Verilated model. Not `Send`: a Verilated model stays on the thread that
/// made it.
pub struct RtlBot {
    sim: NonNull<ffi::BotSim>,
    budget: u64,
    next_sample: u64,
    _thread_bound: PhantomData<*const ()>,
}

impl RtlBot {
    /// A builder with the built-in firmware (threshold 15, `hw` timing) and world.
    pub fn builder() -> Builder {
        Builder {
            firmware: Firmware::default(),
            program: None,
            world: None,
            motors: MotCtl::STOP,
            vcd: None,
            budget: None,
            debug: false,
        }
    }

    /// Replace the program ROM (takes effect as the CPU fetches; reset to restart it).
    pub fn load_program(&mut self, image: &Image) -> Result<(), Error> {
        check_program_size(&image.words[..])?;
        // SAFETY: BOT_ROM_WORDS readable words.
        unsafe { ffi::bot_sim_load_program(self.sim.as_ptr(), image.words.as_ptr(), BOT_ROM_WORDS) };
        Ok(())
    }

    /// Replace the world.
    pub fn load_world(&mut self, w: &World) {
        let cells = w.to_bytes();
        // SAFETY: 16384 readable bytes.
        unsafe { ffi::bot_sim_load_world(self.sim.as_ptr(), cells.as_ptr(), cells.len()) };
    }

    /// Write a VCD from now on.
    pub fn open_vcd(&mut self, path: &Path) -> Result<(), Error> {
        let c = std::ffi::CString::new(path.to_string_lossy().as_bytes())
            .map_err(|_| Error::Io(format!("{}: error: path contains a NUL byte", path.display())))?;
        // SAFETY: a valid C string for the call.
        match unsafe { ffi::bot_sim_open_vcd(self.sim.as_ptr(), c.as_ptr()) } {
            0 => Ok(()),
            _ => Err(Error::Io(format!("{}: error: cannot write VCD file", path.display()))),
        }
    }

    /// Finish and close the VCD file; an error if it could not be written completely.
    pub fn close_vcd(&mut self) -> Result<(), Error> {
        // SAFETY: live model.
        unsafe { ffi::bot_sim_close_vcd(self.sim.as_ptr()) };
        self.fatal().map_or(Ok(()), |msg| Err(stopped_by(msg)))
    }

    /// Set MotCtl_in (from the next cycle on).
    pub fn set_motors(&mut self, m: MotCtl) {
        // SAFETY: live model.
        unsafe { ffi::bot_sim_set_motctl(self.sim.as_ptr(), m.0) }
    }

    /// Hold reset for `cycles` cycles (at least 1), then release it. The next update is
    /// sample 0 again.
    pub fn reset(&mut self, cycles: u64) -> Result<(), Error> {
        self.hold_reset(true);
        let r = self.run(cycles.max(1));
        self.hold_reset(false);
        r
    }

    /// Drive the video port (vid_row, vid_col); `vid_pixel_out` follows two clocks later.
    pub fn set_video(&mut self, row: u16, col: u16) {
        // SAFETY: live model.
        unsafe { ffi::bot_sim_set_video(self.sim.as_ptr(), row, col) }
    }

    /// Read one map cell through the video port: drive the address, run two cycles, return
    /// `vid_pixel_out` in the third.
    pub fn read_video(&mut self, row: u16, col: u16) -> Result<Cell, Error> {
        self.set_video(row, col);
        self.run(2)?;
        Ok(Cell::from_bits(self.tick()?.vid_pixel_out))
    }

    /// Read the whole map through the video port, one cell per clock (pipelined: an address
    /// every cycle, its value two cycles later), in address order. This runs 16,386 cycles:
    /// upd_sysregs pulses in them are not reported as samples.
    pub fn scan_video(&mut self) -> Result<Vec<Cell>, Error> {
        let mut cells = Vec::with_capacity(crate::world::CELLS);
        for i in 0..crate::world::CELLS + 2 {
            if i < crate::world::CELLS {
                self.set_video((i / crate::world::SIZE) as u16, (i % crate::world::SIZE) as u16);
            }
            let o = self.tick()?;
            if i >= 2 {
                cells.push(Cell::from_bits(o.vid_pixel_out));
            }
        }
        Ok(cells)
    }

    /// One clock cycle; returns the outputs during it.
    pub fn tick(&mut self) -> Result<Outputs, Error> {
        let mut o = ffi::BotOutputs::default();
        // SAFETY: live model, writable output.
        if unsafe { ffi::bot_sim_tick(self.sim.as_ptr(), &mut o) } != 0 {
            return Err(self.stopped());
        }
        Ok(Outputs { regs: regs(&o.regs), upd_sysregs: o.upd_sysregs != 0, vid_pixel_out: o.vid_pixel_out })
    }

    /// `cycles` clock cycles in one call.
    pub fn run(&mut self, cycles: u64) -> Result<(), Error> {
        // SAFETY: live model.
        let n = unsafe { ffi::bot_sim_run(self.sim.as_ptr(), cycles) };
        if n < cycles {
            return Err(self.stopped());
        }
        Ok(())
    }

    /// `cycles` cycles of Verilator's minimal loop on this model (clock low, evaluate, clock
    /// high, evaluate; nothing checked, dumped or recorded): the reference `botsim bench`
    /// measures [`RtlBot::run`] against, side by side.
    pub fn bench_minimal(&mut self, cycles: u64) {
        // SAFETY: live model.
        unsafe { ffi::bot_sim_bench_minimal(self.sim.as_ptr(), cycles) }
    }

    /// The next cycle to simulate (cycle 0 is the first after configuration).
    pub fn cycle(&self) -> u64 {
        // SAFETY: live model.
        unsafe { ffi::bot_sim_cycle(self.sim.as_ptr()) }
    }

    /// Where the CPU is now.
    pub fn cpu_at(&self) -> CpuAt {
        let mut pc = 0;
        // SAFETY: live model, writable output.
        match unsafe { ffi::bot_sim_cpu_in_reset(self.sim.as_ptr(), &mut pc) } {
            0 => CpuAt::Address(pc),
            _ => CpuAt::Reset,
        }
    }

    /// Hold the reset pin high (`true`) or release it; [`RtlBot::reset`] pulses it.
    pub fn hold_reset(&mut self, held: bool) {
        // SAFETY: live model.
        unsafe { ffi::bot_sim_set_reset(self.sim.as_ptr(), held as u8) };
        if held {
            self.next_sample = 0;
        }
    }

    /// The cycle budget of [`RtlBot::wait_update`].
    pub fn update_budget(&self) -> u64 {
        self.budget
    }

    /// Run to the next upd_sysregs pulse, within the builder's cycle budget.
    pub fn wait_update(&mut self) -> Result<Snapshot, Error> {
        self.wait_update_within(self.budget)
    }

    /// Run to the next upd_sysregs pulse, within `budget` cycles. The simulation stops at
    /// the start of the pulse's first cycle; the snapshot holds the registers then.
    pub fn wait_update_within(&mut self, budget: u64) -> Result<Snapshot, Error> {
        let mut cycle = 0;
        let mut r = ffi::BotRegs::default();
        // SAFETY: live model, writable outputs.
        match unsafe { ffi::bot_sim_run_until_update(self.sim.as_ptr(), budget, &mut cycle, &mut r) } {
            1 => {
                let s = Snapshot { sample: self.next_sample, cycle, regs: regs(&r) };
                self.next_sample += 1;
                Ok(s)
            }
            0 => Err(Error::no_update(budget, self.cycle(), self.cpu_at())),
            _ => Err(self.stopped()),
        }
    }

    /// As [`RtlBot::wait_update`], appending every port access of the CPU to `events`.
    pub fn wait_update_recording(&mut self, events: &mut Vec<PortEvent>) -> Result<Snapshot, Error> {
        self.wait_update_recording_within(self.budget, events)
    }

    /// As [`RtlBot::wait_update_within`], appending every port access of the CPU to `events`.
    pub fn wait_update_recording_within(
        &mut self,
        budget: u64,
        events: &mut Vec<PortEvent>,
    ) -> Result<Snapshot, Error> {
        match self.record(budget, true, events)? {
            Some(s) => Ok(s),
            None => Err(Error::no_update(budget, self.cycle(), self.cpu_at())),
        }
    }

    /// Run `cycles` cycles, appending every port access of the CPU to `events` (upd_sysregs
    /// pulses in them are not reported as samples).
    pub fn run_recording(&mut self, cycles: u64, events: &mut Vec<PortEvent>) -> Result<(), Error> {
        self.record(cycles, false, events).map(|_| ())
    }

    fn record(&mut self, budget: u64, stop: bool, events: &mut Vec<PortEvent>) -> Result<Option<Snapshot>, Error> {
        let mut left = budget;
        loop {
            let mut buf = vec![ffi::BotPortEvent::default(); 4096];
            let (mut cycle, mut n) = (0, 0);
            let mut r = ffi::BotRegs::default();
            let start = self.cycle();
            // SAFETY: live model; `buf` holds `buf.len()` events, the outputs are writable.
            let rc = unsafe {
                ffi::bot_sim_run_recording(
                    self.sim.as_ptr(),
                    left,
                    stop as i32,
                    &mut cycle,
                    &mut r,
                    buf.as_mut_ptr(),
                    buf.len(),
                    &mut n,
                )
            };
            events.extend(buf[..n].iter().map(|e| PortEvent {
                kind: match e.kind {
                    0 => PortKind::Read,
                    1 => PortKind::Write,
                    _ => PortKind::KWrite,
                },
                port: e.port,
                value: e.value,
                cycle: e.cycle,
            }));
            match rc {
                1 => {
                    let s = Snapshot { sample: self.next_sample, cycle, regs: regs(&r) };
                    self.next_sample += 1;
                    return Ok(Some(s));
                }
                0 => return Ok(None),
                // The buffer filled up: carry on from where the model stopped.
                -2 => left -= self.cycle() - start,
                _ => return Err(self.stopped()),
            }
        }
    }

    /// Closed loop: at each upd_sysregs pulse give the snapshot to `driver` and apply its
    /// MotCtl for the next iteration, until it is finished or `max_samples` snapshots have
    /// been taken. `observe` sees every snapshot. Returns the number of snapshots.
    pub fn drive(
        &mut self,
        driver: &mut dyn crate::driver::Driver,
        max_samples: u64,
        mut observe: impl FnMut(&Snapshot),
    ) -> Result<u64, Error> {
        let mut n = 0;
        while n < max_samples {
            let s = self.wait_update()?;
            n += 1;
            observe(&s);
            let m = driver.next(&s);
            if driver.finished() {
                break;
            }
            self.set_motors(m);
        }
        Ok(n)
    }

    /// The next `n` snapshots with the current motor command.
    pub fn run_samples(&mut self, n: usize) -> Result<Vec<Snapshot>, Error> {
        (0..n).map(|_| self.wait_update()).collect()
    }
}

impl RtlBot {
    /// The fatal runtime error that stopped this model, if any (taken once).
    fn fatal(&mut self) -> Option<String> {
        let mut buf = [0u8; 512];
        // SAFETY: live model, a writable buffer of the given length.
        let n = unsafe { ffi::bot_sim_take_fatal(self.sim.as_ptr(), buf.as_mut_ptr().cast(), buf.len()) };
        (n > 0).then(|| String::from_utf8_lossy(&buf[..n.min(buf.len() - 1)]).into_owned())
    }

    /// Why the model refused to run on.
    fn stopped(&mut self) -> Error {
        self.fatal().map_or(Error::Finished, stopped_by)
    }
}

fn stopped_by(msg: String) -> Error {
    match msg.strip_prefix("VerilatedVcd::bufferFlush: ") {
        Some(reason) => Error::Waveform(reason.to_string()),
        None => Error::Stopped(msg),
    }
}

fn regs(r: &ffi::BotRegs) -> Registers {
    Registers {
        loc_x: r.loc_x,
        loc_y: r.loc_y,
        sensors: r.sensors,
        bot_info: r.bot_info,
        lm_dist: r.lm_dist,
        rm_dist: r.rm_dist,
    }
}

impl Backend for RtlBot {
    fn wait_update_within(&mut self, budget: u64) -> Result<Snapshot, Error> {
        RtlBot::wait_update_within(self, budget)
    }
    fn update_budget(&self) -> u64 {
        self.budget
    }
    fn set_update_budget(&mut self, cycles: u64) {
        self.budget = cycles;
    }
    fn set_motors(&mut self, m: MotCtl) {
        RtlBot::set_motors(self, m)
    }
    fn cycle(&self) -> u64 {
        RtlBot::cycle(self)
    }
    fn cpu_at(&self) -> CpuAt {
        RtlBot::cpu_at(self)
    }
}

impl Drop for RtlBot {
    fn drop(&mut self) {
        // SAFETY: created by bot_sim_new, freed once, on its thread (the type is !Send).
        unsafe { ffi::bot_sim_free(self.sim.as_ptr()) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn taking_a_fatal_message_into_no_buffer_writes_nothing() {
        // A zero-length buffer used to underflow the copy's length.
        let mut bot = RtlBot::builder().timing(Timing::Fast).build().unwrap();
        // SAFETY: live model; a zero-length buffer may be null.
        let n = unsafe { ffi::bot_sim_take_fatal(bot.sim.as_ptr(), std::ptr::null_mut(), 0) };
        assert_eq!(n, 0);
        assert!(bot.fatal().is_none());
        let mut one = [0x55u8; 1];
        // SAFETY: live model, a one-byte buffer.
        let n = unsafe { ffi::bot_sim_take_fatal(bot.sim.as_ptr(), one.as_mut_ptr().cast(), 1) };
        assert_eq!((n, one[0]), (0, 0), "the terminating NUL only");
    }
}
