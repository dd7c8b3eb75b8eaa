//! The line follower completes the built-in course and the three course maps, on the RTL.

mod common;

use botsim::driver::{Driver, LineFollower};
use botsim::world::{Cell, World};
use botsim::{Compat, Orientation, RtlBot, Snapshot, Timing};

struct Run {
    follower: LineFollower,
    path: Vec<(u8, u8)>,
    last: Snapshot,
}

/// Follow the line on the RTL (fast timing, threshold 15, RtlBot 2.0 compatibility).
fn follow(world: &World, max_samples: u64) -> Run {
    let mut bot = RtlBot::builder().timing(Timing::Fast).compat(Compat::BotSim20).world(world.clone()).build().unwrap();
    let mut follower = LineFollower::new(15);
    let mut path: Vec<(u8, u8)> = vec![];
    let mut last = None;
    bot.drive(&mut follower, max_samples, |s| {
        if path.last() != Some(&s.location()) {
            path.push(s.location());
        }
        last = Some(*s);
    })
    .unwrap();
    Run { follower, path, last: last.unwrap() }
}

fn off_line(w: &World, path: &[(u8, u8)]) -> usize {
    path.iter().filter(|&&(x, y)| w.get(x, y) != Cell::Line).count()
}

#[test]
fn completes_the_builtin_course() {
    let w = World::builtin();
    let r = follow(&w, 20_000);
    assert!(r.follower.reached_end(), "{}", r.follower.status());
    let &end = botsim::world::COURSE.last().unwrap();
    assert_eq!((r.last.location(), r.last.orientation()), (end, Orientation::North));
    assert_eq!(r.last.regs.sensors, 0x18, "on the line, wall straight ahead");
    // Every waypoint of the course was visited.
    for p in botsim::world::COURSE {
        assert!(r.path.contains(p), "waypoint {p:?} missed");
    }
    assert!(off_line(&w, &r.path) < r.path.len() / 5);
}

#[test]
fn completes_world_map_part1_along_the_tracker_route() {
    let Some(p) = common::reference_map("world_map_part1.txt") else { return };
    let w = World::load(&p).unwrap();
    let r = follow(&w, 20_000);
    assert!(r.follower.reached_end(), "{}", r.follower.status());
    // The course's "Proj2 Bot tracker": every turn point, in order, and the END blocked.
    let turns = common::PART1_TRACKER;
    let mut at = 0;
    for t in turns {
        let i = r.path[at..]
            .iter()
            .position(|&p| p == t)
            .unwrap_or_else(|| panic!("turn point {t:02X?} not visited in order"));
        at += i;
    }
    assert_eq!((r.last.location(), r.last.orientation(), r.last.regs.sensors), ((0x3B, 0x3F), Orientation::East, 0x18));
    assert_eq!(r.follower.blocked_moves(), 0, "not blocked, not even at the end (it stops facing the wall)");
}

#[test]
fn completes_world_map_lr_and_loop() {
    for name in ["world_map_lr", "world_map_loop"] {
        let Some(p) = common::reference_map(&format!("{name}.txt")) else { return };
        let w = World::load(&p).unwrap();
        let r = follow(&w, 20_000);
        assert!(r.follower.reached_end(), "{name}: {}", r.follower.status());
        assert_eq!(r.last.regs.sensors, 0x18, "{name}: ends on the line facing a wall");
        let line_cells = w.counts()[1];
        let visited_line = r.path.iter().filter(|&&(x, y)| w.get(x, y) == Cell::Line).count();
        assert!(visited_line * 10 > line_cells * 7, "{name}: visited {visited_line} of {line_cells} line cells");
    }
}
