//! A refused move has one definition (`Snapshot::move_refused`): the line follower counts
//! exactly the moves that the path picture marks. (The two used to decide it differently.)

use botsim_core::driver::{Driver, LineFollower};
use botsim_core::golden::GoldenBot;
use botsim_core::render::blocked_moves;
use botsim_core::{Cell, Snapshot, World};

#[test]
fn the_follower_and_the_picture_count_the_same_refused_moves() {
    // A short line east from the start; a wall where the follower's first probe (45 degrees
    // right, south-east of the line's end) goes, so that probe is refused.
    let mut w = World::empty();
    w.fill((0, 0), (127, 127), Cell::Floor);
    w.fill((64, 64), (66, 64), Cell::Line);
    w.set(67, 65, Cell::Obstruction);
    let mut bot = GoldenBot::new(w, 4, Default::default());
    let mut follower = LineFollower::new(4);
    let mut snaps = vec![];
    let mut regs = bot.initial();
    for sample in 0..600 {
        let s = Snapshot { sample, cycle: 0, regs };
        snaps.push(s);
        let m = follower.next(&s);
        if follower.finished() {
            break;
        }
        regs = bot.step(m);
    }
    let marked = blocked_moves(&snaps, 4);
    assert!(follower.blocked_moves() >= 1, "the world is built for a refused probe");
    assert_eq!(follower.blocked_moves(), marked.len() as u64, "marked at {marked:?}");
    assert!(marked.contains(&(66, 64)), "{marked:?}");
}
