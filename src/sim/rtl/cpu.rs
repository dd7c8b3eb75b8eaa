//! The KCPSM6 RTL core in a test harness, simulated by Verilator: the device under test of
//! the CPU lock-step testbench.
//!
//! The harness (`rtl/sim/kcpsm6_harness.v`) holds `rtl/kcpsm6.v`, a 4K program memory and an
//! input-port model that returns `inputs[port_id] ^ cycle` through a register, so an INPUT
//! reads a value that tells exactly which edge sampled it. Reset, sleep and interrupt are
//! driven from Rust each cycle.
//!
//! ```
//! use botsim::sim::rtl::CpuHarness;
//! use kcpsm6::iss::{Pins, ScratchPad};
//! let p = kcpsm6::asm::assemble_str("LOAD s0, 2A\nOUTPUT s0, 07\n").unwrap();
//! let mut dut = CpuHarness::new(ScratchPad::B64);
//! dut.load_program(&p.image.words[..]);
//! let mut writes = vec![];
//! for _ in 0..12 {
//!     let ports = dut.tick(Pins::default()).unwrap();
//!     if ports.write_strobe {
//!         writes.push((dut.cycle() - 1, ports.port_id, ports.out_port));
//!     }
//! }
//! // Self-start: the OUTPUT (second instruction) decodes in cycle 7 and strobes in 8.
//! assert_eq!(writes, vec![(8, 0x07, 0x2A)]);
//! ```

use std::marker::PhantomData;
use std::path::Path;
use std::ptr::NonNull;

use kcpsm6::iss::{Config, Phase, Pins, ScratchPad};

use super::{ffi, CPU_VARIANTS};

/// The core's ports during one cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Ports {
    pub address: u16,
    pub instruction: u32,
    pub bram_enable: bool,
    pub port_id: u8,
    pub out_port: u8,
    pub in_port: u8,
    pub read_strobe: bool,
    pub write_strobe: bool,
    pub k_write_strobe: bool,
    pub interrupt_ack: bool,
}

/// The core's state after a clock edge, read from the RTL: architectural state and the
/// sequencer flops the ISS models one for one.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ArchState {
    pub pc: u16,
    pub phase: Phase,
    pub carry: bool,
    pub zero: bool,
    pub interrupt_enable: bool,
    /// Active bank: false = A.
    pub bank: bool,
    /// The bank of the sX read port and the write port (spec §2.8).
    pub sx_bank: bool,
    /// The wrapping call-stack depth counter (spec §2.5).
    pub depth: u8,
    pub run: bool,
    pub internal_reset: bool,
    /// This cycle is an interrupt entry D (or its reset-cancelled twin): the flop that also
    /// times `interrupt_ack` (spec §2.6).
    pub interrupt_entry: bool,
    /// Bank A's s0..sF, then bank B's.
    pub registers: [u8; 32],
    pub scratch_pad: Vec<u8>,
}

/// The model has executed `$finish`; it is never evaluated again.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the model has finished ($finish) and cannot run further")]
pub struct Finished;

/// One Verilated CPU harness. Not `Send`: a model must stay on the thread that made it.
pub struct CpuHarness {
    sim: NonNull<ffi::CpuSim>,
    config: Config,
    _thread_bound: PhantomData<*const ()>,
}

impl CpuHarness {
    /// A harness with the given scratch-pad size, in its configuration state (cycle 0).
    /// Each size is a separately verilated variant with its own `hwbuild` and
    /// `interrupt_vector` (see [`CpuHarness::config`]).
    pub fn new(size: ScratchPad) -> CpuHarness {
        let bytes = size.bytes() as u32;
        let &(_, hwbuild, interrupt_vector) =
            CPU_VARIANTS.iter().find(|v| v.0 == bytes).expect("every scratch-pad size is built");
        // SAFETY: cpu_sim_new returns a new model or NULL for an unsupported size.
        let sim = NonNull::new(unsafe { ffi::cpu_sim_new(bytes) }).expect("every scratch-pad size is built");
        CpuHarness {
            sim,
            config: Config { hwbuild, interrupt_vector, scratch_pad_size: size },
            _thread_bound: PhantomData,
        }
    }

    /// The core's parameters in this variant, for an ISS that runs beside it.
    pub fn config(&self) -> Config {
        self.config
    }

    /// Load the program memory (up to 4096 words; the rest is zero).
    pub fn load_program(&mut self, words: &[u32]) {
        let n = words.len().min(4096);
        // SAFETY: the pointer and count describe a live slice.
        unsafe { ffi::cpu_sim_load_rom(self.sim.as_ptr(), words.as_ptr(), n) }
    }

    /// Set the 256 input-port values.
    pub fn set_inputs(&mut self, values: &[u8; 256]) {
        // SAFETY: 256 readable bytes.
        unsafe { ffi::cpu_sim_set_inputs(self.sim.as_ptr(), values.as_ptr()) }
    }

    /// Write a VCD of the harness from now on (until dropped or closed).
    pub fn open_vcd(&mut self, path: &Path) -> Result<(), String> {
        let c = std::ffi::CString::new(path.to_string_lossy().as_bytes())
            .map_err(|_| format!("{}: error: path contains a NUL byte", path.display()))?;
        // SAFETY: a valid C string for the duration of the call.
        match unsafe { ffi::cpu_sim_open_vcd(self.sim.as_ptr(), c.as_ptr()) } {
            0 => Ok(()),
            _ => Err(format!("{}: error: cannot write VCD file", path.display())),
        }
    }

    pub fn close_vcd(&mut self) {
        // SAFETY: the model is live.
        unsafe { ffi::cpu_sim_close_vcd(self.sim.as_ptr()) }
    }

    /// One clock cycle with `pins` driven; returns the ports during the cycle.
    pub fn tick(&mut self, pins: Pins) -> Result<Ports, Finished> {
        let mut p = ffi::CpuPorts::default();
        let pins = ffi::CpuPins { reset: pins.reset as u8, sleep: pins.sleep as u8, interrupt: pins.interrupt as u8 };
        // SAFETY: the model is live and `p` is writable.
        if unsafe { ffi::cpu_sim_tick(self.sim.as_ptr(), pins, &mut p) } != 0 {
            return Err(Finished);
        }
        Ok(Ports {
            address: p.address,
            instruction: p.instruction,
            bram_enable: p.bram_enable != 0,
            port_id: p.port_id,
            out_port: p.out_port,
            in_port: p.in_port,
            read_strobe: p.read_strobe != 0,
            write_strobe: p.write_strobe != 0,
            k_write_strobe: p.k_write_strobe != 0,
            interrupt_ack: p.interrupt_ack != 0,
        })
    }

    /// `cycles` cycles with constant pins in one call (the fast path); returns the cycles run.
    pub fn run(&mut self, pins: Pins, cycles: u64) -> u64 {
        let pins = ffi::CpuPins { reset: pins.reset as u8, sleep: pins.sleep as u8, interrupt: pins.interrupt as u8 };
        // SAFETY: the model is live.
        unsafe { ffi::cpu_sim_run(self.sim.as_ptr(), pins, cycles) }
    }

    /// The number of the next cycle to simulate.
    pub fn cycle(&self) -> u64 {
        // SAFETY: the model is live.
        unsafe { ffi::cpu_sim_cycle(self.sim.as_ptr()) }
    }

    /// The architectural state now (after the last edge).
    pub fn state(&self) -> ArchState {
        let mut s = ffi::CpuState::default();
        // SAFETY: the model is live and `s` is writable.
        unsafe { ffi::cpu_sim_state(self.sim.as_ptr(), &mut s) };
        ArchState {
            pc: s.pc,
            phase: match s.t_state {
                0b10 => Phase::Fetch,
                0b01 => Phase::Decode,
                _ => Phase::Idle,
            },
            carry: s.carry != 0,
            zero: s.zero != 0,
            interrupt_enable: s.interrupt_enable != 0,
            bank: s.bank != 0,
            sx_bank: s.xb != 0,
            depth: s.depth,
            run: s.run != 0,
            internal_reset: s.internal_reset != 0,
            interrupt_entry: s.active_interrupt != 0,
            registers: s.registers,
            scratch_pad: s.scratch_pad[..s.scratch_pad_size as usize].to_vec(),
        }
    }
}

impl Drop for CpuHarness {
    fn drop(&mut self) {
        // SAFETY: created by cpu_sim_new, freed once, on the creating thread (the type is !Send).
        unsafe { ffi::cpu_sim_free(self.sim.as_ptr()) }
    }
}

/// The scratch-pad sizes with a verilated harness.
pub const SIZES: [ScratchPad; 3] = [ScratchPad::B64, ScratchPad::B128, ScratchPad::B256];
