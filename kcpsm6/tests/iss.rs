//! The ISS against the spec: every opcode, the worked flag vectors (§1.5), scratch-pad
//! aliasing, the stack, and the cycle numbers of reset, interrupt and sleep (§2.4-§2.7).

use kcpsm6::asm::assemble_str;
use kcpsm6::iss::{Bus, Config, Cpu, Phase, Pins, PortEvent, PortKind, RetireKind, Retired, Routines, ScratchPad};

/// A bus that records every event and answers INPUTs with `port ^ 0xA5`.
#[derive(Default)]
struct Recorder {
    events: Vec<PortEvent>,
}

impl Bus for Recorder {
    fn input(&mut self, port: u8, cycle: u64) -> u8 {
        let v = port ^ 0xA5;
        self.events.push(PortEvent { kind: PortKind::Read, port, value: v, cycle });
        v
    }
    fn output(&mut self, port: u8, value: u8, cycle: u64) {
        self.events.push(PortEvent { kind: PortKind::Write, port, value, cycle });
    }
    fn output_k(&mut self, port: u8, value: u8, cycle: u64) {
        self.events.push(PortEvent { kind: PortKind::KWrite, port, value, cycle });
    }
}

fn cpu_with(config: Config, src: &str) -> Cpu {
    let p = assemble_str(src).unwrap_or_else(|e| panic!("{e}"));
    Cpu::new(config, &p.image.words[..])
}

/// Assemble `src`, run `n` instructions, return the CPU and the records.
fn run(src: &str, n: usize) -> (Cpu, Vec<Retired>) {
    run_with(Config::default(), src, n)
}

fn run_with(config: Config, src: &str, n: usize) -> (Cpu, Vec<Retired>) {
    let mut cpu = cpu_with(config, src);
    let mut bus = Recorder::default();
    let recs = (0..n).map(|_| cpu.step(&mut bus, 100).unwrap()).collect();
    (cpu, recs)
}

fn flags(c: &Cpu) -> (bool, bool) {
    (c.carry(), c.zero())
}

/// (setup, instruction, register checked, expected value, expected (C, Z)).
/// Setup sets flags to a known state: C=1, Z=1 via `LOAD sF, 00 / SUB sF, 00`? no: see `pre`.
const C1Z0: &str = "LOAD sF, 00\nSUB sF, 01\n"; // C=1, Z=0
const C0Z1: &str = "LOAD sF, 00\nADD sF, 00\n"; // C=0, Z=1
const C1Z1: &str = "LOAD sF, FF\nADD sF, 01\n"; // C=1, Z=1

#[test]
fn worked_flag_vectors() {
    // s0=FF, s1=00; ADD s0,01 -> s0=00, Z=1, C=1; then ADDCY s1,00 -> s1=01, Z=0, C=0
    let (c, _) = run("LOAD s0, FF\nLOAD s1, 00\nADD s0, 01\n", 3);
    assert_eq!((c.reg(false, 0), flags(&c)), (0x00, (true, true)));
    let (c, _) = run("LOAD s0, FF\nLOAD s1, 00\nADD s0, 01\nADDCY s1, 00\n", 4);
    assert_eq!((c.reg(false, 1), flags(&c)), (0x01, (false, false)));
    // 16-bit 0xFFFF + 1 = 0
    let (c, _) = run("LOAD s0, FF\nLOAD s1, FF\nADD s0, 01\nADDCY s1, 00\n", 4);
    assert_eq!((c.reg(false, 1), flags(&c)), (0x00, (true, true)));
    // 0x0100 - 1
    let (c, _) = run("LOAD s0, 00\nLOAD s1, 01\nSUB s0, 01\n", 3);
    assert_eq!((c.reg(false, 0), flags(&c)), (0xFF, (true, false)));
    let (c, _) = run("LOAD s0, 00\nLOAD s1, 01\nSUB s0, 01\nSUBCY s1, 00\n", 4);
    assert_eq!((c.reg(false, 1), flags(&c)), (0x00, (false, false)));
    // 16-bit compare equal
    let (c, _) = run("LOAD s0, AB\nLOAD s1, 12\nCOMPARE s0, AB\nCOMPARECY s1, 12\n", 4);
    assert_eq!(flags(&c), (false, true));
    assert_eq!((c.reg(false, 0), c.reg(false, 1)), (0xAB, 0x12), "COMPARE does not write");
    // TEST parity, TESTCY chaining
    let (c, _) = run("LOAD s0, 07\nTEST s0, FF\n", 2);
    assert_eq!(flags(&c), (true, false));
    let (c, _) = run("LOAD s0, 07\nTEST s0, FF\nLOAD s1, 01\nTESTCY s1, FF\n", 4);
    assert_eq!(flags(&c), (false, false));
    // HWBUILD with hwbuild = 00
    let (c, _) = run("LOAD s0, 55\nHWBUILD s0\n", 2);
    assert_eq!((c.reg(false, 0), flags(&c)), (0x00, (true, true)));
    // SL1, SRA
    let (c, _) = run("LOAD s0, 80\nSL1 s0\n", 2);
    assert_eq!((c.reg(false, 0), flags(&c)), (0x01, (true, false)));
    let (c, _) = run(&format!("{C1Z0}LOAD s0, 02\nSRA s0\n"), 4);
    assert_eq!((c.reg(false, 0), flags(&c)), (0x81, (false, false)));
}

/// Run `pre` (which sets flags), load s0 = a and s1 = b, then `instr`; check s0 and flags.
fn alu(pre: &str, a: u8, b: u8, instr: &str) -> (u8, bool, bool) {
    let src = format!("{pre}LOAD s0, {a:02X}\nLOAD s1, {b:02X}\n{instr}\n");
    let n = src.lines().count();
    let (c, _) = run(&src, n);
    (c.reg(false, 0), c.carry(), c.zero())
}

#[test]
fn logic_ops_clear_carry_and_set_zero() {
    assert_eq!(alu(C1Z0, 0xF0, 0x0F, "AND s0, s1"), (0x00, false, true));
    assert_eq!(alu(C1Z0, 0xF0, 0x3C, "AND s0, s1"), (0x30, false, false));
    assert_eq!(alu(C1Z1, 0xF0, 0x0F, "OR s0, s1"), (0xFF, false, false));
    assert_eq!(alu(C1Z0, 0x00, 0x00, "OR s0, 00"), (0x00, false, true));
    assert_eq!(alu(C1Z0, 0x5A, 0x5A, "XOR s0, s1"), (0x00, false, true));
    assert_eq!(alu(C1Z0, 0x5A, 0x00, "XOR s0, FF"), (0xA5, false, false));
}

#[test]
fn load_and_star_leave_flags() {
    assert_eq!(alu(C1Z1, 0x12, 0x34, "LOAD s0, s1"), (0x34, true, true));
    assert_eq!(alu(C1Z0, 0x12, 0x34, "LOAD s0, 00"), (0x00, true, false));
    // STAR writes the other bank from the active bank.
    let (c, _) = run("LOAD s1, 77\nSTAR s0, s1\nSTAR s2, 99\nREGBANK B\nSTAR s3, 11\n", 5);
    assert_eq!((c.reg(true, 0), c.reg(true, 2), c.reg(false, 0)), (0x77, 0x99, 0x00));
    assert_eq!(c.reg(false, 3), 0x11, "STAR from bank B writes bank A");
    assert!(c.bank());
}

#[test]
fn add_sub_carry_borrow_and_z_chain() {
    assert_eq!(alu(C1Z1, 0x80, 0x80, "ADD s0, s1"), (0x00, true, true));
    assert_eq!(alu(C1Z1, 0x01, 0x02, "ADD s0, s1"), (0x03, false, false));
    // ADDCY adds the carry, Z chains: Zold=1 and r==0 -> 1; Zold=0 -> 0.
    assert_eq!(alu(C1Z1, 0xFF, 0x00, "ADDCY s0, s1"), (0x00, true, true));
    assert_eq!(alu(C1Z0, 0xFF, 0x00, "ADDCY s0, s1"), (0x00, true, false));
    assert_eq!(alu(C0Z1, 0x01, 0x01, "ADDCY s0, 01"), (0x02, false, false));
    assert_eq!(alu(C0Z1, 0x05, 0x05, "SUB s0, s1"), (0x00, false, true));
    assert_eq!(alu(C0Z1, 0x05, 0x06, "SUB s0, s1"), (0xFF, true, false));
    // SUBCY subtracts the borrow.
    assert_eq!(alu(C1Z1, 0x05, 0x04, "SUBCY s0, s1"), (0x00, false, true));
    assert_eq!(alu(C1Z0, 0x05, 0x04, "SUBCY s0, s1"), (0x00, false, false));
    assert_eq!(alu(C1Z1, 0x00, 0x00, "SUBCY s0, 00"), (0xFF, true, false));
    // COMPARE / COMPARECY do not write.
    assert_eq!(alu(C0Z1, 0x05, 0x06, "COMPARE s0, s1"), (0x05, true, false));
    assert_eq!(alu(C1Z1, 0x05, 0x04, "COMPARECY s0, s1"), (0x05, false, true));
    assert_eq!(alu(C1Z0, 0x05, 0x04, "COMPARECY s0, s1"), (0x05, false, false));
    assert_eq!(alu(C1Z1, 0x04, 0x04, "COMPARECY s0, 04"), (0x04, true, false));
}

#[test]
fn test_and_testcy() {
    assert_eq!(alu(C0Z1, 0x03, 0x01, "TEST s0, s1"), (0x03, true, false));
    assert_eq!(alu(C1Z0, 0x03, 0x03, "TEST s0, s1"), (0x03, false, false));
    assert_eq!(alu(C1Z0, 0xF0, 0x0F, "TEST s0, s1"), (0xF0, false, true));
    // TESTCY: C = parity ^ Cold, Z = (r==0) & Zold
    assert_eq!(alu(C1Z1, 0x01, 0x01, "TESTCY s0, s1"), (0x01, false, false));
    assert_eq!(alu(C1Z1, 0xF0, 0x0F, "TESTCY s0, s1"), (0xF0, true, true));
    assert_eq!(alu(C1Z0, 0xF0, 0x0F, "TESTCY s0, 0F"), (0xF0, true, false));
    // KCPSM6 v1.0's bug (result bits 01 gave C=1 wrongly) is not here: 0x01 has odd parity.
    assert_eq!(alu(C0Z1, 0x02, 0x00, "TEST s0, 03"), (0x02, true, false));
}

#[test]
fn shifts_and_rotates() {
    // (instr, s0 in, C in, s0 out, C out, Z out)
    let cases: &[(&str, u8, bool, u8, bool, bool)] = &[
        ("SL0 s0", 0x81, false, 0x02, true, false),
        ("SL0 s0", 0x80, false, 0x00, true, true),
        ("SL1 s0", 0x00, false, 0x01, false, false),
        ("SLX s0", 0x41, false, 0x83, false, false),
        ("SLA s0", 0x40, true, 0x81, false, false),
        ("SLA s0", 0x80, false, 0x00, true, true),
        ("RL s0", 0x81, false, 0x03, true, false),
        ("SR0 s0", 0x81, false, 0x40, true, false),
        ("SR0 s0", 0x01, false, 0x00, true, true),
        ("SR1 s0", 0x00, false, 0x80, false, false),
        ("SRX s0", 0x82, false, 0xC1, false, false),
        ("SRA s0", 0x01, true, 0x80, true, false),
        ("RR s0", 0x01, false, 0x80, true, false),
        // Undocumented sub-codes follow the same rule: 01 = SLA, 0D = RR, 1x-7x = low nibble.
        ("INST 14001", 0x40, true, 0x81, false, false),
        ("INST 1400D", 0x01, false, 0x80, true, false),
        ("INST 14076", 0x81, false, 0x02, true, false),
        // Opcode 15 acts as 14.
        ("INST 15006", 0x81, false, 0x02, true, false),
    ];
    for &(ins, a, cin, out, cout, zout) in cases {
        let pre = if cin { C1Z0 } else { C0Z1 };
        assert_eq!(alu(pre, a, 0, ins), (out, cout, zout), "{ins} with s0={a:02X} C={cin}");
    }
}

#[test]
fn hwbuild_parameter() {
    let cfg = Config { hwbuild: 0x42, ..Config::default() };
    let (c, _) = run_with(cfg, &format!("{C0Z1}HWBUILD s3\n"), 3);
    assert_eq!((c.reg(false, 3), c.carry(), c.zero()), (0x42, true, false));
    // HWBUILD is [7] = 1 whatever the other low bits are.
    let (c, _) = run_with(cfg, "INST 143FF\n", 1);
    assert_eq!(c.reg(false, 3), 0x42);
}

#[test]
fn scratch_pad_aliasing_for_each_size() {
    for (size, alias) in [(ScratchPad::B64, 0x03), (ScratchPad::B128, 0x43), (ScratchPad::B256, 0xC3)] {
        let cfg = Config { scratch_pad_size: size, ..Config::default() };
        let src = "LOAD s1, 5A\nSTORE s1, C3\nFETCH s2, C3\nLOAD s4, C3\nFETCH s5, (s4)\n";
        let (c, recs) = run_with(cfg, src, 5);
        assert_eq!(recs[1].spm_write, Some((alias, 0x5A)), "{size:?}");
        assert_eq!((c.reg(false, 2), c.reg(false, 5)), (0x5A, 0x5A));
        assert_eq!(c.scratch_pad()[alias as usize], 0x5A);
        assert_eq!(c.scratch_pad().len(), size.bytes());
    }
}

#[test]
fn ports_strobes_and_ids() {
    let src = "LOAD s0, 12\nLOAD s1, 56\nOUTPUT s0, 56\nOUTPUT s0, (s1)\nINPUT s2, 3C\nINPUT s3, (s1)\n\
               OUTPUTK AB, C\nINST 2A7B0\n";
    let mut cpu = cpu_with(Config::default(), src);
    let mut bus = Recorder::default();
    for _ in 0..8 {
        cpu.step(&mut bus, 100).unwrap();
    }
    let ev: Vec<(PortKind, u8, u8)> = bus.events.iter().map(|e| (e.kind, e.port, e.value)).collect();
    assert_eq!(
        ev,
        vec![
            (PortKind::Write, 0x56, 0x12),
            (PortKind::Write, 0x56, 0x12),
            (PortKind::Read, 0x3C, 0x3C ^ 0xA5),
            (PortKind::Read, 0x56, 0x56 ^ 0xA5),
            // OUTPUTK: port_id carries kk's low nibble in [7:4].
            (PortKind::KWrite, 0xBC, 0xAB),
            // Opcode 2A: out_port = [11:4] = 7B, port_id = sY with Y = [7:4] = B (s11 = sB = 0).
            (PortKind::KWrite, 0x00, 0x7B),
        ]
    );
    assert_eq!((cpu.reg(false, 2), cpu.reg(false, 3)), (0x3C ^ 0xA5, 0x56 ^ 0xA5));
    // Self-start: instruction k has its D in 5 + 2k and its strobe in 6 + 2k.
    let cycles: Vec<u64> = bus.events.iter().map(|e| e.cycle).collect();
    assert_eq!(cycles, vec![10, 12, 14, 16, 18, 20]);
}

#[test]
fn strobe_is_in_the_second_cycle_and_port_id_in_both() {
    let mut cpu = cpu_with(Config::default(), "LOAD s0, 12\nOUTPUT s0, 56\n");
    let mut bus = Recorder::default();
    let mut seen = vec![];
    for _ in 0..10 {
        seen.push((cpu.cycle(), cpu.phase(), cpu.port_id(), cpu.out_port(), cpu.strobe()));
        cpu.tick(Pins::default(), &mut bus);
    }
    // OUTPUT is at 001: D in cycle 7, F in cycle 8.
    assert_eq!(seen[7], (7, Phase::Decode, 0x56, 0x12, None));
    assert_eq!(seen[8], (8, Phase::Fetch, 0x56, 0x12, Some(PortKind::Write)));
    assert_eq!(seen[9].4, None);
}

#[test]
fn undefined_opcodes_are_no_ops() {
    for w in ["23FFF", "27123", "33ABC", "3BFFF", "3F000"] {
        let (c, recs) = run(&format!("{C1Z0}LOAD s0, 77\nINST {w}\nLOAD s1, 01\n"), 5);
        assert_eq!(recs[3].reg_write, None, "{w}");
        assert_eq!(recs[3].next_pc, 4, "{w} falls through");
        assert_eq!((c.reg(false, 0), c.reg(false, 1), flags(&c)), (0x77, 0x01, (true, false)), "{w}");
    }
}

#[test]
fn jumps_calls_returns_and_conditions() {
    let src = "
        LOAD s0, 00
        CALL sub          ; 001
        JUMP done         ; 002
sub:    ADD s0, 01        ; 003
        RETURN            ; 004
done:   LOAD&RETURN s5, 99 ; 005 underflows: not reached in this test
";
    let (c, recs) = run(src, 5);
    let pcs: Vec<u16> = recs.iter().map(|r| r.pc).collect();
    assert_eq!(pcs, vec![0, 1, 3, 4, 2]);
    assert_eq!(recs[1].depth, 1);
    assert_eq!(recs[3].depth, 0);
    assert_eq!(c.pc(), 5);

    // Conditions: only the taken ones move the PC or the stack.
    for (cond, pre, taken) in [
        ("Z", C0Z1, true),
        ("Z", C1Z0, false),
        ("NZ", C1Z0, true),
        ("NZ", C0Z1, false),
        ("C", C1Z0, true),
        ("C", C0Z1, false),
        ("NC", C0Z1, true),
        ("NC", C1Z0, false),
    ] {
        let (_, r) = run(&format!("{pre}JUMP {cond}, 100\n"), 3);
        assert_eq!(r[2].next_pc, if taken { 0x100 } else { 3 }, "JUMP {cond}");
        let (_, r) = run(&format!("{pre}CALL {cond}, 100\n"), 3);
        assert_eq!((r[2].next_pc, r[2].depth), if taken { (0x100, 1) } else { (3, 0) }, "CALL {cond}");
        let (_, r) = run(&format!("{pre}CALL 010\nADDRESS 010\nRETURN {cond}\n"), 4);
        assert_eq!((r[3].next_pc, r[3].depth), if taken { (3, 0) } else { (0x11, 1) }, "RETURN {cond}");
    }
}

#[test]
fn register_indirect_targets_use_low_nibble_of_sx() {
    let (_, r) = run("LOAD s7, F3\nLOAD s8, 45\nJUMP@ (s7, s8)\n", 3);
    assert_eq!(r[2].next_pc, 0x345);
    let (_, r) = run("LOAD s7, 01\nLOAD s8, 00\nCALL@ (s7, s8)\n", 3);
    assert_eq!((r[2].next_pc, r[2].depth), (0x100, 1));
}

#[test]
fn load_and_return_resumes_after_the_call() {
    let (c, r) = run("CALL 010\nLOAD s0, s5\nADDRESS 010\nLOAD&RETURN s5, 3C\n", 3);
    assert_eq!((r[1].next_pc, r[1].reg_write), (1, Some((false, 5, 0x3C))));
    assert_eq!(c.reg(false, 0), 0x3C);
}

#[test]
fn returni_restores_flags_and_bank_and_sets_ie() {
    // Enter the ISR by interrupt with C=1, Z=0, bank B; the ISR changes all three.
    let src = "
        REGBANK B
        LOAD s0, 00
        SUB s0, 01          ; C=1 Z=0
        ENABLE INTERRUPT
spin:   JUMP spin
        ADDRESS 200
handler: REGBANK A
        LOAD s0, 00
        ADD s0, 00          ; C=0 Z=1
        RETURNI ENABLE
        ADDRESS 3FF
isr:    JUMP handler
";
    let mut cpu = cpu_with(Config::default(), src);
    let mut bus = Recorder::default();
    let mut recs = vec![];
    while recs.len() < 12 {
        let irq = recs.iter().all(|r: &Retired| r.kind != RetireKind::Interrupt);
        if let Some(r) = cpu.tick(Pins { interrupt: irq && cpu.cycle() > 12, ..Pins::default() }, &mut bus) {
            recs.push(r);
        }
    }
    let entry = recs.iter().position(|r| r.kind == RetireKind::Interrupt).unwrap();
    assert_eq!(recs[entry].pc, 4, "the cancelled instruction is the spin loop");
    assert!(!recs[entry].ie);
    assert_eq!(recs[entry].next_pc, 0x3FF);
    let ret = recs.iter().position(|r| r.word == 0x29001).unwrap();
    let r = recs[ret];
    assert_eq!((r.c, r.z, r.bank, r.ie, r.next_pc, r.depth), (true, false, true, true, 4, 0));
}

#[test]
fn interrupt_latency_and_ack_from_a_d_cycle() {
    // ENABLE at 000 (D 5); NOPs after. Raise interrupt in cycle 25, a D cycle.
    let mut cpu = cpu_with(Config::default(), "ENABLE INTERRUPT\n");
    let mut bus = Recorder::default();
    let mut ack = vec![];
    let mut vector_d = None;
    for _ in 0..40 {
        let c = cpu.cycle();
        if cpu.interrupt_ack() {
            ack.push(c);
        }
        if cpu.phase() == Phase::Decode && cpu.pc() == 0x3FF && vector_d.is_none() {
            vector_d = Some(c);
        }
        cpu.tick(Pins { interrupt: (25..29).contains(&c), ..Pins::default() }, &mut bus);
    }
    assert_eq!(ack, vec![28]);
    assert_eq!(vector_d, Some(29));
}

#[test]
fn interrupt_latency_from_an_f_cycle_and_one_cycle_pulse_missed() {
    let mut cpu = cpu_with(Config::default(), "ENABLE INTERRUPT\n");
    let mut bus = Recorder::default();
    let mut ack = vec![];
    for _ in 0..40 {
        let c = cpu.cycle();
        if cpu.interrupt_ack() {
            ack.push(c);
        }
        // 26 is an F cycle: ack in 30. A one-cycle pulse in an F cycle (16) is registered
        // during a D cycle, where nothing samples it, and is missed.
        cpu.tick(Pins { interrupt: c == 16 || (26..31).contains(&c), ..Pins::default() }, &mut bus);
    }
    assert_eq!(ack, vec![30]);
}

#[test]
fn enable_with_pending_request_cancels_the_next_instruction() {
    let mut cpu = cpu_with(Config::default(), "ENABLE INTERRUPT\nLOAD s0, 11\nLOAD s1, 22\n");
    let mut bus = Recorder::default();
    let mut recs = vec![];
    let mut ack = vec![];
    for _ in 0..14 {
        if cpu.interrupt_ack() {
            ack.push(cpu.cycle());
        }
        if let Some(r) = cpu.tick(Pins { interrupt: true, ..Pins::default() }, &mut bus) {
            recs.push(r);
        }
    }
    // ENABLE D=5, F=6; 001 cancelled in D=7; vector fetched (ack) in 8, two cycles after ENABLE's F.
    assert_eq!(ack, vec![8]);
    assert_eq!((recs[1].kind, recs[1].pc, recs[1].reg_write), (RetireKind::Interrupt, 1, None));
    assert_eq!(cpu.reg(false, 0), 0, "the cancelled LOAD wrote nothing");
}

#[test]
fn disable_interrupt_takes_effect_at_the_end_of_its_d() {
    let mut cpu = cpu_with(Config::default(), "ENABLE INTERRUPT\nDISABLE INTERRUPT\n");
    let mut bus = Recorder::default();
    let mut taken = false;
    for _ in 0..30 {
        // High from DISABLE's D (7): first seen in its F (8), where IE is already 0.
        let c = cpu.cycle();
        if let Some(r) = cpu.tick(Pins { interrupt: c >= 7, ..Pins::default() }, &mut bus) {
            taken |= r.kind == RetireKind::Interrupt;
        }
    }
    assert!(!taken);
}

#[test]
fn interrupt_vector_parameter() {
    let cfg = Config { interrupt_vector: 0x123, ..Config::default() };
    let mut cpu = cpu_with(cfg, "ENABLE INTERRUPT\n");
    let mut bus = Recorder::default();
    let r = loop {
        if let Some(r) = cpu.tick(Pins { interrupt: true, ..Pins::default() }, &mut bus) {
            if r.kind == RetireKind::Interrupt {
                break r;
            }
        }
    };
    assert_eq!((r.next_pc, r.depth), (0x123, 1));
}

#[test]
fn sleep_finishes_the_instruction_then_wakes_in_m_plus_3() {
    let mut cpu = cpu_with(Config::default(), "LOAD s0, 01\nOUTPUT s0, 10\nLOAD s1, 02\n");
    let mut bus = Recorder::default();
    let mut trace = vec![];
    for _ in 0..30 {
        let c = cpu.cycle();
        trace.push((c, cpu.phase(), cpu.bram_enable(), cpu.pc()));
        // Sleep high in cycle 6 (F of 000): registered, seen in 001's D (7) -> 8 is idle.
        cpu.tick(Pins { sleep: (6..20).contains(&c), ..Pins::default() }, &mut bus);
    }
    // OUTPUT's strobe still happens in cycle 8 (the first idle cycle).
    assert_eq!(bus.events[0].cycle, 8);
    assert_eq!(trace[8].1, Phase::Idle);
    assert!(trace[8..22].iter().all(|t| !t.2 && t.3 == 2), "no fetch, address frozen");
    // Sleep low first in cycle m = 20: fetch in 22, D in 23.
    assert_eq!((trace[22].1, trace[22].2), (Phase::Fetch, true));
    assert_eq!((trace[23].1, trace[23].3), (Phase::Decode, 2));
}

#[test]
fn interrupt_held_through_sleep_is_taken_after_wake_up() {
    let mut cpu = cpu_with(Config::default(), "ENABLE INTERRUPT\nLOAD s0, 01\nLOAD s1, 02\n");
    let mut bus = Recorder::default();
    let mut ack = vec![];
    for _ in 0..40 {
        let c = cpu.cycle();
        if cpu.interrupt_ack() {
            ack.push(c);
        }
        // Sleep from ENABLE's D (seen at 6 -> no: registered, effective in 7's D -> idle 8..).
        cpu.tick(Pins { sleep: (6..20).contains(&c), interrupt: c >= 12, ..Pins::default() }, &mut bus);
    }
    // Wake: fetch in 22 (F) sees the request, 23 cancels, ack in 24.
    assert_eq!(ack, vec![24]);
}

#[test]
fn reset_keeps_registers_and_scratch_pad_and_clears_flags() {
    let src = "LOAD s0, 5A\nSTORE s0, 10\nREGBANK B\nLOAD s1, 00\nSUB s1, 01\nENABLE INTERRUPT\nCALL 100\n";
    let mut cpu = cpu_with(Config::default(), src);
    let mut bus = Recorder::default();
    for _ in 0..7 {
        cpu.step(&mut bus, 100).unwrap();
    }
    assert!(cpu.carry() && cpu.bank() && cpu.interrupt_enabled() && cpu.depth() == 1);
    for _ in 0..3 {
        cpu.tick(Pins { reset: true, ..Pins::default() }, &mut bus);
    }
    for _ in 0..4 {
        cpu.tick(Pins::default(), &mut bus);
    }
    assert_eq!(
        (cpu.pc(), cpu.carry(), cpu.zero(), cpu.bank(), cpu.interrupt_enabled(), cpu.depth()),
        (0, false, false, false, false, 0)
    );
    assert_eq!((cpu.reg(false, 0), cpu.reg(true, 1), cpu.scratch_pad()[0x10]), (0x5A, 0xFF, 0x5A));
}

#[test]
fn strobe_of_an_instruction_in_flight_fires_during_reset() {
    let mut cpu = cpu_with(Config::default(), "OUTPUT s0, 01\nOUTPUT s0, 02\n");
    let mut bus = Recorder::default();
    for _ in 0..12 {
        let c = cpu.cycle();
        // Reset sampled high at the end of 7 (D of the second OUTPUT): its strobe fires in 8.
        cpu.tick(Pins { reset: (7..9).contains(&c), ..Pins::default() }, &mut bus);
    }
    let ports: Vec<(u8, u64)> = bus.events.iter().map(|e| (e.port, e.cycle)).collect();
    assert_eq!(ports, vec![(1, 6), (2, 8)]);
}

#[test]
fn stack_holds_30_levels_and_the_31st_call_resets() {
    // Recursion: each level counts in s0 and calls itself.
    let src = "
        LOAD s0, 00
        LOAD s1, 00
rec:    ADD s0, 01
        CALL rec
";
    let mut cpu = cpu_with(Config::default(), src);
    let mut bus = Recorder::default();
    let mut max_depth = 0;
    let mut reset_at = None;
    for i in 0..200 {
        let r = cpu.step(&mut bus, 100).unwrap();
        max_depth = max_depth.max(r.depth);
        if r.next_pc == 0 && i > 2 {
            reset_at = Some(r);
            break;
        }
    }
    // 30 CALLs fit; the 31st overflows. The first instruction at its target (ADD) still writes.
    let r = reset_at.expect("internal reset");
    assert!(max_depth >= 30);
    assert_eq!(cpu.reg(false, 0), 32, "30 levels + the overflowing call's target write + 1");
    assert_eq!(r.depth, 0);
    assert!(!cpu.carry() && !cpu.zero());
}

#[test]
fn return_with_empty_stack_resets_and_the_garbage_target_still_strobes() {
    let src = "LOAD s0, 00\nRETURN\n";
    let mut cpu = cpu_with(Config::default(), src);
    let mut bus = Recorder::default();
    let mut pcs = vec![];
    for _ in 0..6 {
        pcs.push(cpu.step(&mut bus, 100).unwrap().pc);
    }
    // RETURN pops entry 31 (never written: 000) -> resumes at 001 (the RETURN itself) while
    // the internal reset starts; then 000 again.
    assert_eq!(&pcs[..4], &[0, 1, 1, 0]);
}

#[test]
fn out_port_reads_the_new_bank_one_cycle_late() {
    // s0 = 11 in bank A, 22 in bank B. CALL pushes bank A; the callee switches to B and
    // RETURNI (D 13, F 14) restores A. RETURNI's out_port is sX (bit 13 = 0): in its F the
    // bank is already A but the register file is still read with the registered bank B.
    let src = "LOAD s0, 11\nSTAR s0, 22\nCALL 010\nADDRESS 010\nREGBANK B\nRETURNI DISABLE\n";
    let mut cpu = cpu_with(Config::default(), src);
    let mut bus = Recorder::default();
    let mut out = vec![];
    for _ in 0..16 {
        out.push((cpu.cycle(), cpu.out_port(), cpu.bank()));
        cpu.tick(Pins::default(), &mut bus);
    }
    assert_eq!(out[13], (13, 0x22, true));
    assert_eq!(out[14], (14, 0x22, false));
    assert_eq!(out[15], (15, 0x11, false));
}

mod fast_path {
    use super::*;
    use proptest::prelude::*;

    /// Random words biased towards meaningful programs of 48 words, with countdown loops.
    fn program() -> impl Strategy<Value = Vec<u32>> {
        let word = prop_oneof![
            6 => (prop::sample::select(vec![0x00u32, 0x02, 0x04, 0x06, 0x08, 0x0A, 0x0C, 0x0E, 0x10, 0x12, 0x16, 0x18, 0x1A, 0x1C, 0x1E, 0x2C, 0x2E]),
                  any::<bool>(), 0u32..16, 0u32..16, any::<u8>())
                .prop_map(|(op, k, x, y, kk)| if k { (op + 1) << 12 | x << 8 | kk as u32 } else { op << 12 | x << 8 | y << 4 }),
            2 => (0u32..16, any::<u8>()).prop_map(|(x, s)| 0x14000 | x << 8 | s as u32),
            3 => (prop::sample::select(vec![0x20u32, 0x22, 0x30, 0x32, 0x34, 0x36, 0x38, 0x3A, 0x3C, 0x3E]), 0u32..50)
                .prop_map(|(op, t)| op << 12 | t),
            2 => prop::sample::select(vec![0x25000u32, 0x31000, 0x35000, 0x29001, 0x21342, 0x28001, 0x37001, 0x37000, 0x2B123, 0x23000]),
            1 => 0u32..=0x3FFFF,
        ];
        (prop::collection::vec(word, 48), prop::collection::vec((0usize..44, 0u32..16, any::<u8>()), 0..4)).prop_map(
            |(mut p, loops)| {
                // Countdown loops: LOAD sX, kk / SUB sX, 01 / JUMP NZ, <the SUB>.
                for (at, x, k) in loops {
                    p[at] = 0x01000 | x << 8 | k as u32;
                    p[at + 1] = 0x19001 | x << 8;
                    p[at + 2] = 0x36000 | (at as u32 + 1);
                }
                p.push(0x22000);
                p
            },
        )
    }

    fn state(c: &Cpu) -> (u64, u16, bool, bool, bool, bool, u8, [u8; 32], Vec<u8>) {
        (
            c.cycle(),
            c.pc(),
            c.carry(),
            c.zero(),
            c.bank(),
            c.interrupt_enabled(),
            c.depth(),
            *c.regs(),
            c.scratch_pad().to_vec(),
        )
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 2000, failure_persistence: None, ..ProptestConfig::default() })]

        #[test]
        fn run_fast_equals_cycle_by_cycle(prog in program(), until in 1u64..4000) {
            let mut fast = Cpu::new(Config::default(), &prog);
            let mut fast_bus = Recorder::default();
            fast.run_fast(&mut fast_bus, until, |_| false);
            let end = fast.cycle();
            let mut slow = Cpu::new(Config::default(), &prog);
            let mut slow_bus = Recorder::default();
            while slow.cycle() < end {
                slow.tick(Pins::default(), &mut slow_bus);
            }
            prop_assert_eq!(&fast_bus.events, &slow_bus.events);
            prop_assert_eq!(state(&fast), state(&slow));
            // And both go on identically from there.
            let more = end + 500;
            fast.run_fast(&mut fast_bus, more, |_| false);
            while slow.cycle() < fast.cycle() {
                slow.tick(Pins::default(), &mut slow_bus);
            }
            prop_assert_eq!(&fast_bus.events, &slow_bus.events);
            prop_assert_eq!(state(&fast), state(&slow));
        }
    }

    /// Firmware shaped like a team's: a main loop that does some work, writes a port and calls
    /// a delay of nested levels (each `LOAD sK, n` / body / `CALL` the next / `SUB sK, 01` /
    /// `JUMP NZ`), the bodies random ALU work, sometimes a level that reads a register it did
    /// not load (an input: its calls repeat only with the same value), sometimes one that
    /// writes a port or the scratch pad (not one that only computes).
    fn nested_delays() -> impl Strategy<Value = Vec<u32>> {
        let alu = (
            prop::sample::select(vec![0x00u32, 0x02, 0x04, 0x06, 0x0C, 0x10, 0x12, 0x18, 0x1A, 0x1C]),
            any::<bool>(),
            0u32..16,
            0u32..16,
            any::<u8>(),
        )
            .prop_map(
                |(op, k, x, y, kk)| if k { (op + 1) << 12 | x << 8 | kk as u32 } else { op << 12 | x << 8 | y << 4 },
            );
        let level = (1u32..12, 2u8..9, prop::collection::vec(alu.clone(), 0..4), 0u32..10);
        (prop::collection::vec(level, 1..4), prop::collection::vec(alu, 0..5), 1u32..5).prop_map(
            |(levels, work, nudge)| {
                let mut p = vec![0u32; 256];
                // main at 0: work, OUTPUT s5, 01, CALL level 0, ADD s5, nudge, JUMP 0.
                let mut at = 0;
                for w in &work {
                    p[at] = *w;
                    at += 1;
                }
                p[at] = 0x2C501;
                p[at + 1] = 0x20040;
                p[at + 2] = 0x11500 | nudge;
                p[at + 3] = 0x22000;
                // Level i at 0x40 + 0x20 i.
                for (i, (k, n, body, special)) in levels.iter().enumerate() {
                    let base = 0x40 + 0x20 * i as u32;
                    let mut a = base as usize;
                    let counter = 12 + *k % 4; // sC..sF count; the bodies touch any register
                    p[a] = 0x01000 | counter << 8 | *n as u32;
                    a += 1;
                    let head = a as u32;
                    for w in body {
                        // Keep the counters of this level and the ones around it.
                        p[a] = if (w >> 8 & 15) >= 12 { w & !0xC00 } else { *w };
                        a += 1;
                    }
                    match special {
                        0 => {
                            p[a] = 0x00070; // LOAD s0, s7: s7 is read before this level writes it
                            a += 1;
                        }
                        1 => {
                            p[a] = 0x2C702; // OUTPUT s7, 02
                            a += 1;
                        }
                        2 => {
                            p[a] = 0x2F730; // STORE s7, 30
                            a += 1;
                        }
                        _ => {}
                    }
                    if i + 1 < levels.len() {
                        p[a] = 0x20000 | (base + 0x20);
                        a += 1;
                    }
                    p[a] = 0x19001 | counter << 8;
                    p[a + 1] = 0x36000 | head;
                    p[a + 2] = 0x25000;
                }
                p
            },
        )
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 300, failure_persistence: None, ..ProptestConfig::default() })]

        /// Calls replayed from their recordings leave the core, every flop of it (the stack
        /// RAM too), and the ports exactly as simulating them cycle by cycle does, run in
        /// pieces of any length.
        #[test]
        fn replayed_calls_equal_cycle_by_cycle(prog in nested_delays(), pieces in prop::collection::vec(1u64..40_000, 1..12)) {
            let mut fast = Cpu::new(Config::default(), &prog);
            let mut routines = Routines::default();
            let mut fast_bus = Recorder::default();
            let mut slow = Cpu::new(Config::default(), &prog);
            let mut slow_bus = Recorder::default();
            for piece in pieces {
                let until = fast.cycle() + piece;
                fast.run_with(&mut fast_bus, until, |_| false, &mut routines);
                while slow.cycle() < fast.cycle() {
                    slow.tick(Pins::default(), &mut slow_bus);
                }
                prop_assert_eq!(&fast_bus.events, &slow_bus.events);
                prop_assert!(fast == slow, "at cycle {}: {:?} != {:?}", fast.cycle(), state(&fast), state(&slow));
            }
        }
    }

    #[test]
    fn a_delay_of_nested_calls_is_replayed_whole() {
        // BotSim's shape: four levels, 24 x 40 x 25 x 50 turns (about 5 M cycles).
        let src = "main: OUTPUT s5, 01\nCALL wait4\nADD s5, 01\nJUMP main\n\
                   wait1: LOAD s0, 18\nspin: SUB s0, 01\nJUMP NZ, spin\nRETURN\n\
                   wait2: LOAD s1, 28\nturn2: CALL wait1\nSUB s1, 01\nJUMP NZ, turn2\nRETURN\n\
                   wait3: LOAD s2, 19\nturn3: CALL wait2\nSUB s2, 01\nJUMP NZ, turn3\nRETURN\n\
                   wait4: LOAD s3, 32\nturn4: CALL wait3\nSUB s3, 01\nJUMP NZ, turn4\nRETURN\n";
        let mut fast = cpu_with(Config::default(), src);
        let mut routines = Routines::default();
        let mut bus = Recorder::default();
        let mut steps = 0u64;
        fast.run_with(
            &mut bus,
            30_000_000,
            |_| {
                steps += 1;
                false
            },
            &mut routines,
        );
        let mut slow = cpu_with(Config::default(), src);
        let mut slow_bus = Recorder::default();
        slow.run_fast(&mut slow_bus, fast.cycle(), |_| false);
        assert!(fast == slow);
        assert_eq!(bus.events, slow_bus.events);
        assert!(bus.events.len() >= 5, "{:?}", bus.events.len());
        // The first main loop is simulated (the innermost countdown in one step): about
        // 50 x 25 x 40 x 5 instructions; the later ones are a handful of steps each.
        assert!(steps < 300_000, "{steps} steps");
        assert!(routines.replayed() > 0);
    }

    #[test]
    fn countdown_loop_is_fast_forwarded_exactly() {
        // LOAD s3, 18 / SUB s3, 01 / JUMP NZ, 001 / OUTPUT s3, 01: 24 passes of 4 cycles.
        let prog = [0x01318, 0x19301, 0x36001, 0x2D301];
        let mut fast = Cpu::new(Config::default(), &prog);
        let mut bus = Recorder::default();
        let mut steps = 0;
        fast.run_fast(&mut bus, 1_000, |b| {
            steps += 1;
            !b.events.is_empty()
        });
        // LOAD D at 5; the loop 7..103; OUTPUT D at 103, strobe in 104.
        assert_eq!((bus.events[0].cycle, bus.events[0].value), (104, 0));
        assert_eq!(fast.cycle(), 105);
        // Four reset cycles, LOAD, OUTPUT: the 48 instructions of the loop took one step.
        assert!(steps < 10, "the countdown was not fast-forwarded: {steps} steps");
    }
}
