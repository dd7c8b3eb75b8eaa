//! The golden behavioural model of BotSim 2.0: spec/botsim.md §3-§7 in plain Rust, with no
//! CPU and no firmware. The scoreboard tests compare every RTL snapshot with it.
//!
//! ```
//! use botsim_core::golden::GoldenBot;
//! use botsim_core::regs::MotCtl;
//! use botsim_core::world::World;
//! let mut m = GoldenBot::new(World::builtin(), 15, Default::default());
//! assert_eq!(m.initial().bot_info, 0x02);
//! for n in 1..=15 {
//!     let r = m.step(MotCtl::FORWARD);
//!     assert_eq!((r.loc_x, r.lm_dist), (64, n)); // counting; the move shows next sample
//! }
//! assert_eq!(m.step(MotCtl::FORWARD).loc_x, 65);
//! ```

use crate::firmware::Compat;
use crate::regs::{MotCtl, Movement, Orientation, Registers};
use crate::world::{Cell, World};

/// Left-front, front and right-front cells per heading (spec §7.1), symmetric form.
const PROXIMITY: [[(i8, i8); 3]; 8] = [
    [(-1, -1), (0, -1), (1, -1)],   // N
    [(1, -2), (1, -1), (2, -1)],    // NE
    [(1, -1), (1, 0), (1, 1)],      // E
    [(2, 1), (1, 1), (1, 2)],       // SE
    [(1, 1), (0, 1), (-1, 1)],      // S
    [(-1, 2), (-1, 1), (-2, 1)],    // SW
    [(-1, 1), (-1, 0), (-1, -1)],   // W
    [(-2, -1), (-1, -1), (-1, -2)], // NW
];

/// The 2014 program's right-front cell when facing SW.
const SW_RIGHT_BOTSIM20: (i8, i8) = (-1, 0);

/// The bot's state between samples.
#[derive(Clone, Debug)]
pub struct GoldenBot {
    world: World,
    threshold: u8,
    compat: Compat,
    x: u8,
    y: u8,
    orient: Orientation,
    lm_dist: u8,
    rm_dist: u8,
}

impl GoldenBot {
    /// The state after reset: (0x40, 0x40) facing East, counters 0.
    pub fn new(world: World, threshold: u8, compat: Compat) -> GoldenBot {
        GoldenBot { world, threshold, compat, x: 0x40, y: 0x40, orient: Orientation::East, lm_dist: 0, rm_dist: 0 }
    }

    pub fn world(&self) -> &World {
        &self.world
    }

    fn at(&self, (dx, dy): (i8, i8)) -> Cell {
        self.world.get(self.x.wrapping_add(dx as u8), self.y.wrapping_add(dy as u8))
    }

    /// Sensors for the current position and heading.
    pub fn sensors(&self) -> u8 {
        let mut cells = PROXIMITY[self.orient as usize];
        if self.compat == Compat::BotSim20 && self.orient == Orientation::SouthWest {
            cells[2] = SW_RIGHT_BOTSIM20;
        }
        let [l, c, r] = cells.map(|d| self.at(d) == Cell::Obstruction);
        let line = if self.at((0, 0)) == Cell::Line { 0 } else { 0b111 };
        ((l || c) as u8) << 4 | ((r || c) as u8) << 3 | line
    }

    fn registers(&self, m: Movement) -> Registers {
        Registers {
            loc_x: self.x,
            loc_y: self.y,
            sensors: self.sensors(),
            bot_info: m.code() << 4 | self.orient.bits(),
            lm_dist: self.lm_dist,
            rm_dist: self.rm_dist,
        }
    }

    /// Sample 0: the initial register dump.
    pub fn initial(&self) -> Registers {
        self.registers(Movement::Stopped)
    }

    /// One main-loop iteration with `motctl` sampled: returns the published registers.
    pub fn step(&mut self, motctl: MotCtl) -> Registers {
        if motctl.left_on() {
            self.lm_dist = self.lm_dist.wrapping_add(1);
        }
        if motctl.right_on() {
            self.rm_dist = self.rm_dist.wrapping_add(1);
        }
        let m = motctl.movement();
        let published = self.registers(m);
        if self.lm_dist >= self.threshold || self.rm_dist >= self.threshold {
            self.orient = self.orient.turned(m);
            let sign: i8 = match m {
                Movement::Forward => 1,
                Movement::Reverse => -1,
                _ => 0,
            };
            if sign != 0 {
                let (dx, dy) = self.orient.step();
                let (nx, ny) = (self.x.wrapping_add((dx * sign) as u8), self.y.wrapping_add((dy * sign) as u8));
                if self.world.get(nx, ny) != Cell::Obstruction {
                    self.x = nx;
                    self.y = ny;
                }
            }
            self.lm_dist = 0;
            self.rm_dist = 0;
        }
        published
    }
}
