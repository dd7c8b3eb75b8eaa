//! Closed-loop drivers: read the snapshot at each upd_sysregs pulse, choose MotCtl for the
//! next main-loop iteration.
//!
//! ```
//! use botsim_core::driver::{Driver, LineFollower};
//! use botsim_core::golden::GoldenBot;
//! use botsim_core::world::World;
//! use botsim_core::Snapshot;
//! // Drive the golden model along the built-in course to its end.
//! let mut model = GoldenBot::new(World::builtin(), 15, Default::default());
//! let mut follower = LineFollower::new(15);
//! let mut regs = model.initial();
//! for sample in 0..20_000 {
//!     let m = follower.next(&Snapshot { sample, cycle: 0, regs });
//!     if follower.finished() { break; }
//!     regs = model.step(m);
//! }
//! assert!(follower.reached_end());
//! ```

use crate::regs::{MotCtl, Orientation, Snapshot};
use crate::script::MotorScript;

/// Something that drives the bot: called with every snapshot (sample 0 first), returns the
/// MotCtl value for the next main-loop iteration.
pub trait Driver {
    fn next(&mut self, snapshot: &Snapshot) -> MotCtl;

    /// True when the driver has nothing more to do (the run may stop).
    fn finished(&self) -> bool {
        false
    }

    /// A short status for summaries.
    fn status(&self) -> String {
        String::new()
    }
}

/// A motor script as a driver: iteration k gets the segment that covers k.
pub struct ScriptDriver {
    script: MotorScript,
}

impl ScriptDriver {
    pub fn new(script: MotorScript) -> ScriptDriver {
        ScriptDriver { script }
    }
}

impl Driver for ScriptDriver {
    fn next(&mut self, s: &Snapshot) -> MotCtl {
        self.script.value_for(s.sample + 1)
    }
}

/// Where the line follower is in its work.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Phase {
    /// Forward along the line.
    Follow,
    /// A forward step left the line: back onto it, then search.
    BackToLine { heading: Orientation, tried: usize },
    /// Turning to the next heading to probe.
    Turn { heading: Orientation, tried: usize, target: Orientation },
    /// One step forward on the new heading: on the line or not?
    Probe { heading: Orientation, tried: usize, from: (u8, u8) },
    /// On the line with a wall straight ahead: the end of the course.
    End,
    /// No heading within 90 degrees continues the line.
    Lost,
}

/// Headings tried when the line ends under the bot, relative to the last heading:
/// 45 degrees right, 45 left, 90 right, 90 left. Never more, so the bot never turns around.
const SEARCH: [i8; 4] = [1, -1, 2, -2];

/// The course's black-line follower: forward while on the line; when a step leaves it,
/// reverse until back on it, turn 45 degrees and try again; extended to try left as well as
/// right (45 and 90 degrees each way) so it takes left turns without turning around. It stops
/// on the line with a wall straight ahead (the end of a course).
///
/// One action (a move or a 45/90-degree turn) completes when a counter reaches the threshold;
/// the follower then stops the motors for one sample, sees the result in the next snapshot,
/// and decides.
pub struct LineFollower {
    threshold: u8,
    phase: Phase,
    command: MotCtl,
    /// The snapshot of the last threshold event, until the next one shows its result (or
    /// `None` at the start and while an action is under way).
    event: Option<Snapshot>,
    /// No action has been decided yet: the first snapshot decides.
    started: bool,
    moves: u64,
    blocked: u64,
}

impl LineFollower {
    /// A follower for the firmware's threshold (samples per action).
    pub fn new(threshold: u8) -> LineFollower {
        LineFollower {
            threshold: threshold.max(1),
            phase: Phase::Follow,
            command: MotCtl::STOP,
            event: None,
            started: false,
            moves: 0,
            blocked: 0,
        }
    }

    /// The bot stopped on the line with a wall ahead.
    pub fn reached_end(&self) -> bool {
        self.phase == Phase::End
    }

    /// The line was lost.
    pub fn lost(&self) -> bool {
        self.phase == Phase::Lost
    }

    /// Actions completed so far.
    pub fn actions(&self) -> u64 {
        self.moves
    }

    /// Forward or reverse moves refused by an obstruction.
    pub fn blocked_moves(&self) -> u64 {
        self.blocked
    }

    /// The motor command that turns from `from` towards `to` (at most 90 degrees a step).
    fn turn_command(from: Orientation, to: Orientation) -> MotCtl {
        match (to as i8 - from as i8).rem_euclid(8) {
            1 => MotCtl::SLOW_RIGHT,
            2..=4 => MotCtl::FAST_RIGHT,
            7 => MotCtl::SLOW_LEFT,
            _ => MotCtl::FAST_LEFT,
        }
    }

    /// Start (or continue) the search for the line's next direction.
    fn search(&mut self, heading: Orientation, tried: usize, now: Orientation) -> MotCtl {
        match SEARCH.get(tried) {
            None => {
                self.phase = Phase::Lost;
                MotCtl::STOP
            }
            Some(&rel) => {
                let target = heading.rotated(rel);
                self.phase = Phase::Turn { heading, tried, target };
                Self::turn_command(now, target)
            }
        }
    }

    /// Decide after an action's result is visible in `s`.
    fn decide(&mut self, s: &Snapshot) -> MotCtl {
        let sensors = s.sensors();
        let on_line = sensors.on_line();
        let wall_ahead = sensors.prox_left() && sensors.prox_right();
        let now = s.orientation();
        match self.phase {
            Phase::Follow if on_line && wall_ahead => {
                self.phase = Phase::End;
                MotCtl::STOP
            }
            Phase::Follow if on_line => MotCtl::FORWARD,
            Phase::Follow => {
                self.phase = Phase::BackToLine { heading: now, tried: 0 };
                MotCtl::REVERSE
            }
            Phase::BackToLine { heading, tried } if on_line => self.search(heading, tried, now),
            Phase::BackToLine { .. } => MotCtl::REVERSE,
            Phase::Turn { heading, tried, target } if now == target => {
                self.phase = Phase::Probe { heading, tried, from: s.location() };
                MotCtl::FORWARD
            }
            Phase::Turn { target, .. } => Self::turn_command(now, target),
            Phase::Probe { heading, tried, from } => {
                if on_line && s.location() != from {
                    self.phase = Phase::Follow;
                    self.decide(s)
                } else if s.location() == from {
                    // Blocked: nothing to undo; try the next heading.
                    self.search(heading, tried + 1, now)
                } else {
                    self.phase = Phase::BackToLine { heading, tried: tried + 1 };
                    MotCtl::REVERSE
                }
            }
            Phase::End | Phase::Lost => MotCtl::STOP,
        }
    }
}

impl Driver for LineFollower {
    fn next(&mut self, s: &Snapshot) -> MotCtl {
        if let Some(event) = self.event.take() {
            if event.move_refused(s, self.threshold) {
                self.blocked += 1;
            }
            self.command = self.decide(s);
        } else if !self.started {
            self.started = true;
            self.command = self.decide(s);
        } else if s.threshold_event(self.threshold) {
            // An action completes in this iteration; its result shows in the next snapshot.
            self.moves += 1;
            self.event = Some(*s);
            return MotCtl::STOP;
        }
        self.command
    }

    fn finished(&self) -> bool {
        matches!(self.phase, Phase::End | Phase::Lost)
    }

    fn status(&self) -> String {
        match self.phase {
            Phase::End => "reached the end of the line".into(),
            Phase::Lost => "lost the line".into(),
            _ => "following".into(),
        }
    }
}
