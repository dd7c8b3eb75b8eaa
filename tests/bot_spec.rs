//! RtlBot 2.0 against spec/botsim.md, behaviour by behaviour. Expected values are written
//! out from the spec's tables and worked traces (not taken from the model or the RTL).

mod common;

use botsim::firmware::{Compat, Timing};
use botsim::regs::{MotCtl, Movement, Orientation};
use botsim::world::{Cell, World};
use botsim::{RtlBot, Snapshot};

/// A bot in `fast` timing on `world`, past its sample 0.
fn bot(world: World, threshold: u8, compat: Compat) -> (RtlBot, Snapshot) {
    let mut b =
        RtlBot::builder().timing(Timing::Fast).threshold(threshold).compat(compat).world(world).build().unwrap();
    let s0 = b.wait_update().unwrap();
    (b, s0)
}

fn run(b: &mut RtlBot, m: u8, n: usize) -> Vec<Snapshot> {
    b.set_motors(MotCtl(m));
    b.run_samples(n).unwrap()
}

/// (x, y, bot_info, sensors, lm, rm) of a snapshot.
fn row(s: &Snapshot) -> (u8, u8, u8, u8, u8, u8) {
    let r = s.regs;
    (r.loc_x, r.loc_y, r.bot_info, r.sensors, r.lm_dist, r.rm_dist)
}

/// The spec's forward step per heading (§5.3 table).
const STEP: [(i16, i16); 8] = [(0, -1), (1, -1), (1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1)];

/// The spec's proximity cells per heading, (L, C, R) (§7.1), symmetric SW.
const PROX: [[(i16, i16); 3]; 8] = [
    [(-1, -1), (0, -1), (1, -1)],
    [(1, -2), (1, -1), (2, -1)],
    [(1, -1), (1, 0), (1, 1)],
    [(2, 1), (1, 1), (1, 2)],
    [(1, 1), (0, 1), (-1, 1)],
    [(-1, 2), (-1, 1), (-2, 1)],
    [(-1, 1), (-1, 0), (-1, -1)],
    [(-2, -1), (-1, -1), (-1, -2)],
];

/// Turn from East to heading `o` with slow right turns (threshold 1), then stop; returns the
/// first snapshot that shows heading `o`.
fn face(b: &mut RtlBot, o: u8) -> Snapshot {
    let turns = (o as usize + 8 - 2) % 8;
    if turns > 0 {
        run(b, 0x30, turns);
    }
    let s = run(b, 0x00, 1)[0];
    assert_eq!(s.orientation() as u8, o);
    s
}

#[test]
fn reset_state_and_initial_dump() {
    let mut b = RtlBot::builder().timing(Timing::Fast).build().unwrap();
    // All outputs are 0 from configuration until the first snapshot (spec §6).
    let mut cycles = 0;
    loop {
        let o = b.tick().unwrap();
        if o.upd_sysregs {
            break;
        }
        if o.regs != Default::default() {
            // the registers load 3 clocks before the pulse (§8.3)
            assert!(cycles > 100, "registers changed too early, cycle {cycles}");
        }
        cycles += 1;
        assert!(cycles < 5_000, "no first pulse");
    }
    b.reset(3).unwrap();
    let o = b.tick().unwrap();
    assert_eq!((o.regs, o.upd_sysregs), (Default::default(), false), "reset clears the visible registers");
    let s0 = b.wait_update().unwrap();
    assert_eq!(s0.sample, 0);
    // (0x40, 0x40), stopped facing East, on the built-in start line, counters 0.
    assert_eq!(row(&s0), (0x40, 0x40, 0x02, 0x00, 0, 0));
}

#[test]
fn all_sixteen_motor_states_and_ignored_speed_bits() {
    // (lm_on, rm_on, lm_dir, rm_dir) -> Mvmt (§4); bits 7, 6, 3, 2 set in half the cases.
    let table: [(u8, u8, u8, u8, u8); 16] = [
        (0, 0, 0, 0, 0x0),
        (0, 0, 0, 1, 0x0),
        (0, 0, 1, 0, 0x0),
        (0, 0, 1, 1, 0x0),
        (0, 1, 0, 0, 0xE),
        (0, 1, 0, 1, 0xC),
        (0, 1, 1, 0, 0xE),
        (0, 1, 1, 1, 0xC),
        (1, 0, 0, 0, 0xC),
        (1, 0, 0, 1, 0xC),
        (1, 0, 1, 0, 0xE),
        (1, 0, 1, 1, 0xE),
        (1, 1, 0, 0, 0x8),
        (1, 1, 0, 1, 0xD),
        (1, 1, 1, 0, 0xF),
        (1, 1, 1, 1, 0x4),
    ];
    let (mut b, _) = bot(World::builtin(), 200, Compat::Symmetric);
    for (i, &(lo, ro, ld, rd, mv)) in table.iter().enumerate() {
        let noise = if i % 2 == 0 { 0xCC } else { 0x00 };
        let m = lo << 5 | ld << 4 | ro << 1 | rd | noise;
        let s = run(&mut b, m, 1)[0];
        assert_eq!(s.regs.bot_info >> 4, mv, "MotCtl {m:02X}");
    }
    // 0x44 has speed 010 on both motors: both off.
    assert_eq!(run(&mut b, 0x44, 1)[0].movement(), Movement::Stopped);
}

#[test]
fn slow_and_fast_turns_through_all_headings() {
    let (mut b, _) = bot(World::empty(), 3, Compat::Symmetric);
    // Slow right (0x30): +45 degrees per 3 samples; the new heading shows one sample later.
    let s = run(&mut b, 0x30, 24);
    let headings: Vec<u8> = s.iter().map(|s| s.regs.bot_info & 7).collect();
    assert_eq!(headings, [2, 2, 2, 3, 3, 3, 4, 4, 4, 5, 5, 5, 6, 6, 6, 7, 7, 7, 0, 0, 0, 1, 1, 1]);
    assert!(s.iter().all(|s| s.movement() == Movement::SlowRight && s.regs.rm_dist == 0));
    // Slow left (0x03): -45. Fast right (0x32): +90. Fast left (0x23): -90.
    let h: Vec<u8> = run(&mut b, 0x03, 9).iter().step_by(3).map(|s| s.regs.bot_info & 7).collect();
    assert_eq!(h, [2, 1, 0]);
    let h: Vec<u8> = run(&mut b, 0x32, 12).iter().step_by(3).map(|s| s.regs.bot_info).collect();
    assert_eq!(h, [0xF7, 0xF1, 0xF3, 0xF5]);
    let h: Vec<u8> = run(&mut b, 0x23, 12).iter().step_by(3).map(|s| s.regs.bot_info).collect();
    assert_eq!(h, [0xD7, 0xD5, 0xD3, 0xD1]);
}

#[test]
fn forward_and_reverse_in_all_eight_directions() {
    for o in 0..8u8 {
        for (m, sign) in [(0x33u8, 1i16), (0x22, -1)] {
            let (mut b, _) = bot(World::empty(), 1, Compat::Symmetric);
            let start = face(&mut b, o);
            let (x0, y0) = (start.regs.loc_x as i16, start.regs.loc_y as i16);
            let s = run(&mut b, m, 4);
            let (dx, dy) = STEP[o as usize];
            // Threshold 1: each sample moves; the move of sample k shows in sample k+1.
            for (k, s) in s.iter().enumerate() {
                let want = (((x0 + sign * dx * k as i16) & 0xFF) as u8, ((y0 + sign * dy * k as i16) & 0xFF) as u8);
                assert_eq!(s.location(), want, "heading {o} MotCtl {m:02X} sample {k}");
                assert_eq!(s.orientation() as u8, o);
            }
        }
    }
}

#[test]
fn blocked_moves_check_only_the_destination_and_still_clear_the_counters() {
    // Facing NE from (64, 64): the side cells (65, 64) and (64, 63) are walls, the diagonal
    // destination (65, 63) is free: the move succeeds. Then (66, 62) blocks.
    let mut w = World::empty();
    w.set(65, 64, Cell::Obstruction);
    w.set(64, 63, Cell::Obstruction);
    w.set(66, 62, Cell::Obstruction);
    let (mut b, _) = bot(w, 3, Compat::Symmetric);
    run(&mut b, 0x03, 3); // slow left: E -> NE after 3 samples
    let s = run(&mut b, 0x33, 10);
    let got: Vec<((u8, u8), (u8, u8))> = s.iter().map(|s| (s.location(), s.distances())).collect();
    assert_eq!(got[0], ((64, 64), (1, 1)));
    assert_eq!(got[3], ((65, 63), (1, 1)), "diagonal between two walls");
    // Blocked from now on, counters keep clearing every 3 samples.
    assert_eq!(got[6..], [((65, 63), (1, 1)), ((65, 63), (2, 2)), ((65, 63), (3, 3)), ((65, 63), (1, 1))]);
}

#[test]
fn counts_carry_across_command_changes() {
    // §5.4: 0x33 for 14 samples, 0x00 for 3, 0x30 for 1, then 0x00.
    let (mut b, _) = bot(World::builtin(), 15, Compat::Symmetric);
    let a = run(&mut b, 0x33, 14);
    assert_eq!(row(&a[13]), (0x40, 0x40, 0x42, 0x00, 14, 14));
    for s in run(&mut b, 0x00, 3) {
        assert_eq!(row(&s), (0x40, 0x40, 0x02, 0x00, 14, 14));
    }
    assert_eq!(row(&run(&mut b, 0x30, 1)[0]), (0x40, 0x40, 0xE2, 0x00, 15, 14));
    assert_eq!(row(&run(&mut b, 0x00, 1)[0]), (0x40, 0x40, 0x03, 0x00, 0, 0));
}

fn sensors_with_obstacle(o: u8, cell: (i16, i16), compat: Compat) -> u8 {
    let mut w = World::empty();
    w.set((64 + cell.0) as u8, (64 + cell.1) as u8, Cell::Obstruction);
    let (mut b, _) = bot(w, 1, compat);
    face(&mut b, o).regs.sensors
}

#[test]
fn proximity_sensors_in_all_headings_and_both_compat_modes() {
    for o in 0..8u8 {
        for (i, &cell) in PROX[o as usize].iter().enumerate() {
            let want = [0x17, 0x1F, 0x0F][i]; // ProxL / both / ProxR, off the line
            for compat in [Compat::Symmetric, Compat::BotSim20] {
                let want = if compat == Compat::BotSim20 && o == 5 && i == 2 { 0x07 } else { want };
                assert_eq!(sensors_with_obstacle(o, cell, compat), want, "heading {o} cell {i} {compat:?}");
            }
        }
    }
    // The 2014 program's SW right-front cell is (X-1, Y).
    assert_eq!(sensors_with_obstacle(5, (-1, 0), Compat::BotSim20), 0x0F);
    assert_eq!(sensors_with_obstacle(5, (-1, 0), Compat::Symmetric), 0x07);
}

#[test]
fn line_sensors_and_reserved_cells() {
    let mut w = World::empty();
    w.set(64, 64, Cell::Line);
    w.set(65, 64, Cell::Reserved); // ahead: reserved is passable, no line, no proximity
    w.set(66, 64, Cell::Line);
    let (mut b, s0) = bot(w, 1, Compat::Symmetric);
    assert_eq!(s0.regs.sensors, 0x00, "on the line, nothing ahead");
    let s = run(&mut b, 0x33, 3);
    assert_eq!((s[1].location(), s[1].regs.sensors), ((65, 64), 0x07), "on reserved: off the line");
    assert_eq!((s[2].location(), s[2].regs.sensors), ((66, 64), 0x00));
}

#[test]
fn coordinates_wrap_on_a_world_without_walls() {
    // Reverse West from X = 64: 0, then 0xFF (no clamp, spec §3.5).
    let (mut b, _) = bot(World::empty(), 1, Compat::Symmetric);
    let s = run(&mut b, 0x22, 67);
    assert_eq!(s[64].location(), (0, 64));
    assert_eq!(s[65].location(), (0xFF, 64));
    assert_eq!(s[66].location(), (0xFE, 64));
    // Forward North from Y = 64 (fast left from East): 0, then 0xFF.
    let (mut b, _) = bot(World::empty(), 1, Compat::Symmetric);
    run(&mut b, 0x23, 1);
    let s = run(&mut b, 0x33, 67);
    assert_eq!(s[0].orientation(), Orientation::North);
    assert_eq!(s[64].location(), (64, 0));
    assert_eq!(s[65].location(), (64, 0xFF));
}

#[test]
fn counters_count_to_a_large_threshold_then_clear() {
    // 8-bit counters, compared with >= (spec §5.3): with T = 200 they read 1..200, then 1.
    let (mut b, _) = bot(World::empty(), 200, Compat::Symmetric);
    let s = run(&mut b, 0x33, 201);
    assert!(s[..200]
        .iter()
        .enumerate()
        .all(|(k, s)| s.distances() == (k as u8 + 1, k as u8 + 1) && s.location() == (64, 64)));
    assert_eq!((s[200].distances(), s[200].location()), ((1, 1), (65, 64)));
}

#[test]
fn two_phase_load_and_the_two_clock_pulse() {
    let (mut b, _) = bot(World::builtin(), 1, Compat::Symmetric);
    b.set_motors(MotCtl::FORWARD);
    // Watch every cycle of the next samples, from the first cycle of sample 0's pulse.
    let first = b.cycle();
    let mut prev = b.tick().unwrap();
    assert!(prev.upd_sysregs);
    let mut changes: Vec<(u64, Vec<&str>)> = vec![];
    let mut pulses: Vec<(u64, u64)> = vec![];
    let mut high_since = Some(first);
    for _ in 0..10_000 {
        let c = b.cycle();
        let o = b.tick().unwrap();
        let mut which = vec![];
        for (name, a, z) in [
            ("x", prev.regs.loc_x, o.regs.loc_x),
            ("y", prev.regs.loc_y, o.regs.loc_y),
            ("s", prev.regs.sensors, o.regs.sensors),
            ("i", prev.regs.bot_info, o.regs.bot_info),
        ] {
            if a != z {
                which.push(name);
            }
        }
        if !which.is_empty() {
            changes.push((c, which));
        }
        match (o.upd_sysregs, high_since) {
            (true, None) => high_since = Some(c),
            (false, Some(h)) => {
                pulses.push((h, c - h));
                high_since = None;
            }
            _ => {}
        }
        prev = o;
        if pulses.len() == 3 {
            break;
        }
    }
    assert!(pulses.iter().all(|&(_, w)| w == 2), "upd_sysregs is high for exactly 2 clocks: {pulses:?}");
    // The location and the heading change in one cycle, 3 full clocks before the pulse rises.
    let move_change = changes.iter().find(|(_, w)| w.contains(&"x")).expect("the bot moved");
    let next_pulse = pulses.iter().find(|&&(h, _)| h > move_change.0).unwrap().0;
    // They change at the end of s+1, so they are first visible in s+2; upd rises in s+5:
    // three full clocks of stable new values before the pulse (spec §8.3).
    assert_eq!(next_pulse - move_change.0, 3);
    assert!(changes.iter().all(|(c, _)| pulses.iter().any(|&(h, _)| h == c + 3)), "{changes:?} {pulses:?}");
}

#[test]
fn hw_timing_sample_period_is_about_50_ms() {
    let mut b = RtlBot::builder().build().unwrap();
    let s: Vec<Snapshot> = (0..3).map(|_| b.wait_update().unwrap()).collect();
    let period = s[2].cycle - s[1].cycle;
    // 5,313,006 clocks of busy-wait (spec §11.2) plus the rest of the iteration; the 2014
    // program's period is 5,313,270 (§11.1).
    assert!((5_313_006 + 100..5_313_006 + 1_000).contains(&period), "period {period}");
    eprintln!("hw sample period: {period} clocks ({:.3} ms at 100 MHz)", period as f64 / 1e5);
}

#[test]
fn video_port_contents_and_two_clock_latency() {
    let w = World::builtin();
    let (mut b, _) = bot(w.clone(), 15, Compat::Symmetric);
    for (row, col) in [(0u16, 0u16), (64, 64), (64, 70), (46, 36), (100, 104), (127, 127), (70, 72)] {
        assert_eq!(b.read_video(row, col).unwrap(), w.get(col as u8, row as u8), "({row}, {col})");
    }
    // Only bits [6:0] are used.
    assert_eq!(b.read_video(64 + 128, 64 + 256).unwrap(), Cell::Line);
    assert_eq!(b.read_video(0x3FF, 0x3FF).unwrap(), w.get(127, 127));
    assert_eq!(b.read_video(0x2C0, 0x1C0).unwrap(), w.get(64, 64), "row 0x2C0 = 64 + 5 x 128");
    // Latency: the value appears exactly two clocks after the address.
    b.set_video(0, 0);
    b.run(3).unwrap();
    b.set_video(64, 64);
    let seen: Vec<u8> = (0..4).map(|_| b.tick().unwrap().vid_pixel_out).collect();
    assert_eq!(seen, [2, 2, 1, 1]);
}

/// The §5.4 worked traces, on the course's world_map_part1 (read from BOTSIM_REFERENCE).
#[test]
fn worked_traces_on_world_map_part1() {
    let Some(path) = common::reference_map("world_map_part1.txt") else { return };
    let part1 = World::load(&path).unwrap();
    let fresh = || bot(part1.clone(), 15, Compat::BotSim20);

    let (mut b, _) = fresh();
    for s in run(&mut b, 0x00, 5) {
        assert_eq!(row(&s), (0x40, 0x40, 0x02, 0x00, 0, 0));
    }

    let (mut b, _) = fresh();
    let s = run(&mut b, 0x33, 31);
    for (k, s) in s[..15].iter().enumerate() {
        assert_eq!(row(s), (0x40, 0x40, 0x42, 0x00, k as u8 + 1, k as u8 + 1));
    }
    assert_eq!(row(&s[15]), (0x41, 0x40, 0x42, 0x00, 1, 1));
    assert_eq!(s[30].location(), (0x42, 0x40));

    let (mut b, _) = fresh();
    let s = run(&mut b, 0x30, 31);
    assert!(s[..15].iter().enumerate().all(|(k, s)| s.regs.bot_info == 0xE2 && s.distances() == (k as u8 + 1, 0)));
    assert_eq!((s[15].regs.bot_info, s[15].distances()), (0xE3, (1, 0)));
    assert_eq!(s[30].regs.bot_info, 0xE4);

    let (mut b, _) = fresh();
    let info: Vec<u8> = run(&mut b, 0x32, 61).iter().step_by(15).map(|s| s.regs.bot_info).collect();
    assert_eq!(info, [0xF2, 0xF4, 0xF6, 0xF0, 0xF2]);
    let (mut b, _) = fresh();
    let info: Vec<u8> = run(&mut b, 0x23, 61).iter().step_by(15).map(|s| s.regs.bot_info).collect();
    assert_eq!(info, [0xD2, 0xD0, 0xD6, 0xD4, 0xD2]);

    // Reverse from E at (64, 64): 3F at sample 16, 3E at 31, then blocked by (0x3D, 0x40).
    let (mut b, _) = fresh();
    let s = run(&mut b, 0x22, 60);
    assert_eq!(s[15].regs.loc_x, 0x3F);
    assert_eq!(s[30].regs.loc_x, 0x3E);
    assert!(s[30..].iter().all(|s| s.regs.loc_x == 0x3E && s.regs.bot_info == 0x82 && s.regs.sensors == 0x07));
    assert_eq!(s[45].distances(), (1, 1), "counters keep clearing while blocked");
    assert_eq!(Orientation::from_bits(s[59].regs.bot_info), Orientation::East);
}
