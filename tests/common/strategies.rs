//! Random worlds and motor sequences for the property tests (scoreboard, lock-step).

use botsim::world::{Cell, World};
use proptest::prelude::*;

/// A random world: scattered cells of every value, with a bias to keep it passable.
pub fn world() -> impl Strategy<Value = World> {
    (any::<u64>(), 0u32..40, 0u32..30, 0u32..8, any::<bool>()).prop_map(|(seed, walls, lines, reserved, border)| {
        let mut w = World::empty();
        let mut x = seed | 1;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        // Dense features near the start so the bot meets them.
        for (count, cell) in [(walls, Cell::Obstruction), (lines, Cell::Line), (reserved, Cell::Reserved)] {
            for _ in 0..count * 8 {
                let r = next();
                let (dx, dy) = ((r % 17) as u8, (r >> 8) % 17);
                w.set(56 + dx, 56 + dy as u8, cell);
            }
        }
        if border {
            w.fill((0, 0), (127, 0), Cell::Obstruction);
        }
        w.set(64, 64, if seed & 1 == 0 { Cell::Line } else { Cell::Floor });
        w
    })
}

/// Motor segments: (MotCtl, samples), any byte value (speed bits included).
pub fn motors() -> impl Strategy<Value = Vec<(u8, u8)>> {
    prop::collection::vec((any::<u8>(), 1u8..12), 1..10)
}
