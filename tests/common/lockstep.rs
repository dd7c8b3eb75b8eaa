//! The RTL core and the ISS in lock-step: every port compared in every cycle, the whole
//! architectural state compared after every completed instruction.

#![allow(dead_code)]

use botsim::cpu::{ArchState, CpuHarness, Ports};
use kcpsm6::iss::{Bus, Cpu, Pins, PortKind, Retired, ScratchPad};

/// The ISS's model of the harness's input port: a register loaded every cycle with
/// `inputs[port_id] ^ cycle`, so an INPUT whose strobe is in cycle t reads the value for t-1.
pub struct HarnessBus {
    pub inputs: [u8; 256],
}

impl Bus for HarnessBus {
    fn input(&mut self, port: u8, cycle: u64) -> u8 {
        self.inputs[port as usize] ^ (cycle.wrapping_sub(1) as u8)
    }
    fn output(&mut self, _port: u8, _value: u8, _cycle: u64) {}
    fn output_k(&mut self, _port: u8, _value: u8, _cycle: u64) {}
}

pub struct Lockstep {
    pub iss: Cpu,
    pub rtl: CpuHarness,
    pub bus: HarnessBus,
    pub retired: Vec<Retired>,
}

impl Lockstep {
    pub fn new(size: ScratchPad, program: &[u32], inputs: [u8; 256]) -> Lockstep {
        let mut rtl = CpuHarness::new(size);
        rtl.load_program(program);
        rtl.set_inputs(&inputs);
        let iss = Cpu::new(rtl.config(), program);
        Lockstep { iss, rtl, bus: HarnessBus { inputs }, retired: Vec::new() }
    }

    /// The ISS's view of the ports in the current cycle.
    fn iss_ports(&self) -> Ports {
        let s = self.iss.strobe();
        Ports {
            address: self.iss.pc(),
            instruction: self.iss.instruction(),
            bram_enable: self.iss.bram_enable(),
            port_id: self.iss.port_id(),
            out_port: self.iss.out_port(),
            in_port: 0,
            read_strobe: s == Some(PortKind::Read),
            write_strobe: s == Some(PortKind::Write),
            k_write_strobe: s == Some(PortKind::KWrite),
            interrupt_ack: self.iss.interrupt_ack(),
        }
    }

    fn iss_state(&self) -> ArchState {
        ArchState {
            pc: self.iss.pc(),
            phase: self.iss.phase(),
            carry: self.iss.carry(),
            zero: self.iss.zero(),
            interrupt_enable: self.iss.interrupt_enabled(),
            bank: self.iss.bank(),
            stack_pointer: self.iss.depth(),
            registers: *self.iss.regs(),
            scratch_pad: self.iss.scratch_pad().to_vec(),
        }
    }

    /// One cycle on both; an error describes the first difference.
    pub fn cycle(&mut self, pins: Pins) -> Result<Option<Retired>, String> {
        let c = self.iss.cycle();
        let want = self.iss_ports();
        let mut got = self.rtl.tick(pins).map_err(|e| e.to_string())?;
        got.in_port = 0;
        if got != want {
            return Err(format!("cycle {c}: ports differ (pins {pins:?})\n  iss: {want:?}\n  rtl: {got:?}"));
        }
        let r = self.iss.tick(pins, &mut self.bus);
        let rtl = self.rtl.state();
        if rtl.phase != self.iss.phase() || rtl.pc != self.iss.pc() {
            return Err(format!(
                "after cycle {c}: sequencing differs: iss {:?} pc {:03X}, rtl {:?} pc {:03X}",
                self.iss.phase(),
                self.iss.pc(),
                rtl.phase,
                rtl.pc
            ));
        }
        if let Some(rec) = r {
            let iss = self.iss_state();
            if rtl != iss {
                return Err(format!("after cycle {c} ({rec:?}): state differs\n  iss: {iss:?}\n  rtl: {rtl:?}"));
            }
            self.retired.push(rec);
        }
        Ok(r)
    }

    /// Run `cycles` cycles with pins from `stimulus(cycle)`.
    pub fn run(&mut self, cycles: u64, mut stimulus: impl FnMut(u64) -> Pins) -> Result<(), String> {
        for _ in 0..cycles {
            let c = self.iss.cycle();
            self.cycle(stimulus(c))?;
        }
        Ok(())
    }
}
