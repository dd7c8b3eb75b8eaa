//! The RTL core and the ISS in lock-step: every port and the whole state (registers, scratch
//! pad, flags, bank, depth and the sequencer flops) compared in every cycle.
//!
//! Both cores also stand alone behind the [`Core`] trait, so a spec-rule test runs the same
//! expectation on the RTL and on the ISS.

#![allow(dead_code)]

use botsim::sim::rtl::{ArchState, CpuHarness, Ports};
use kcpsm6::iss::{Bus, Config, Cpu, Pins, PortKind, Retired, ScratchPad};

/// The ISS's model of the harness's input port: a register loaded at the end of every cycle
/// with `inputs[port_id] ^ cycle` from that cycle's `port_id` (which can change between an
/// INPUT's two cycles when a reset switches the bank, spec §2.8).
pub struct HarnessBus {
    pub inputs: [u8; 256],
    /// The register's value during the current cycle.
    in_port: u8,
}

impl Bus for HarnessBus {
    fn input(&mut self, _port: u8, _cycle: u64) -> u8 {
        self.in_port
    }
    fn output(&mut self, _port: u8, _value: u8, _cycle: u64) {}
    fn output_k(&mut self, _port: u8, _value: u8, _cycle: u64) {}
}

/// A KCPSM6 behind the harness's ports: the RTL harness or the ISS with the harness's bus.
pub trait Core {
    /// Which core this is, for messages.
    fn name(&self) -> &'static str;
    /// One cycle with `pins`; the ports during it (`in_port` reads as 0).
    fn tick(&mut self, pins: Pins) -> Ports;
    /// The state after the last edge.
    fn state(&self) -> ArchState;
}

impl Core for CpuHarness {
    fn name(&self) -> &'static str {
        "rtl"
    }
    fn tick(&mut self, pins: Pins) -> Ports {
        let mut p = CpuHarness::tick(self, pins).expect("the harness never finishes");
        p.in_port = 0;
        p
    }
    fn state(&self) -> ArchState {
        CpuHarness::state(self)
    }
}

/// The ISS with the harness's bus.
pub struct IssCore {
    pub cpu: Cpu,
    pub bus: HarnessBus,
}

impl IssCore {
    pub fn new(config: Config, program: &[u32], inputs: [u8; 256]) -> IssCore {
        IssCore { cpu: Cpu::new(config, program), bus: HarnessBus { inputs, in_port: 0 } }
    }

    /// The ports in the current cycle.
    pub fn ports(&self) -> Ports {
        let c = &self.cpu;
        let s = c.strobe();
        Ports {
            address: c.pc(),
            instruction: c.instruction(),
            bram_enable: c.bram_enable(),
            port_id: c.port_id(),
            out_port: c.out_port(),
            in_port: 0,
            read_strobe: s == Some(PortKind::Read),
            write_strobe: s == Some(PortKind::Write),
            k_write_strobe: s == Some(PortKind::KWrite),
            interrupt_ack: c.interrupt_ack(),
        }
    }

    /// One cycle; the record of an instruction whose second cycle it was.
    pub fn step(&mut self, pins: Pins) -> Option<Retired> {
        let next_in = self.bus.inputs[self.cpu.port_id() as usize] ^ self.cpu.cycle() as u8;
        let r = self.cpu.tick(pins, &mut self.bus);
        self.bus.in_port = next_in;
        r
    }
}

impl Core for IssCore {
    fn name(&self) -> &'static str {
        "iss"
    }
    fn tick(&mut self, pins: Pins) -> Ports {
        let p = self.ports();
        self.step(pins);
        p
    }
    fn state(&self) -> ArchState {
        let c = &self.cpu;
        ArchState {
            pc: c.pc(),
            phase: c.phase(),
            carry: c.carry(),
            zero: c.zero(),
            interrupt_enable: c.interrupt_enabled(),
            bank: c.bank(),
            sx_bank: c.sx_bank(),
            depth: c.depth(),
            run: c.running(),
            internal_reset: c.in_reset(),
            interrupt_entry: c.interrupt_entry(),
            registers: *c.regs(),
            scratch_pad: c.scratch_pad().to_vec(),
        }
    }
}

/// The RTL harness and the ISS of its variant, both loaded with `program` and `inputs`.
pub fn both_cores(size: ScratchPad, program: &[u32], inputs: [u8; 256]) -> [Box<dyn Core>; 2] {
    let mut rtl = CpuHarness::new(size);
    rtl.load_program(program);
    rtl.set_inputs(&inputs);
    let iss = IssCore::new(rtl.config(), program, inputs);
    [Box::new(rtl), Box::new(iss)]
}

pub struct Lockstep {
    pub iss: IssCore,
    pub rtl: CpuHarness,
    pub retired: Vec<Retired>,
}

impl Lockstep {
    pub fn new(size: ScratchPad, program: &[u32], inputs: [u8; 256]) -> Lockstep {
        let mut rtl = CpuHarness::new(size);
        rtl.load_program(program);
        rtl.set_inputs(&inputs);
        let iss = IssCore::new(rtl.config(), program, inputs);
        Lockstep { iss, rtl, retired: Vec::new() }
    }

    /// One cycle on both: the ports during the cycle and the whole state after its edge must
    /// be equal; an error describes the first difference.
    pub fn cycle(&mut self, pins: Pins) -> Result<Option<Retired>, String> {
        let c = self.iss.cpu.cycle();
        let want = self.iss.ports();
        let got = Core::tick(&mut self.rtl, pins);
        if got != want {
            return Err(format!("cycle {c}: ports differ (pins {pins:?})\n  iss: {want:?}\n  rtl: {got:?}"));
        }
        let r = self.iss.step(pins);
        let (rtl, iss) = (Core::state(&self.rtl), Core::state(&self.iss));
        if rtl != iss {
            return Err(format!(
                "after cycle {c} (pins {pins:?}, {r:?}): state differs\n  iss: {iss:?}\n  rtl: {rtl:?}"
            ));
        }
        if let Some(rec) = r {
            self.retired.push(rec);
        }
        Ok(r)
    }

    /// Run `cycles` cycles with pins from `stimulus`, which sees the ISS at the start of each
    /// cycle (so it can aim an event at the instruction in flight).
    pub fn run(&mut self, cycles: u64, mut stimulus: impl FnMut(&Cpu) -> Pins) -> Result<(), String> {
        for _ in 0..cycles {
            let pins = stimulus(&self.iss.cpu);
            self.cycle(pins)?;
        }
        Ok(())
    }
}
