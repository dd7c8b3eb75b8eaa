//! The README's example test, kept compiling and passing.

use botsim::{MotCtl, Orientation, RtlBot, Timing};

#[test]
fn drives_one_cell_east() {
    let mut bot = RtlBot::builder().timing(Timing::Fast).build().unwrap();
    let start = bot.wait_update().unwrap(); // sample 0: the dump after reset
    assert_eq!(start.location(), (64, 64));
    bot.set_motors(MotCtl::FORWARD);
    let s = bot.run_samples(16).unwrap(); // threshold 15: one cell per 15 samples
    assert_eq!(s[15].location(), (65, 64));
    assert_eq!(s[15].orientation(), Orientation::East);
    assert!(s[15].sensors().on_line());
}
