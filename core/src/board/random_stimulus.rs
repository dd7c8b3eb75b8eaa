//! A seeded random stimulus for a design, of the inputs it has pins for: presses of its
//! buttons, one CPU reset in the middle of the run (more may come), switch changes, and where
//! the design reaches them, text to its USB-UART, keys of the keyboard and the board's tilt.
//! `botsim board --random-stimulus SEED` runs it; the differential check
//! (`--check`, scripts/dev/corpus.py) compares the boards under it.
//!
//! The same seed, pins and span give the same events, on every machine.
//!
//! ```
//! use botsim_core::frontend::pins::Role;
//! use botsim_core::board::random_stimulus::random_stimulus;
//! let pins = [Role::Clock, Role::Reset { active_low: true }, Role::Button(0), Role::Switches];
//! let s = random_stimulus(7, &pins, 10_000_000_000);
//! assert_eq!(s, random_stimulus(7, &pins, 10_000_000_000));
//! assert!(s.presses.iter().any(|p| p.button.is_none()), "the CPU reset");
//! assert!(s.presses.iter().all(|p| p.button.is_none() || p.button == Some(0)), "only btnC");
//! assert!(s.keys.is_empty() && s.uart.is_empty() && s.tilts.is_empty());
//! ```

use super::keyboard::Key;
use super::stimulus::{KeyPress, Press, Stimulus, POWER_ON_RESET_PS};
use crate::frontend::pins::{Peripheral, Role};
use crate::PS_PER_CYCLE;

/// How many events a stimulus has besides its one certain CPU reset.
pub const EVENTS: u64 = 16;

/// Keys a random stimulus presses: letters, digits and the keys games read.
const KEYS: [&str; 12] = [
    "KeyA",
    "KeyD",
    "KeyS",
    "KeyW",
    "Space",
    "Enter",
    "ArrowUp",
    "ArrowDown",
    "ArrowLeft",
    "ArrowRight",
    "Digit1",
    "KeyQ",
];

/// SplitMix64: small, seedable, the same everywhere.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A value in `0..n` (`n` > 0).
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }

    /// A value in `lo..hi` (`lo` < `hi`), on a cycle of the 100 MHz clock.
    fn within(&mut self, lo: u64, hi: u64) -> u64 {
        let t = lo + self.below(hi - lo);
        (t - t % PS_PER_CYCLE).max(lo.next_multiple_of(PS_PER_CYCLE))
    }
}

/// What a random event may be, for the pins the design has.
#[derive(Clone, Copy)]
enum Event {
    Press(u8),
    Switches,
    Uart,
    Key,
    Tilt,
}

/// The stimulus of `seed` for a design with the pins `roles`, its events within `span_ps` of
/// board time (after the power-on reset). Presses and keys are held from a 200th to an 8th
/// of the span, so that a debouncer of any length sees some of them.
pub fn random_stimulus(seed: u64, roles: &[Role], span_ps: u64) -> Stimulus {
    let mut rng = Rng(seed);
    let has = |r: Role| roles.contains(&r);
    let mut kinds: Vec<Event> = (0..5u8).filter(|&b| has(Role::Button(b))).map(Event::Press).collect();
    if has(Role::Switches) {
        // Switches as often as a button.
        kinds.extend([Event::Switches, Event::Switches]);
    }
    if has(Role::UartRx) {
        kinds.push(Event::Uart);
    }
    if has(Role::Ps2Clock) && has(Role::Ps2Data) {
        kinds.extend([Event::Key, Event::Key]);
    }
    if roles.iter().any(|r| r.peripheral() == Some(Peripheral::Accelerometer)) {
        kinds.push(Event::Tilt);
    }
    let mut s = Stimulus::default();
    let start = POWER_ON_RESET_PS + POWER_ON_RESET_PS / 5;
    let span = span_ps.max(start + 1_000_000);
    let held = |rng: &mut Rng| rng.within(span / 200 + 1, span / 8 + 2);
    if roles.iter().any(|r| matches!(r, Role::Reset { .. })) {
        // One CPU reset for certain, in the middle third: the CPUs, the bot and the
        // interfaces restart while everything else goes on.
        let at = rng.within(span / 3, 2 * span / 3);
        s.presses.push(Press { button: None, from: at, to: at + rng.within(50_000_000, 200_000_000) });
    }
    if kinds.is_empty() {
        return s;
    }
    for _ in 0..EVENTS {
        let at = rng.within(start, span);
        match kinds[rng.below(kinds.len() as u64) as usize] {
            Event::Press(b) => {
                let len = held(&mut rng);
                s.presses.push(Press { button: Some(b), from: at, to: at + len });
            }
            Event::Switches => s.switches.push((at, rng.below(1 << 16) as u16)),
            Event::Uart => {
                let n = rng.within(1, 9);
                let text = (0..n).map(|_| b"abcdefghijklmnopqrstuvwxyz0123456789 \r"[rng.below(38) as usize]);
                s.uart.push((at, text.collect()));
            }
            Event::Key => {
                let key = Key::named(KEYS[rng.below(KEYS.len() as u64) as usize]).expect("a key of the table");
                let len = held(&mut rng);
                s.keys.push(KeyPress { key, from: at, to: at + len });
            }
            Event::Tilt => {
                let mut g = || rng.below(2001) as i32 - 1000;
                s.tilts.push((at, [g(), g(), g()]));
            }
        }
    }
    in_time_order(&mut s);
    s
}

/// Each kind of event of `s` in time order.
fn in_time_order(s: &mut Stimulus) {
    s.presses.sort_by_key(|p| p.from);
    s.keys.sort_by_key(|k| k.from);
    s.switches.sort_by_key(|&(t, _)| t);
    s.uart.sort_by_key(|&(t, _)| t);
    s.tilts.sort_by_key(|&(t, _)| t);
}

/// `other`'s events added to `s`, each kind in time order.
pub fn merge(s: &mut Stimulus, other: Stimulus) {
    s.presses.extend(other.presses);
    s.keys.extend(other.keys);
    s.switches.extend(other.switches);
    s.uart.extend(other.uart);
    s.tilts.extend(other.tilts);
    in_time_order(s);
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPAN: u64 = 50_000_000_000;

    #[test]
    fn events_fall_within_the_span_after_the_power_on_reset() {
        let all = [
            Role::Reset { active_low: true },
            Role::Button(0),
            Role::Button(4),
            Role::Switches,
            Role::UartRx,
            Role::Ps2Clock,
            Role::Ps2Data,
            Role::AclMiso,
        ];
        for seed in 0..50 {
            let s = random_stimulus(seed, &all, SPAN);
            let times: Vec<u64> = s
                .presses
                .iter()
                .map(|p| p.from)
                .chain(s.keys.iter().map(|k| k.from))
                .chain(s.switches.iter().map(|x| x.0))
                .chain(s.uart.iter().map(|x| x.0))
                .chain(s.tilts.iter().map(|x| x.0))
                .collect();
            assert_eq!(times.len() as u64, EVENTS + 1, "seed {seed}");
            assert!(times.iter().all(|&t| t > POWER_ON_RESET_PS && t < SPAN), "seed {seed}: {times:?}");
            assert_eq!(s.presses.iter().filter(|p| p.button.is_none()).count(), 1);
            assert!(s.presses.iter().all(|p| p.to > p.from) && s.keys.iter().all(|k| k.to > k.from));
        }
    }

    #[test]
    fn only_the_pins_the_design_has_and_every_kind_over_seeds() {
        let all = [
            Role::Button(1),
            Role::Button(3),
            Role::Switches,
            Role::UartRx,
            Role::Ps2Clock,
            Role::Ps2Data,
            Role::AclSck,
        ];
        let mut seen = [false; 5];
        for seed in 0..40 {
            let s = random_stimulus(seed, &all, SPAN);
            assert!(s.presses.iter().all(|p| matches!(p.button, Some(1) | Some(3))), "no reset pin: no reset");
            for (k, any) in [
                !s.presses.is_empty(),
                !s.switches.is_empty(),
                !s.uart.is_empty(),
                !s.keys.is_empty(),
                !s.tilts.is_empty(),
            ]
            .into_iter()
            .enumerate()
            {
                seen[k] |= any;
            }
        }
        assert_eq!(seen, [true; 5]);
        // A design with no input pins but its clock gets nothing.
        assert_eq!(random_stimulus(3, &[Role::Clock, Role::Leds], SPAN), Stimulus::default());
        // Other seeds, other events; the text the file format reads back.
        let (a, b) = (random_stimulus(1, &all, SPAN), random_stimulus(2, &all, SPAN));
        assert_ne!(a, b);
        let text = a.text(SPAN, "seed 1");
        assert_eq!(Stimulus::parse(std::path::Path::new("s.txt"), &text).unwrap().text(SPAN, "seed 1"), text);
    }
}
