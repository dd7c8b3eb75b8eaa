//! The RTL core's port timing against the exact cycle numbers of spec/kcpsm6.md §2.
//! These do not use the ISS: the expected numbers are the spec's.

use botsim::cpu::{CpuHarness, Ports};
use kcpsm6::asm::assemble_str;
use kcpsm6::iss::{Pins, ScratchPad};

fn harness(src: &str) -> CpuHarness {
    let mut h = CpuHarness::new(ScratchPad::B64);
    h.load_program(&assemble_str(src).unwrap_or_else(|e| panic!("{e}")).image.words[..]);
    h
}

/// Ports of cycles 0..n, with pins from `pins(cycle)`.
fn trace(h: &mut CpuHarness, n: u64, pins: impl Fn(u64) -> Pins) -> Vec<Ports> {
    (0..n).map(|c| h.tick(pins(c)).unwrap()).collect()
}

fn cycles_where(t: &[Ports], f: impl Fn(&Ports) -> bool) -> Vec<usize> {
    t.iter().enumerate().filter(|(_, p)| f(p)).map(|(i, _)| i).collect()
}

#[test]
fn power_up_self_start() {
    // One extra bram_enable pulse in cycle 1, the self-start fetch in 4, first D in 5 (§2.4, §2.8).
    let mut h = harness("LOAD s0, 01\nLOAD s0, 02\n");
    let t = trace(&mut h, 8, |_| Pins::default());
    assert_eq!(cycles_where(&t, |p| p.bram_enable), vec![1, 4, 6]);
    assert!(t[..5].iter().all(|p| p.address == 0));
    assert_eq!(t[5].instruction, 0x01001, "000 is on `instruction` in its D cycle");
    assert_eq!((t[6].address, t[6].bram_enable), (1, true), "F of 000 fetches 001");
}

#[test]
fn output_timing_table() {
    // §2.2: OUTPUT s0, 56 with s0 = 12: D shows port_id/out_port without strobe, F strobes.
    let mut h = harness("LOAD s0, 12\nOUTPUT s0, 56\n");
    let t = trace(&mut h, 10, |_| Pins::default());
    let (d, f) = (&t[7], &t[8]);
    assert_eq!(
        (d.address, d.bram_enable, d.instruction, d.port_id, d.out_port, d.write_strobe),
        (1, false, 0x2D056, 0x56, 0x12, false)
    );
    assert_eq!(
        (f.address, f.bram_enable, f.instruction, f.port_id, f.out_port, f.write_strobe),
        (2, true, 0x2D056, 0x56, 0x12, true)
    );
    assert_eq!(cycles_where(&t, |p| p.write_strobe || p.read_strobe || p.k_write_strobe), vec![8]);
}

#[test]
fn outputk_pulses_only_k_write_strobe() {
    let mut h = harness("OUTPUTK AB, C\n");
    let t = trace(&mut h, 8, |_| Pins::default());
    assert_eq!((t[6].k_write_strobe, t[6].write_strobe, t[6].out_port, t[6].port_id), (true, false, 0xAB, 0xBC));
}

#[test]
fn input_samples_in_port_at_the_end_of_its_second_cycle() {
    // The harness's in_port in cycle t is inputs[port] ^ (t - 1); INPUT at 000 has D 5, F 6:
    // it reads inputs[3C] ^ 5, then OUTPUTs it.
    let mut h = harness("INPUT s0, 3C\nOUTPUT s0, 01\n");
    let mut inputs = [0u8; 256];
    inputs[0x3C] = 0xA0;
    h.set_inputs(&inputs);
    let t = trace(&mut h, 10, |_| Pins::default());
    assert!(t[6].read_strobe);
    assert_eq!((t[8].write_strobe, t[8].out_port), (true, 0xA0 ^ 5));
}

#[test]
fn external_reset_sequence() {
    // §2.4 example: reset high in 21-22 -> r = 23 -> fetch in 26 -> 000's D in 27.
    let mut h = harness("LOAD s0, 01\nLOAD s0, 02\nJUMP 001\n");
    let t = trace(&mut h, 29, |c| Pins { reset: c == 21 || c == 22, ..Pins::default() });
    let fetches: Vec<usize> = cycles_where(&t, |p| p.bram_enable).into_iter().filter(|&c| c >= 21).collect();
    assert_eq!(fetches[..2], [22, 26], "k+1 still makes the step decided in k (22 is F), then 26");
    assert!(t[23..26].iter().all(|p| !p.bram_enable && p.address == 0));
    assert_eq!((t[27].address, t[27].instruction), (0, 0x01001));
    assert_eq!(h.state().registers[0], 0x01, "000 ran again (its write at the end of 28)");
}

#[test]
fn reset_keeps_registers_and_clears_flags_ie_bank_and_stack() {
    let src = "LOAD s3, 77\nSTORE s3, 05\nREGBANK B\nLOAD s1, 00\nSUB s1, 01\nENABLE INTERRUPT\nCALL 100\n";
    let mut h = harness(src);
    trace(&mut h, 20, |_| Pins::default());
    let s = h.state();
    assert!(s.carry && s.bank && s.interrupt_enable && s.stack_pointer == 1);
    trace(&mut h, 3, |_| Pins { reset: true, ..Pins::default() });
    let s = h.state();
    assert_eq!(
        (s.pc, s.carry, s.zero, s.bank, s.interrupt_enable, s.stack_pointer),
        (0, false, false, false, false, 0)
    );
    assert_eq!((s.registers[3], s.registers[16 + 1], s.scratch_pad[5]), (0x77, 0xFF, 0x77));
}

#[test]
fn interrupt_example_trace() {
    // §2.6: 25 (D) interrupt rises; 27 cancels; 28 ack with the vector fetched; 29 vector's D.
    let mut h = harness("ENABLE INTERRUPT\n");
    let t = trace(&mut h, 34, |c| Pins { interrupt: (25..29).contains(&c), ..Pins::default() });
    assert_eq!(cycles_where(&t, |p| p.interrupt_ack), vec![28]);
    assert_eq!((t[28].address, t[28].bram_enable), (0x3FF, true));
    assert_eq!(t[29].address, 0x3FF);
    assert_eq!(h.state().stack_pointer, 1);
}

#[test]
fn interrupt_from_an_f_cycle_acks_four_later_and_one_cycle_f_pulses_are_missed() {
    let mut h = harness("ENABLE INTERRUPT\n");
    let t = trace(&mut h, 40, |c| Pins { interrupt: c == 16 || (26..31).contains(&c), ..Pins::default() });
    assert_eq!(cycles_where(&t, |p| p.interrupt_ack), vec![30]);
}

#[test]
fn enable_interrupt_with_a_pending_request() {
    // ENABLE at 000 (D 5, F 6) with the request held: 001 is cancelled, vector fetched in 8.
    let mut h = harness("ENABLE INTERRUPT\nLOAD s0, 11\n");
    let t = trace(&mut h, 12, |_| Pins { interrupt: true, ..Pins::default() });
    assert_eq!(cycles_where(&t, |p| p.interrupt_ack), vec![8]);
    assert_eq!(h.state().registers[0], 0, "the cancelled LOAD never wrote");
}

#[test]
fn sleep_completes_the_instruction_and_wakes_two_cycles_after_release() {
    // §2.7: sleep high from 6: 001 (OUTPUT) decodes in 7, strobes in 8 (idle); sleep low
    // first in m = 20: fetch in 22, D in 23.
    let mut h = harness("LOAD s0, 01\nOUTPUT s0, 10\nLOAD s1, 02\n");
    let t = trace(&mut h, 26, |c| Pins { sleep: (6..20).contains(&c), ..Pins::default() });
    assert!(t[8].write_strobe && !t[8].bram_enable);
    assert!(t[8..22].iter().all(|p| !p.bram_enable && p.address == 2));
    assert!(t[22].bram_enable);
    assert_eq!((t[23].address, t[23].instruction), (2, 0x01102));
}

#[test]
fn stack_overflow_restarts_and_the_target_still_writes() {
    // 30 nested CALLs fit; the 31st overflows. Its target's register write still happens.
    let mut h = harness("LOAD s0, 00\nrec: ADD s0, 01\nCALL rec\n");
    let mut restarted = None;
    for c in 0..400u64 {
        let p = h.tick(Pins::default()).unwrap();
        if c > 10 && p.address == 0 && p.bram_enable {
            restarted = Some(c);
            break;
        }
    }
    assert!(restarted.is_some(), "no internal reset");
    // s0: 1 from the first ADD, +1 after each of the 30 CALLs that fit, +1 from the
    // overflowing CALL's target (ADD), which still writes during the reset sequence.
    assert_eq!(h.state().registers[0], 32);
}

#[test]
fn scratch_pad_size_aliases_addresses() {
    for (size, addr) in [(ScratchPad::B64, 0x03usize), (ScratchPad::B128, 0x43), (ScratchPad::B256, 0xC3)] {
        let mut h = CpuHarness::new(size);
        h.load_program(&assemble_str("LOAD s1, 5A\nSTORE s1, C3\n").unwrap().image.words[..]);
        trace(&mut h, 12, |_| Pins::default());
        let s = h.state();
        assert_eq!(s.scratch_pad.len(), size.bytes());
        assert_eq!(s.scratch_pad[addr], 0x5A, "{size:?}");
    }
}

#[test]
fn hwbuild_and_vector_parameters_reach_the_core() {
    let mut h = CpuHarness::new(ScratchPad::B128);
    let cfg = h.config();
    assert_eq!((cfg.hwbuild, cfg.interrupt_vector), (0x5A, 0x1C0));
    h.load_program(&assemble_str("HWBUILD s2\nENABLE INTERRUPT\n").unwrap().image.words[..]);
    let t = trace(&mut h, 20, |c| Pins { interrupt: c > 8, ..Pins::default() });
    assert_eq!(h.state().registers[2], 0x5A);
    let ack = cycles_where(&t, |p| p.interrupt_ack);
    assert_eq!(t[ack[0]].address, 0x1C0);
}

#[test]
fn vcd_is_written_on_request() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("cpu.vcd");
    let mut h = harness("LOAD s0, 01\nOUTPUT s0, 02\n");
    h.open_vcd(&path).unwrap();
    trace(&mut h, 20, |_| Pins::default());
    h.close_vcd();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("$timescale"));
    assert!(text.contains(" write_strobe "));
    assert!(text.contains("$scope module cpu $end"));
    assert!(h.open_vcd(&dir.path().join("no/such/dir/x.vcd")).is_err());
}
