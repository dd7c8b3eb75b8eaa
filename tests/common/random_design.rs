//! Random board designs for the fast-forward's property tests (tests/boards/random_designs.rs):
//! clean-room Verilog and a team program, generated from a seed.
//!
//! A design is a Nexys4 top around the course's system, as teams build it: the course's
//! `debounce` and `sevensegment` (botsim's, board.md §2.1, with `SIMULATE` 0 or 1), the team's
//! KCPSM6 with its program (`teampgm.psm`, which botsim assembles) waiting in one of a few
//! kinds of loop, its port interface, the upd_sysregs interrupt, and the bot; around them a
//! random mix of the things teams add: wrap counters of any terminal count, free-running
//! counters, clock dividers, toggles, rotating shift registers, PWM compares, LFSRs,
//! watchdogs cleared by a heartbeat, some enabled by others' ticks, on the oscillator or on clocks from an MMCM or a DCM_SP with
//! rational ratios; their bits feed the LEDs, the display's digits and points, the CPU's input
//! ports and sometimes a VGA output (the course's `dtg` on a 25 MHz clock, or a team's own that
//! counts its totals inclusively).
//!
//! The generator also says whether it knows the design to be periodic within reach: every
//! part either repeats with a short period (the CPU's loop, a short wrap counter, a ring, a
//! PWM's low byte...) or is a counter whose value the rest reads only at long intervals, so a
//! run should skip nearly all of it. That knowledge comes from the elements' definitions
//! here, not from botsim.

use std::fmt::Write;

/// A deterministic generator (xorshift64*).
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// A number in `lo..=hi`.
    pub fn range(&mut self, lo: u64, hi: u64) -> u64 {
        lo + self.next() % (hi - lo + 1)
    }
    pub fn chance(&mut self, percent: u64) -> bool {
        self.next() % 100 < percent
    }
    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[(self.next() % items.len() as u64) as usize]
    }
}

/// A design, ready to write out.
pub struct Design {
    pub seed: u64,
    /// `nexys4fpga.v`, `teampgm.psm`.
    pub top: String,
    pub program: String,
    pub simulate: bool,
    /// A stimulus file (botsim board --stimulus).
    pub stimulus: String,
    pub seconds: f64,
    /// Ok(the period of what is not a counter, in 100 MHz clocks): the design should skip
    /// nearly all of a run; Err(why the generator does not know that).
    pub reach: Result<u64, String>,
    /// One line per part, for a failure's message.
    pub parts: Vec<String>,
    /// The board's peripherals the design has: a UART receiver on RsRx, a PS/2 receiver on
    /// PS2_CLK/PS2_DATA (their modules from tests/board_designs/console).
    pub uart: bool,
    pub keyboard: bool,
    /// A second bot (a game's monster) beside the team's: its instance name, or `None` when
    /// the design instantiates it without one (botsim names it).
    pub monster: Option<Option<&'static str>>,
    /// The programs of the design's other KCPSM6s (a second core's): each ROM's module name
    /// (its source `<name>.psm`) and the source.
    pub programs: Vec<(String, String)>,
    /// A net with several drivers (Vivado's DRC MDRV-1), whose value an LED shows: its name.
    pub shared: Option<String>,
    /// Then the same top with the net's resolution written out (each driver on a wire of its
    /// own, the net their AND: the bits they agree on, as botsim resolves it).
    pub resolved: Option<String>,
    /// It has a game's logic beside its parts and the game's firmware ([`game_part`]).
    pub game: bool,
    /// The folder its sources are in, under the run's: often none, else named as users
    /// name folders (spaces, commas, `&`, parentheses, accents; [`folder`]).
    pub folder: String,
}

impl Design {
    /// Write the design's files into `dir`: its sources in its [`Design::folder`], the
    /// stimulus and the parts at the top.
    pub fn write(&self, dir: &std::path::Path) {
        let src = dir.join(&self.folder);
        std::fs::create_dir_all(&src).unwrap();
        std::fs::write(self.top_file(dir), &self.top).unwrap();
        std::fs::write(src.join("teampgm.psm"), &self.program).unwrap();
        for (name, source) in &self.programs {
            std::fs::write(src.join(format!("{name}.psm")), source).unwrap();
        }
        std::fs::write(dir.join("stimulus.txt"), &self.stimulus).unwrap();
        std::fs::write(dir.join("parts.txt"), self.parts.join("\n") + "\n").unwrap();
        let console = super::root().join("tests/board_designs/console");
        for (on, file) in [(self.uart, "uart_rx.v"), (self.keyboard, "ps2_rx.v")] {
            if on {
                std::fs::copy(console.join(file), src.join(file)).unwrap();
            }
        }
    }

    /// The top's file, as [`Design::write`] places it in `dir`.
    pub fn top_file(&self, dir: &std::path::Path) -> std::path::PathBuf {
        dir.join(&self.folder).join("nexys4fpga.v")
    }
}

/// The folder a design's sources are in: none for 2 seeds in 5, else one or two levels of
/// words joined as users join them (drawn from a stream of its own, so the design a seed
/// draws is the same whatever its folder).
pub fn folder(seed: u64) -> String {
    let mut r = Rng::new(seed ^ 0x00f0_1de2_5eed);
    if r.chance(40) {
        return String::new();
    }
    let words: [&str; 10] = ["Verilog", "files", "Projet", "final", "jeu", "équipe", "v2", "Lab 4", "Größe", "src"];
    let joins: [&str; 9] = [" ", ", ", " & ", " (", ") ", "-", "_", "+", "'"];
    let level = |r: &mut Rng| {
        let mut name = r.pick(&words).to_string();
        for _ in 0..r.range(1, 4) {
            let (join, word) = (*r.pick(&joins), *r.pick(&words));
            name.push_str(join);
            name.push_str(word);
        }
        name
    };
    let mut path = level(&mut r);
    if r.chance(30) {
        path = format!("{path}/{}", level(&mut r));
    }
    path
}

/// A time as a fraction of a picosecond: num / den.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Ps {
    num: u128,
    den: u128,
}

fn gcd(a: u128, b: u128) -> u128 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

impl Ps {
    fn new(num: u128, den: u128) -> Ps {
        let g = gcd(num, den);
        Ps { num: num / g, den: den / g }
    }
    /// The least common multiple of two periods (in lowest terms: lcm of the numerators over
    /// the gcd of the denominators).
    fn lcm(self, o: Ps) -> Ps {
        let n = self.num / gcd(self.num, o.num) * o.num;
        Ps::new(n, gcd(self.den, o.den))
    }
    fn times(self, k: u64) -> Ps {
        Ps::new(self.num * k as u128, self.den)
    }
    /// In 100 MHz clocks, rounded up.
    fn clocks(self) -> u64 {
        (self.num.div_ceil(self.den * 10_000)) as u64
    }
}

/// A clock of the design: its net and period.
struct Clock {
    net: String,
    period: Ps,
}

/// What the rest of the design can tell of a part over time.
#[derive(Clone, Copy, Debug)]
enum Shape {
    /// What the rest reads of it repeats every `period` cycles of its clock, but at its
    /// boundaries, at least `boundary` cycles apart (a counter whose low bits repeat while the
    /// rest counts: a compared constant, a high bit shown).
    Known { period: u64, boundary: Option<u64> },
    /// Not within reach (an LFSR of 32 bits, a count between short and long).
    Unknown(&'static str),
}

/// A part whose state repeats every `period` cycles.
fn periodic(period: u64) -> Shape {
    Shape::Known { period, boundary: None }
}

/// A counter of `width` bits counting to `top` (wrapping there, or at 2^width: `None`), of
/// which bit `bit` is shown, and whose low byte the CPU's port mux reads: short, it is state;
/// long, its low byte repeats every 256 and its boundaries (the wrap, the bit shown) are
/// far apart; neither in between (the fast-forward may take it either way, and the
/// generator does not claim a skip then).
fn counter(width: u32, top: Option<u64>, bit: Option<u32>) -> Shape {
    let cycle = top.map_or(1u64 << width.min(48), |t| t + 1);
    if cycle <= 64 {
        return periodic(cycle);
    }
    if width <= 8 {
        return Shape::Unknown("a short counter read whole");
    }
    let mut boundary = top.map(|t| t + 1);
    if let Some(k) = bit.filter(|&k| k >= 8) {
        boundary = Some(boundary.map_or(1 << k, |b| b.min(1 << k)));
    }
    match boundary {
        Some(b) if b < 50_000 => Shape::Unknown("a count between short and long"),
        b => Shape::Known { period: 256, boundary: b },
    }
}

/// One part the generator adds.
struct Part {
    /// Its Verilog (declarations and always blocks).
    verilog: String,
    /// A one-bit output, and a wider value (at least 5 bits) for a digit.
    bit: String,
    value: String,
    shape: Shape,
    clock: usize,
    text: String,
    /// Its one-bit output changes nearly every cycle (a toggle, a ring, an LFSR, a counter's
    /// lowest bits): shown on an LED or a point it makes a pin change a clock, which costs the
    /// runs that record every pin more than it tests.
    fast: bool,
    /// A module of its own it instantiates (written after the top's), if any.
    module: String,
    /// A debounced button it gives that may reset the bot (a team's debouncer), if any.
    resets: Option<String>,
    /// A program of its own (a second KCPSM6's): its ROM's module name and its source.
    program: Option<(String, String)>,
}

/// The design for `seed`.
pub fn generate(seed: u64) -> Design {
    let mut r = Rng::new(seed);
    let simulate = r.chance(50);
    // Half the designs are drawn tame (clock ratios with short common periods, counts either
    // short or long, short LFSRs, short delays), so that many repeat within reach; whether
    // one does is still worked out from its parts (`reach`), whatever the draw.
    let tame = r.chance(50);
    let mut parts_text =
        vec![format!("seed {seed}, SIMULATE = {}{}", simulate as u8, if tame { ", tame" } else { "" })];

    // Clocks: the oscillator, and maybe an MMCM or a DCM_SP.
    let osc = Ps::new(10_000, 1);
    let mut clocks = vec![Clock { net: "clk".into(), period: osc }];
    let mut clocking = String::new();
    let mut vga_clock = None;
    match r.range(0, 2) {
        1 => {
            let mult = if tame { 10 } else { r.range(6, 12) };
            let divide = |r: &mut Rng| if tame { *r.pick(&[10u64, 20, 25, 40, 50]) } else { r.range(2, 40) };
            let d0 = divide(&mut r);
            let d1 = divide(&mut r);
            // VGA's 25 MHz when it fits: VCO / 25 (600..1200 MHz: 24..48).
            let vga =
                if (24..=48).contains(&(mult * 100 / 25)) && (mult * 100) % 25 == 0 { Some(mult * 4) } else { None };
            let d2 = vga.unwrap_or_else(|| divide(&mut r));
            writeln!(
                clocking,
                "    // An MMCM: VCO = 100 MHz x {mult}; outputs / {d0}, / {d1}, / {d2}.
    wire mmcm_fb, mmcm_a, mmcm_b, mmcm_c, locked;
    MMCME2_BASE #(.CLKIN1_PERIOD(10.0), .CLKFBOUT_MULT_F({mult}.0), .DIVCLK_DIVIDE(1),
        .CLKOUT0_DIVIDE_F({d0}.0), .CLKOUT1_DIVIDE({d1}), .CLKOUT2_DIVIDE({d2})) MMCM (
        .CLKIN1(clk), .CLKFBIN(mmcm_fb), .CLKFBOUT(mmcm_fb), .CLKOUT0(mmcm_a), .CLKOUT1(mmcm_b),
        .CLKOUT2(mmcm_c), .LOCKED(locked), .PWRDWN(1'b0), .RST(1'b0));
    wire clk_a, clk_b, clk_c;
    BUFG BA (.I(mmcm_a), .O(clk_a));
    BUFG BB (.I(mmcm_b), .O(clk_b));
    BUFG BC (.I(mmcm_c), .O(clk_c));"
            )
            .unwrap();
            for (net, d) in [("clk_a", d0), ("clk_b", d1), ("clk_c", d2)] {
                clocks.push(Clock { net: net.into(), period: Ps::new(10_000 * d as u128, mult as u128) });
            }
            if vga.is_some() {
                vga_clock = Some(3);
            }
            parts_text.push(format!("MMCM x{mult}: /{d0} /{d1} /{d2}"));
        }
        2 => {
            let dv = *r.pick(&[2u64, 4, 5, 8, 10, 16]);
            let ratios: &[(u64, u64)] = if tame {
                &[(2, 1), (2, 4), (4, 8)]
            } else {
                &[(2, 1), (3, 2), (4, 3), (5, 4), (3, 4), (2, 3), (7, 5), (5, 2)]
            };
            let (m, d) = *r.pick(ratios);
            writeln!(
                clocking,
                "    // A DCM_SP: CLK0 through a BUFG, CLKDV = 100 MHz / {dv}, CLKFX = 100 MHz x {m} / {d}.
    wire dcm_0, dcm_dv, dcm_fx, clk_0, clk_dv, clk_fx, locked;
    DCM_SP #(.CLKIN_PERIOD(10.0), .CLKDV_DIVIDE({dv}.0), .CLKFX_MULTIPLY({m}), .CLKFX_DIVIDE({d})) DCM (
        .CLKIN(clk), .CLKFB(clk_0), .CLK0(dcm_0), .CLKDV(dcm_dv), .CLKFX(dcm_fx), .LOCKED(locked),
        .RST(1'b0), .PSEN(1'b0), .PSINCDEC(1'b0), .PSCLK(1'b0), .DSSEN(1'b0));
    BUFG B0 (.I(dcm_0), .O(clk_0));
    BUFG BDV (.I(dcm_dv), .O(clk_dv));
    BUFG BFX (.I(dcm_fx), .O(clk_fx));"
            )
            .unwrap();
            clocks.push(Clock { net: "clk_0".into(), period: osc });
            clocks.push(Clock { net: "clk_dv".into(), period: Ps::new(10_000 * dv as u128, 1) });
            clocks.push(Clock { net: "clk_fx".into(), period: Ps::new(10_000 * d as u128, m as u128) });
            if dv == 4 {
                vga_clock = Some(2);
            }
            parts_text.push(format!("DCM_SP: CLKDV /{dv}, CLKFX x{m}/{d}"));
        }
        _ => {
            clocking.push_str("    wire locked = 1'b1;\n");
        }
    }

    // The parts.
    let mut parts: Vec<Part> = Vec::new();
    let n = r.range(2, 7) as usize;
    let mut held_stream = Rng::new(seed ^ 0x484F_4C44);
    // Parts written as students write them (their own debouncer, Nexys3-release shaped),
    // from a stream of their own: a seed's other parts are as they were.
    let mut style_stream = Rng::new(seed ^ 0x5354_594C);
    // A watchdog in place of a part, sometimes (its own stream too); a free part likewise.
    let mut watchdog_stream = Rng::new(seed ^ 0x5744_4F47);
    let mut free_stream = Rng::new(seed ^ 0x4652_4545);
    // A second KCPSM6 in nested delays likewise (a team's own BotSim 3.1 bot).
    let mut own_stream = Rng::new(seed ^ 0x4F57_4E43);
    for i in 0..n {
        let clock = if clocks.len() > 1 && r.chance(40) { r.range(1, clocks.len() as u64 - 1) as usize } else { 0 };
        // Enabled by an earlier part's one-bit output (its tick, its toggle), sometimes.
        let enable =
            (i > 0 && r.chance(25)).then(|| r.range(0, i as u64 - 1) as usize).filter(|&j| parts[j].clock == clock);
        // Whether a wrap counter's terminal count is held in a register (compared as
        // `count == limit` or `count + 1 >= limit`, as tone generators do) rather than
        // written as a constant: from a stream of its own, so a seed's parts are otherwise
        // as they were.
        let held = match (held_stream.chance(40), held_stream.chance(25)) {
            (false, _) => Held::No,
            (true, false) => Held::Constant,
            (true, true) => Held::Alternating,
        };
        let mut part = make_part(&mut r, i, clock, enable.map(|j| &parts[j]), simulate, tame, held);
        let mut plain = true;
        if watchdog_stream.chance(8) {
            part = watchdog(&mut watchdog_stream, i, clock);
            plain = false;
        }
        if free_stream.chance(8) {
            part = free_part(&mut free_stream, i, clock);
            plain = false;
        }
        if style_stream.chance(12) {
            part = team_debouncer(&mut style_stream, i, clock, tame);
            plain = false;
        }
        // (In place of a plain part only: a seed's other classes are as they were.)
        if own_stream.chance(8) && plain {
            part = own_core(&mut own_stream, i, clock);
        }
        parts_text.push(format!("part {i} on {}: {}", clocks[clock].net, part.text));
        parts.push(part);
    }

    // A game's logic beside them, sometimes (a stream of its own: a seed's other parts are
    // as they were), and then the game's firmware in place of the team program.
    let mut game_stream = Rng::new(seed ^ 0x4741_4D45);
    let game = game_stream.chance(12).then(|| {
        let part = game_part(&mut game_stream, parts.len());
        parts_text.push(format!("part {} on clk: {}", parts.len(), part.text));
        parts.push(part);
        0x20 + parts.len() as u8 - 1
    });

    // The port interface's read mux, as many teams write it: combinational (`always @(*)`),
    // so what the CPU reads is the logic's value at the edge itself.
    let comb_mux = style_stream.chance(40);
    if comb_mux {
        parts_text.push("the read mux combinational".into());
    }
    // A team's debounced button resets the CPU and the bot, as the Nexys3 designs' system
    // reset does (both then read the debouncer's output at every edge).
    let bot_reset = parts.iter().find_map(|p| p.resets.clone()).filter(|_| style_stream.chance(60));
    if let Some(b) = &bot_reset {
        parts_text.push(format!("the CPU and the bot also reset by {b}"));
    }
    let bot_reset = bot_reset.map_or("sysreset".to_string(), |b| format!("sysreset | {b}"));

    // The team's program.
    let kind = *r.pick(&[Program::Semaphore, Program::PollSwitches, Program::Countdown(0), Program::Countdown(0)]);
    let kind = match kind {
        // Tame: a trip of 36, 60 or 108 clocks, which the course modules' 48 divide well.
        Program::Countdown(_) if r.chance(40) => {
            Program::Countdown(if tame { *r.pick(&[2, 5, 11]) } else { r.range(1, 200) })
        }
        // Or a software delay as teams write them (see Delay).
        Program::Countdown(_) => Program::Delay(Delay::draw(&mut r, tame)),
        k => k,
    };
    let kind = game.map_or(kind, Program::Game);
    parts_text.push(format!("team program: {kind:?}"));
    let program = program(kind);

    // VGA, sometimes, on a 25 MHz clock; its vertical sync sometimes shown on an LED too
    // (then what a run observes includes the pixel clock's part: a frame is 1.68 M clocks).
    let vga = vga_clock.filter(|_| r.chance(50));
    let vga_on_led = vga.is_some() && r.chance(30);
    // The team's own timing generator instead of the course's, sometimes, counting its totals
    // inclusively as rstasney_p2's does (from a stream of its own: a seed's other parts are as
    // they were).
    let team_dtg = vga.is_some() && Rng::new(seed ^ 0x4454_4749).chance(40);
    // A sprite on the raster whose pixel an LED shows, as pdxrayw_p2video's icon (its own
    // stream too): the pixel row and column compared with a window's edges, the sprite's row
    // and column (`pixel_row - top`) read only inside it.
    let sprite = vga.filter(|_| !vga_on_led).and_then(|_| {
        let mut r = Rng::new(seed ^ 0x5350_5254);
        r.chance(40).then(|| Sprite::draw(&mut r))
    });
    if let Some(c) = vga {
        parts_text.push(format!(
            "VGA on {}{}{}",
            clocks[c].net,
            if team_dtg { ", the team's timing generator counting to 800 and 525 inclusively" } else { "" },
            if vga_on_led { ", its vsync on LED 15" } else { "" }
        ));
    }
    if let Some(sp) = &sprite {
        parts_text.push(format!("a sprite on the raster, its pixel on LED 14: {sp:?}"));
    }

    // What each LED, digit and point shows.
    // The parts' outputs shown on LEDs and points: the slower ones (all, if none is slow).
    let mut sources: Vec<String> = parts.iter().filter(|p| !p.fast).map(|p| p.bit.clone()).collect();
    if sources.is_empty() {
        sources = parts.iter().map(|p| p.bit.clone()).collect();
    }
    let mut leds = Vec::new();
    for k in 0..16 {
        let s = if k == 15 && vga_on_led {
            "vga_vs".to_string()
        } else if k == 14 && sprite.is_some() {
            "sprite_px".to_string()
        } else {
            match r.range(0, 3) {
                0 => format!("cpu_leds[{k}]"),
                1 => format!("db_sw[{k}]"),
                2 => format!("db_btns[{}]", k % 5),
                _ => r.pick(&sources).clone(),
            }
        };
        leds.push(s);
    }
    // Sometimes a team shows what out_port shows between OUTPUTs (a debugging LED): then a
    // count the program keeps there can be told apart, and may not be skipped.
    let mut watch_stream = Rng::new(seed ^ 0x4F55_5450);
    let out_watch = watch_stream.chance(15);
    if out_watch {
        let k = watch_stream.range(0, 14) as usize;
        leds[k] = "out_zero".into();
        parts_text.push(format!("LED {k} shows out_port == 0 at every clock (no strobe)"));
    }
    // Sometimes a second bot in the same world (a game's monster), as teams write one:
    // named or not, driven by the switches or by the team's motor register, its place
    // sometimes on an LED.
    let mut bots_stream = Rng::new(seed ^ 0x424F_5432);
    let monster = bots_stream.chance(20).then(|| *bots_stream.pick(&[Some("MONSTER"), None, None]));
    let mut monster_verilog = String::new();
    if let Some(name) = monster {
        let drive = *bots_stream.pick(&["db_sw[15:8]", "motctl"]);
        // `bot(` as some teams write it, or `bot (`.
        let instance = match name {
            Some(n) => format!("bot {n} ("),
            None => (if bots_stream.chance(50) { "bot(" } else { "bot (" }).to_string(),
        };
        monster_verilog = format!(
            "
    // A second bot in the same world.
    wire [ 7:0] m_locx, m_locy, m_info, m_sensors, m_lmdist, m_rmdist;
    wire        m_upd;
    {instance}.MotCtl_in({drive}), .LocX_reg(m_locx), .LocY_reg(m_locy), .Sensors_reg(m_sensors),
        .BotInfo_reg(m_info), .LMDist_reg(m_lmdist), .RMDist_reg(m_rmdist),
        .vid_row(7'd0), .vid_col(7'd0), .vid_pixel_out(), .clk(clk), .reset({bot_reset}), .upd_sysregs(m_upd));
"
        );
        let shown = bots_stream.chance(50).then(|| bots_stream.range(0, 14) as usize);
        let shown = shown.filter(|&k| leds[k] != "out_zero");
        if let Some(k) = shown {
            leds[k] = "m_locx[0]".into();
        }
        parts_text.push(format!(
            "a second bot ({}), driven by {drive}{}",
            name.unwrap_or("no instance name"),
            shown.map_or(String::new(), |k| format!(", its LocX bit 0 on LED {k}"))
        ));
    }
    // Sometimes a net with several drivers, as games have them (its own stream): the second
    // bot's distances on the team bot's wires, an `assign` to a bot's output, or two
    // `assign`s to one wire; an LED shows it (the bits the drivers agree on, botsim says).
    let mut shared_stream = Rng::new(seed ^ 0x4D44_5256);
    let mut shared = None;
    let mut shared_verilog = String::new();
    // The same net resolved by hand: edits of the top (each driver on a wire of its own) and
    // the lines that AND them, in place of `shared_verilog`.
    let mut by_hand: Vec<(&str, &str)> = Vec::new();
    let mut by_hand_verilog = String::new();
    let free: Vec<usize> = (0..14).filter(|&k| leds[k] != "out_zero" && leds[k] != "m_locx[0]").collect();
    if shared_stream.chance(15) && !free.is_empty() {
        let k = *shared_stream.pick(&free);
        let bit = shared_stream.range(0, 3);
        let (a, b) = (shared_stream.pick(&sources).clone(), shared_stream.pick(&sources).clone());
        let variant = if monster.is_some() { shared_stream.range(0, 2) } else { shared_stream.range(1, 2) };
        shared_verilog.push_str("    // A net with two drivers.\n");
        by_hand_verilog.push_str("    // A net with two drivers.\n");
        // The team bot's distances on wires of their own.
        let hero = [
            ("lmdist, rmdist;", "lmdist, rmdist, h_lmdist, h_rmdist;"),
            (
                "(botinfo), .LMDist_reg(lmdist), .RMDist_reg(rmdist)",
                "(botinfo), .LMDist_reg(h_lmdist), .RMDist_reg(h_rmdist)",
            ),
        ];
        let (net, text) = match variant {
            0 => {
                monster_verilog = monster_verilog.replace(
                    ".LMDist_reg(m_lmdist), .RMDist_reg(m_rmdist)",
                    ".LMDist_reg(lmdist), .RMDist_reg(rmdist)",
                );
                by_hand.extend(hero);
                by_hand.push((
                    "(m_info), .LMDist_reg(lmdist), .RMDist_reg(rmdist)",
                    "(m_info), .LMDist_reg(m_lmdist), .RMDist_reg(m_rmdist)",
                ));
                by_hand_verilog
                    .push_str("    assign lmdist = h_lmdist & m_lmdist;\n    assign rmdist = h_rmdist & m_rmdist;\n");
                leds[k] = format!("lmdist[{bit}]");
                ("lmdist".to_string(), "the second bot's distances on the team bot's wires".to_string())
            }
            1 => {
                writeln!(shared_verilog, "    assign rmdist = {{8{{{a}}}}};").unwrap();
                by_hand.extend(hero);
                writeln!(
                    by_hand_verilog,
                    "    assign lmdist = h_lmdist;\n    assign rmdist = h_rmdist & {{8{{{a}}}}};"
                )
                .unwrap();
                leds[k] = format!("rmdist[{bit}]");
                ("rmdist".to_string(), format!("the team bot's RMDist and `assign rmdist = {{8{{{a}}}}}`"))
            }
            _ => {
                writeln!(shared_verilog, "    wire shared;\n    assign shared = {a};\n    assign shared = {b};")
                    .unwrap();
                writeln!(by_hand_verilog, "    wire shared;\n    assign shared = {a} & {b};").unwrap();
                leds[k] = "shared".into();
                ("shared".to_string(), format!("`assign shared = {a}` and `assign shared = {b}`"))
            }
        };
        parts_text.push(format!("a net with two drivers, {net} ({text}), on LED {k}"));
        shared = Some(net);
    }
    leds.reverse();
    let mut digits = Vec::new();
    for k in 0..8 {
        digits.push(if r.chance(60) {
            format!("cpu_dig{k}")
        } else {
            let p = r.pick(&parts);
            format!("{}[4:0]", p.value)
        });
    }
    let mut points = Vec::new();
    for _ in 0..8 {
        points.push(if r.chance(50) { "1'b0".to_string() } else { r.pick(&sources).clone() });
    }
    points.reverse();
    // Input ports 20.. read the parts' values (the CPU's programs here do not read them, but
    // the read mux is logic the design has).
    let mut in_mux = String::new();
    for (i, p) in parts.iter().enumerate() {
        writeln!(in_mux, "            8'h{:02X}: in_port <= {}[7:0];", 0x20 + i, p.value).unwrap();
    }

    // The board's peripherals, drawn from a stream of their own (a seed's other parts are as
    // they were before designs had them): received bytes and scan codes shown on the LEDs.
    let mut pr = Rng::new(seed ^ 0x50_4552_4955_u64);
    let (uart, keyboard) = (pr.chance(35), pr.chance(35));
    let mut periph_ports = String::new();
    let mut periph_verilog = String::new();
    let mut periph_xor = String::new();
    if uart {
        periph_ports.push_str("    input  wire        RsRx,\n");
        periph_verilog.push_str(
            "    // A UART receiver (115200 baud): the last byte received on LEDs 7-0.
    wire [7:0] rx_data;
    wire rx_valid;
    reg [7:0] rx_last = 8'd0;
    uart_rx RX (.clk(clk), .rx(RsRx), .data(rx_data), .valid(rx_valid), .errors());
    always @(posedge clk) if (rx_valid) rx_last <= rx_data;
",
        );
        periph_xor.push_str(" ^ {8'd0, rx_last}");
        parts_text.push("a UART receiver on RsRx, its last byte on LEDs 7-0".into());
    }
    if keyboard {
        periph_ports.push_str("    inout  wire        PS2_CLK, PS2_DATA,\n");
        periph_verilog.push_str(
            "    // A PS/2 receiver (switch 14 inhibits the keyboard): the last code on LEDs 15-8.
    wire [7:0] kbd_data;
    wire kbd_valid;
    reg [7:0] key_last = 8'd0;
    ps2_rx KBD (.clk(clk), .inhibit(db_sw[14]), .ps2_clk(PS2_CLK), .ps2_data(PS2_DATA), .data(kbd_data),
        .valid(kbd_valid), .errors());
    always @(posedge clk) if (kbd_valid) key_last <= kbd_data;
",
        );
        periph_xor.push_str(" ^ {key_last, 8'd0}");
        parts_text.push("a PS/2 receiver on PS2_CLK/PS2_DATA (switch 14 inhibits), its last code on LEDs 15-8".into());
    }

    // Whether the generator knows the design to repeat within reach (the peripherals' traffic
    // at random times aside).
    let vga_observed = match (vga.is_some(), vga_on_led, sprite.is_some()) {
        (true, true, _) => Some("an LED shows the VGA timing (a frame is 1.68 M clocks)"),
        (true, _, true) => Some("an LED shows a sprite on the VGA raster (a frame is 1.68 M clocks)"),
        _ => None,
    };
    let reach = reach(&parts, &clocks, simulate, kind, vga_observed);
    let reach = match (out_watch, kind, reach) {
        (true, Program::Delay(_), Ok(_)) => Err("an LED shows out_port, where the delay's count is".into()),
        (_, _, r) => r,
    };
    let reach = match (uart || keyboard, reach) {
        (false, r) => r,
        (true, Ok(p)) => {
            Err(format!("the peripherals' traffic comes at random times (the rest repeats every {p} clocks)"))
        }
        (true, Err(why)) => Err(format!("the peripherals' traffic comes at random times, and {why}")),
    };
    parts_text.push(match &reach {
        Ok(p) => format!("periodic within reach: {p} clocks"),
        Err(why) => format!("not known to be periodic within reach: {why}"),
    });

    let mut verilog_parts = String::new();
    let mut modules = String::new();
    for p in &parts {
        verilog_parts.push_str(&p.verilog);
        modules.push_str(&p.module);
    }
    if team_dtg {
        modules.push_str(TEAM_DTG);
    }
    for (i, c) in clocks.iter().enumerate() {
        verilog_parts = verilog_parts.replace(&format!("@CLK{i}@"), &c.net);
    }
    let vga_verilog = match vga {
        Some(c) => {
            let color = r.pick(&sources).clone();
            format!(
                "    // VGA from the course's display timing generator on {net}.
    wire vga_hs, vga_vs, video_on;
    wire [10:0] pixel_row, pixel_column;
    {dtg} DTG (.clock({net}), .rst(sysreset), .horiz_sync(vga_hs), .vert_sync(vga_vs), .video_on(video_on),
        .pixel_row(pixel_row), .pixel_column(pixel_column));
    reg [11:0] rgb = 12'd0;
    always @(posedge {net}) rgb <= video_on ? {{pixel_row[5:2], pixel_column[5:2], {color}, 3'b101}} : 12'd0;
    assign vgaRed = rgb[11:8];
    assign vgaGreen = rgb[7:4];
    assign vgaBlue = rgb[3:0];
    assign Hsync = vga_hs;
    assign Vsync = vga_vs;
{sprite}",
                net = clocks[c].net,
                dtg = if team_dtg { "team_dtg" } else { "dtg" },
                sprite = sprite.as_ref().map_or(String::new(), |sp| sp.verilog(&clocks[c].net))
            )
        }
        None => "    wire vga_vs = 1'b0;\n".into(),
    };
    let vga_ports = if vga.is_some() {
        "    output wire [ 3:0] vgaRed, vgaGreen, vgaBlue,\n    output wire        Hsync, Vsync,\n"
    } else {
        ""
    };
    let interrupt = if kind == Program::Semaphore {
        "    // upd_sysregs interrupts the team CPU until it acknowledges.
    always @(posedge clk) begin
        if (interrupt_ack | sysreset) interrupt <= 1'b0;
        else if (upd_sysregs) interrupt <= 1'b1;
    end
"
    } else {
        ""
    };
    let top = format!(
        "// nexys4fpga.v: a random board design (tests/common/random_design.rs, seed {seed}).
`timescale 1ns / 1ps
module nexys4fpga #(
    parameter SIMULATE = 0
) (
    input  wire        clk,
    input  wire        btnCpuReset,
    input  wire        btnC, btnU, btnD, btnL, btnR,
    input  wire [15:0] sw,
    output wire [15:0] led,
    output wire [ 6:0] seg,
    output wire        dp,
{vga_ports}{periph_ports}    output wire [ 7:0] an
);
{clocking}
    // The course's debounce: bit 0 the CPU reset button (active low).
    wire [ 5:0] db_pbtns;
    wire [15:0] db_sw;
    wire [ 4:0] db_btns = db_pbtns[5:1];
    wire        sysreset = ~db_pbtns[0] | ~locked;
    debounce #(.RESET_POLARITY_LOW(1), .SIMULATE(SIMULATE)) DB (
        .clk(clk), .pbtn_in({{btnC, btnL, btnU, btnR, btnD, btnCpuReset}}), .switch_in(sw),
        .pbtn_db(db_pbtns), .swtch_db(db_sw));

    // The team's PicoBlaze and its program.
    wire [11:0] address;
    wire [17:0] instruction;
    wire        bram_enable, rdl;
    wire [ 7:0] port_id, out_port;
    reg  [ 7:0] in_port = 8'd0;
    wire        write_strobe, k_write_strobe, read_strobe, interrupt_ack;
    reg         interrupt = 1'b0;
    kcpsm6 #(.interrupt_vector(12'h3FF), .scratch_pad_memory_size(64), .hwbuild(8'h00)) APPCPU (
        .address(address), .instruction(instruction), .bram_enable(bram_enable),
        .port_id(port_id), .write_strobe(write_strobe), .k_write_strobe(k_write_strobe),
        .out_port(out_port), .read_strobe(read_strobe), .in_port(in_port),
        .interrupt(interrupt), .interrupt_ack(interrupt_ack), .sleep(1'b0),
        .reset({bot_reset} | rdl), .clk(clk));
    teampgm APPPGM (.enable(bram_enable), .address(address), .instruction(instruction), .rdl(rdl), .clk(clk));

    // The bot.
    reg  [ 7:0] motctl = 8'd0;
    wire [ 7:0] locx, locy, botinfo, sensors, lmdist, rmdist;
    wire        upd_sysregs;
    bot ROJOBOT (.MotCtl_in(motctl), .LocX_reg(locx), .LocY_reg(locy), .Sensors_reg(sensors),
        .BotInfo_reg(botinfo), .LMDist_reg(lmdist), .RMDist_reg(rmdist),
        .vid_row(7'd0), .vid_col(7'd0), .vid_pixel_out(), .clk(clk), .reset({bot_reset}), .upd_sysregs(upd_sysregs));
{monster_verilog}{shared_verilog}{interrupt}
    // The parts.
{verilog_parts}
    // The port interface (the course's demo port numbers).
    reg [15:0] cpu_leds = 16'd0;
    reg [ 4:0] cpu_dig0 = 5'd23, cpu_dig1 = 5'd23, cpu_dig2 = 5'd23, cpu_dig3 = 5'd23;
    reg [ 4:0] cpu_dig4 = 5'd23, cpu_dig5 = 5'd23, cpu_dig6 = 5'd23, cpu_dig7 = 5'd23;
    always @(posedge clk) begin
        case (port_id)
            8'h00: in_port <= {{3'b000, db_btns}};
            8'h01: in_port <= db_sw[7:0];
            8'h0A: in_port <= locx;
            8'h0B: in_port <= locy;
            8'h0C: in_port <= botinfo;
            8'h0D: in_port <= sensors;
            8'h0E: in_port <= lmdist;
            8'h0F: in_port <= rmdist;
            8'h11: in_port <= db_sw[15:8];
{in_mux}            default: in_port <= 8'h00;
        endcase
    end
    always @(posedge clk) begin
        if (sysreset) begin
            cpu_leds <= 16'd0;
            motctl <= 8'd0;
        end else if (write_strobe | k_write_strobe) begin
            case (port_id)
                8'h02: cpu_leds[7:0] <= out_port;
                8'h03: cpu_dig0 <= out_port[4:0];
                8'h04: cpu_dig1 <= out_port[4:0];
                8'h05: cpu_dig2 <= out_port[4:0];
                8'h06: cpu_dig3 <= out_port[4:0];
                8'h09: motctl <= out_port;
                8'h12: cpu_leds[15:8] <= out_port;
                8'h13: cpu_dig4 <= out_port[4:0];
                8'h14: cpu_dig5 <= out_port[4:0];
                8'h15: cpu_dig6 <= out_port[4:0];
                8'h16: cpu_dig7 <= out_port[4:0];
                default: ;
            endcase
        end
    end
{vga_verilog}
    // The course's seven-segment driver.
    sevensegment #(.RESET_POLARITY_LOW(0), .SIMULATE(SIMULATE)) SSB (
        .clk(clk), .reset(sysreset),
        .d7({d7}), .d6({d6}), .d5({d5}), .d4({d4}), .d3({d3}), .d2({d2}), .d1({d1}), .d0({d0}),
        .dp({{{points}}}), .seg({{dp, seg}}), .an(an), .digits_out());

{periph_verilog}{out_watch_verilog}
    assign led = {{{leds}}}{periph_xor};
endmodule
{modules}",
        d7 = digits[7],
        d6 = digits[6],
        d5 = digits[5],
        d4 = digits[4],
        d3 = digits[3],
        d2 = digits[2],
        d1 = digits[1],
        d0 = digits[0],
        points = points.join(", "),
        leds = leds.join(", "),
        out_watch_verilog = if out_watch {
            "    reg out_zero = 1'b0;\n    always @(posedge clk) out_zero <= (out_port == 8'h00);\n"
        } else {
            ""
        },
    );

    // Random inputs: switch changes and presses, and one CPU reset.
    let seconds = if simulate { 0.08 } else { 0.12 };
    let mut stimulus = String::new();
    let mut at = 5.0 + r.range(0, 10) as f64;
    while at < seconds * 1000.0 - 20.0 {
        match r.range(0, 3) {
            0 => writeln!(stimulus, "{at:.3}ms switches {:04X}", r.next() & 0xFFFF).unwrap(),
            1 => writeln!(
                stimulus,
                "{at:.3}ms press {} {}ms",
                r.pick(&["btnC", "btnU", "btnD", "btnL", "btnR"]),
                r.range(1, 25)
            )
            .unwrap(),
            _ => writeln!(stimulus, "{at:.3}ms switches {:04X}", 1u64 << r.range(0, 15)).unwrap(),
        }
        at += r.range(8, 45) as f64 + r.range(0, 999) as f64 / 1000.0;
    }
    writeln!(stimulus, "{:.3}ms press btnCpuReset {}ms", seconds * 500.0, r.range(1, 20)).unwrap();
    // The peripherals' traffic: text to the UART, keys held a while.
    let mut at = 3.0 + pr.range(0, 10) as f64;
    while (uart || keyboard) && at < seconds * 1000.0 - 15.0 {
        if uart && (!keyboard || pr.chance(50)) {
            let text: String = (0..pr.range(1, 6)).map(|_| format!("\\x{:02X}", pr.range(0, 256))).collect();
            writeln!(stimulus, "{at:.3}ms uart \"{text}\"").unwrap();
        } else {
            let key = pr.pick(&["KeyA", "Digit7", "Space", "ArrowUp", "Enter", "F5", "ArrowLeft"]);
            writeln!(stimulus, "{at:.3}ms key {key} {}ms", pr.range(1, 12)).unwrap();
        }
        at += pr.range(6, 30) as f64 + pr.range(0, 999) as f64 / 1000.0;
    }

    let top = if comb_mux {
        let registered = "    always @(posedge clk) begin\n        case (port_id)\n            8'h00: in_port <=";
        assert!(top.contains(registered));
        let (head, tail) = top.split_once(registered).unwrap();
        let (mux, rest) = tail.split_once("endcase").unwrap();
        format!(
            "{head}    always @(*) begin\n        case (port_id)\n            8'h00: in_port ={}endcase{rest}",
            mux.replace("in_port <=", "in_port =")
        )
    } else {
        top
    };
    let resolved = shared.is_some().then(|| {
        let mut t = top.replacen(&shared_verilog, &by_hand_verilog, 1);
        for (from, to) in &by_hand {
            assert!(t.contains(from), "{from}");
            t = t.replacen(from, to, 1);
        }
        t
    });
    let programs = parts.iter().filter_map(|p| p.program.clone()).collect();
    let folder = folder(seed);
    if !folder.is_empty() {
        parts_text.push(format!("its sources in the folder {folder:?}"));
    }
    Design {
        game: game.is_some(),
        folder,
        seed,
        top,
        program,
        simulate,
        stimulus,
        seconds,
        reach,
        parts: parts_text,
        uart,
        keyboard,
        monster,
        programs,
        shared,
        resolved,
    }
}

/// The team program's kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Program {
    /// Waits on a semaphore in the scratchpad (no port access), set by the upd_sysregs
    /// interrupt's routine; then shows the bot's place and drives it with the switches.
    Semaphore,
    /// Polls the switches; on a change shows them and drives the bot with them.
    PollSwitches,
    /// Counts down from N, then toggles an LED and a digit.
    Countdown(u64),
    /// A software delay, then toggles an LED and a digit.
    Delay(Delay),
    /// A game's firmware: at each interrupt of the game's frame tick, moves the sprite by the
    /// left button (writing its place to the game's port), reads the game's status (its
    /// score, the raster at the sprite and obstacle, its state, the collision flag) from the
    /// same port and shows it on the LEDs and a digit.
    Game(u8),
}

/// How a software delay counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Count {
    /// `SUB`, `SUBCY`..., `JUMP NZ` (to zero) or `JUMP NC` (past it).
    DownToZero,
    DownPastZero,
    /// `ADD`, `ADDCY`..., `JUMP NC` (to the carry out of the top byte).
    UpToCarry,
    /// `ADD`, `ADDCY`..., `COMPARE`, `COMPARECY`..., `JUMP NZ` (to a limit).
    UpToLimit(u64),
    /// Down in the scratch pad: `FETCH`, `SUB`, `SUBCY`..., `STORE`, `JUMP NZ`.
    InScratchPad,
    /// Nested loops down to zero: this one's turn (a count of one or two bytes) reloads a
    /// middle count (the second `u8`; none when 0), whose turn reloads an inner count (the
    /// first), each of one byte.
    Nested(u8, u8),
}

/// A software delay of the team's program: `bytes` registers counting from `value` as
/// `count` says, in a subroutine or inline, at `addr`; the mnemonics in lower case or not,
/// constants in hex or decimal (`1'd`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Delay {
    count: Count,
    bytes: u32,
    value: u64,
    regs: [u8; 4],
    call: bool,
    addr: u16,
    lower: bool,
    decimal: bool,
}

/// Inner and middle counts of a tame three-loop delay whose outer count is one byte: its
/// outer turns are 240 to 864 clocks, each a multiple of 48; and of one whose outer count
/// is two bytes (96 to 960 clocks).
const TAME_NESTS: [(u8, u8); 8] = [(12, 7), (9, 9), (5, 9), (15, 5), (24, 7), (21, 9), (15, 13), (2, 27)];
const TAME_NESTS_WIDE: [(u8, u8); 8] = [(4, 4), (10, 4), (2, 20), (22, 4), (5, 20), (4, 28), (8, 20), (7, 28)];

impl Delay {
    fn draw(r: &mut Rng, tame: bool) -> Delay {
        let bytes = r.range(1, 3) as u32;
        // s3 and s4 are the program's own; the count anywhere else.
        let mut pool: Vec<u8> = (5..16).collect();
        let mut regs = [0u8; 4];
        for reg in &mut regs {
            *reg = pool.remove(r.range(0, pool.len() as u64 - 1) as usize);
        }
        let top = 1u64 << (8 * bytes);
        // Turns: up to a few tens of milliseconds of the board at 8-12 clocks a turn.
        let turns = r.range(2, (top - 1).min(200_000));
        let count = match r.range(0, 5) {
            0 => Count::DownToZero,
            1 => Count::DownPastZero,
            2 => Count::UpToCarry,
            3 => Count::UpToLimit(0),
            4 => Count::InScratchPad,
            _ => {
                let (inner, middle) = (r.range(2, 255) as u8, r.range(2, 255) as u8);
                let i = inner as usize;
                // Tame: counts whose outer turn (trip) the course modules' 48 clocks divide
                // (or, with one byte and two loops, of few factors).
                match (r.chance(60), tame, bytes) {
                    (true, true, 1) => Count::Nested(TAME_NESTS[i % 8].0, TAME_NESTS[i % 8].1),
                    (true, true, _) => Count::Nested(TAME_NESTS_WIDE[i % 8].0, TAME_NESTS_WIDE[i % 8].1),
                    (true, false, _) => Count::Nested(inner, middle),
                    (false, true, 1) => Count::Nested([6, 11, 21, 36, 61, 111][i % 6], 0),
                    (false, true, _) => Count::Nested([10, 22, 46, 94, 118][i % 5], 0),
                    (false, false, _) => Count::Nested(inner, 0),
                }
            }
        };
        let (count, bytes, value) = match count {
            Count::DownToZero | Count::InScratchPad => (count, bytes, turns),
            Count::DownPastZero => (count, bytes, turns - 1),
            Count::UpToCarry => (count, bytes, top - turns),
            Count::UpToLimit(_) => {
                let from = r.range(0, top - 1 - turns);
                (Count::UpToLimit(from + turns), bytes, from)
            }
            // The outer count of one or two bytes (tame: long, so that its end is far from
            // the next).
            Count::Nested(..) => {
                let bytes = bytes.min(2);
                let top = 1 << (8 * bytes);
                (count, bytes, if tame { r.range(top * 7 / 10, top - 1) } else { r.range(2, top - 1) })
            }
        };
        Delay {
            count,
            bytes,
            value,
            regs,
            call: r.chance(50),
            addr: r.range(0x10, 0x2C0) as u16,
            lower: r.chance(30),
            decimal: r.chance(30),
        }
    }

    /// The instructions: (label, text), the delay's loop labelled `delay`.
    fn lines(&self) -> Vec<(Option<&'static str>, String)> {
        let k = |v: u64| if self.decimal { format!("{v}'d") } else { format!("{v:02X}") };
        let r = |i: usize| format!("s{:X}", self.regs[i]);
        let byte = |v: u64, i: usize| (v >> (8 * i)) & 0xFF;
        let n = self.bytes as usize;
        let mut out: Vec<(Option<&'static str>, String)> = Vec::new();
        let chain = |out: &mut Vec<(Option<&'static str>, String)>, op: &str, label: Option<&'static str>| {
            for i in 0..n {
                let mnemonic = if i == 0 { op.to_string() } else { format!("{op}CY") };
                out.push((if i == 0 { label } else { None }, format!("{mnemonic} {}, {}", r(i), k(u64::from(i == 0)))));
            }
        };
        match self.count {
            Count::Nested(inner, middle) => {
                for i in 0..n {
                    out.push((None, format!("LOAD {}, {}", r(i), k(byte(self.value, i)))));
                }
                // The middle and inner counts in the registers after the outer count's.
                let innermost = if middle == 0 {
                    out.push((Some("outer"), format!("LOAD {}, {}", r(n), k(inner as u64))));
                    n
                } else {
                    out.push((Some("outer"), format!("LOAD {}, {}", r(n), k(middle as u64))));
                    out.push((Some("middle"), format!("LOAD {}, {}", r(n + 1), k(inner as u64))));
                    n + 1
                };
                out.push((Some("delay"), format!("SUB {}, {}", r(innermost), k(1))));
                out.push((None, "JUMP NZ, delay".into()));
                if middle != 0 {
                    out.push((None, format!("SUB {}, {}", r(n), k(1))));
                    out.push((None, "JUMP NZ, middle".into()));
                }
                chain(&mut out, "SUB", None);
                out.push((None, "JUMP NZ, outer".into()));
            }
            Count::InScratchPad => {
                for i in 0..n {
                    out.push((None, format!("LOAD {}, {}", r(i), k(byte(self.value, i)))));
                    out.push((None, format!("STORE {}, {}", r(i), k(0x20 + i as u64))));
                }
                for i in 0..n {
                    let label = if i == 0 { Some("delay") } else { None };
                    out.push((label, format!("FETCH {}, {}", r(i), k(0x20 + i as u64))));
                }
                chain(&mut out, "SUB", None);
                for i in 0..n {
                    out.push((None, format!("STORE {}, {}", r(i), k(0x20 + i as u64))));
                }
                out.push((None, "JUMP NZ, delay".into()));
            }
            _ => {
                for i in 0..n {
                    out.push((None, format!("LOAD {}, {}", r(i), k(byte(self.value, i)))));
                }
                let (op, jump) = match self.count {
                    Count::DownToZero => ("SUB", "JUMP NZ, delay"),
                    Count::DownPastZero => ("SUB", "JUMP NC, delay"),
                    Count::UpToCarry => ("ADD", "JUMP NC, delay"),
                    _ => ("ADD", "JUMP NZ, delay"),
                };
                chain(&mut out, op, Some("delay"));
                if let Count::UpToLimit(limit) = self.count {
                    for i in 0..n {
                        let m = if i == 0 { "COMPARE" } else { "COMPARECY" };
                        out.push((None, format!("{m} {}, {}", r(i), k(byte(limit, i)))));
                    }
                }
                out.push((None, jump.into()));
            }
        }
        out
    }

    /// The clocks of one turn of the loop that counts (the outer loop, when nested).
    fn trip(&self) -> u64 {
        let lines = self.lines();
        let at = lines.iter().position(|(l, _)| *l == Some("delay")).unwrap();
        let turn = 2 * (lines.len() - at) as u64;
        match self.count {
            // The reload, the loops within, the outer count's chain and its JUMP.
            Count::Nested(inner, 0) => 2 * (1 + 2 * inner as u64 + self.bytes as u64 + 1),
            Count::Nested(inner, middle) => {
                2 * (1 + middle as u64 * (1 + 2 * inner as u64 + 2) + self.bytes as u64 + 1)
            }
            _ => turn,
        }
    }

    /// Its turns (the outer loop's, when nested).
    fn turns(&self) -> u64 {
        match self.count {
            Count::DownToZero | Count::InScratchPad | Count::Nested(..) => self.value,
            Count::DownPastZero => self.value + 1,
            Count::UpToCarry => (1 << (8 * self.bytes)) - self.value,
            Count::UpToLimit(l) => l - self.value,
        }
    }

    /// The address of the loop that counts (after `top: CALL wait` and the four lines of the
    /// toggle when it is called): its JUMP shows the register bits 7:4 of that
    /// address name on port_id in every cycle (the hardware does: a count there cannot be
    /// skipped exactly).
    fn loop_address(&self) -> u16 {
        let lines = self.lines();
        let at = lines.iter().position(|(l, _)| *l == Some("delay")).unwrap();
        self.addr + u16::from(self.call) * 5 + at as u16
    }

    /// Why botsim may not skip it whole, if it may not.
    fn unskippable(&self) -> Option<String> {
        let shown = (self.loop_address() >> 4 & 15) as u8;
        let outer = self.loop_address() - 1;
        if self.regs[..self.bytes as usize].contains(&shown) {
            return Some(format!("its delay's JUMP shows its count (s{shown:X}) on port_id"));
        }
        if let Count::Nested(_, middle) = self.count {
            // The JUMPs to `middle` and `outer`, above `delay`.
            let outer = if middle == 0 { outer } else { outer - 1 };
            if [outer, outer + 1].iter().any(|a| self.regs[..self.bytes as usize].contains(&((a >> 4 & 15) as u8))) {
                return Some("its delay's outer JUMP shows its count on port_id".into());
            }
        }
        None
    }
}

/// The program of `kind`, and the clocks of its loop's period once settled.
fn program(kind: Program) -> String {
    let head = "; teampgm.psm: a random design's team program (tests/common/random_design.rs).
CONSTANT PA_PBTNS, 00
CONSTANT PA_SW, 01
CONSTANT PA_LEDS, 02
CONSTANT PA_DIG0, 03
CONSTANT PA_DIG1, 04
CONSTANT PA_MOTCTL, 09
CONSTANT PA_LOCX, 0A
CONSTANT PA_LOCY, 0B
CONSTANT PA_SENSORS, 0D
CONSTANT PA_LEDS_HI, 12
CONSTANT PA_DIG7, 16
CONSTANT PA_SW_HI, 11
CONSTANT SEM, 10
";
    let body = match kind {
        Program::Semaphore => "            ADDRESS 000
main:       LOAD    s0, 00
            STORE   s0, SEM
            ENABLE  INTERRUPT
wait:       FETCH   s0, SEM
            COMPARE s0, 00
            JUMP    Z, wait
            LOAD    s0, 00
            STORE   s0, SEM
            INPUT   s1, PA_LOCX
            INPUT   s2, PA_LOCY
            AND     s1, 0F
            AND     s2, 0F
            OUTPUT  s1, PA_DIG0
            OUTPUT  s2, PA_DIG1
            INPUT   s3, PA_SENSORS
            OUTPUT  s3, PA_LEDS_HI
            INPUT   s4, PA_SW
            OUTPUT  s4, PA_MOTCTL
            JUMP    wait

            ADDRESS 300
isr:        LOAD    s0, 01
            STORE   s0, SEM
            RETURNI ENABLE

            ADDRESS 3FF
            JUMP    isr
"
        .to_string(),
        Program::PollSwitches => "            ADDRESS 000
main:       LOAD    s1, FF
poll:       INPUT   s0, PA_SW
            COMPARE s0, s1
            JUMP    Z, poll
            LOAD    s1, s0
            OUTPUT  s0, PA_LEDS
            OUTPUT  s0, PA_MOTCTL
            AND     s0, 0F
            OUTPUT  s0, PA_DIG7
            JUMP    poll
"
        .to_string(),
        Program::Delay(d) => {
            let mut body = String::from(
                "            ADDRESS 000
main:       LOAD    s3, 00
            INPUT   s4, PA_SW_HI
            OUTPUT  s4, PA_MOTCTL
            JUMP    top
",
            );
            body += &format!("            ADDRESS {:03X}\n", d.addr);
            let toggle = "            XOR     s3, 01\n            OUTPUT  s3, PA_LEDS\n            OUTPUT  s3, PA_DIG0\n            JUMP    top\n";
            let mut delay = String::new();
            for (label, text) in d.lines() {
                let text = if d.lower { text.to_lowercase() } else { text };
                delay += &format!("{:<12}{text}\n", label.map_or(String::new(), |l| format!("{l}:")));
            }
            if d.call {
                body += "top:        CALL    wait\n";
                body += toggle;
                body += "wait:\n";
                body += &delay;
                body += "            RETURN\n";
            } else {
                body += "top:\n";
                body += &delay;
                body += toggle;
            }
            body
        }
        Program::Game(port) => format!(
            "CONSTANT PA_GAME, {port:02X}
            ADDRESS 000
main:       LOAD    s0, 00
            STORE   s0, SEM
            LOAD    s5, 04
            ENABLE  INTERRUPT
wait:       FETCH   s0, SEM
            COMPARE s0, 00
            JUMP    Z, wait
            LOAD    s0, 00
            STORE   s0, SEM
            INPUT   s1, PA_PBTNS
            TEST    s1, 08
            JUMP    Z, right
            SUB     s5, 01
            JUMP    moved
right:      ADD     s5, 01
moved:      AND     s5, 1F
            OUTPUT  s5, PA_GAME
            INPUT   s2, PA_GAME
            OUTPUT  s2, PA_LEDS
            OUTPUT  s2, PA_DIG0
            JUMP    wait

            ADDRESS 300
isr:        LOAD    s0, 01
            STORE   s0, SEM
            RETURNI ENABLE

            ADDRESS 3FF
            JUMP    isr
"
        ),
        Program::Countdown(n) => format!(
            "            ADDRESS 000
main:       LOAD    s3, 00
            INPUT   s4, PA_SW_HI
            OUTPUT  s4, PA_MOTCTL
top:        LOAD    s2, {n:02X}
delay:      SUB     s2, 01
            JUMP    NZ, delay
            XOR     s3, 01
            OUTPUT  s3, PA_LEDS
            OUTPUT  s3, PA_DIG0
            JUMP    top
"
        ),
    };
    format!("{head}{body}")
}

/// The clocks one trip of a program's waiting loop takes (two per instruction), the trip
/// the state repeats after.
fn program_period(kind: Program) -> u64 {
    match kind {
        Program::Semaphore | Program::PollSwitches | Program::Game(_) => 6,
        // LOAD, N x (SUB, JUMP), XOR, OUTPUT, OUTPUT, JUMP; s3 toggles: two trips.
        Program::Countdown(n) => 2 * 2 * (1 + 2 * n + 4),
        // The loop's turn: the count is moved on whole, up to its end.
        Program::Delay(d) => d.trip(),
    }
}

/// Where a wrap counter's terminal count comes from.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Held {
    /// A constant in the comparison.
    No,
    /// A register that holds it (set again at every reset): a tone generator's shape.
    Constant,
    /// A register that alternates between it and another count at every clock (the counter
    /// is then compared with a variable that does not hold: the fast-forward must notice).
    Alternating,
}

/// A wrap counter's terminal count: the constant, or a register `lim{i}` as `held` says, and
/// the register's Verilog.
fn held_limit(i: usize, clk: &str, width: u32, top: u64, held: Held) -> (String, String) {
    let w1 = width - 1;
    let other = top / 2 + 1;
    match held {
        Held::No => (format!("{width}'d{top}"), String::new()),
        Held::Constant => (
            format!("lim{i}"),
            format!(
                "    reg [{w1}:0] lim{i} = {width}'d{top};\n    always @(posedge {clk}) if (sysreset) lim{i} <= {width}'d{top};\n"
            ),
        ),
        Held::Alternating => (
            format!("lim{i}"),
            format!(
                "    reg [{w1}:0] lim{i} = {width}'d{top};\n    always @(posedge {clk}) lim{i} <= (lim{i} == {width}'d{top}) ? {width}'d{other} : {width}'d{top};\n"
            ),
        ),
    }
}

/// One random part, number `i`, on clock `clock` (its nets are `@CLK{clock}@` until the
/// clocks are named), enabled by `enable`'s one-bit output when given.
fn make_part(
    r: &mut Rng,
    i: usize,
    clock: usize,
    enable: Option<&Part>,
    simulate: bool,
    tame: bool,
    held: Held,
) -> Part {
    let clk = format!("@CLK{clock}@");
    let reset = r.chance(40);
    let en = enable.map_or("1'b1".to_string(), |p| p.bit.clone());
    let guard = |body: &str| -> String {
        let body = if enable.is_some() { format!("if ({en}) begin {body} end") } else { body.to_string() };
        if reset {
            format!("if (sysreset) begin p{i} <= 0; end else begin {body} end")
        } else {
            body
        }
    };
    // Short counts (state) or long ones (counters); SIMULATE = 1 designs favour short ones,
    // as course modules are then.
    let short = r.chance(if simulate { 60 } else { 40 });
    // Tame short counts: periods that divide 48, as the course modules' do.
    let count = |r: &mut Rng| match (short, tame) {
        (true, true) => *r.pick(&[1, 2, 3, 5, 7, 11, 15, 23, 47]),
        (true, false) => r.range(1, 60),
        _ => r.range(100_000, 3_000_000),
    };
    let kind = r.range(0, 6);
    let mut fast = matches!(kind, 3 | 5 | 6);
    let (verilog, bit, value, shape, text) = match kind {
        0 => {
            // A wrap counter: == top sets 0; its tick or one of its bits shown.
            let top = count(r);
            let width = 64 - top.leading_zeros() + r.range(0, 8) as u32;
            let width = width.min(32);
            let by_bit = r.chance(40);
            let bits = 64 - top.leading_zeros();
            let k = if tame && !short {
                r.range(17.min(bits as u64 - 1), bits as u64 - 1)
            } else {
                r.range(0, bits as u64 - 1)
            } as u32;
            let (limit, hold) = held_limit(i, &clk, width, top, held);
            let body = format!("p{i} <= (p{i} == {limit}) ? {width}'d0 : p{i} + {width}'d1;");
            let verilog = format!(
                "{hold}    reg [{w1}:0] p{i} = {width}'d0;\n    always @(posedge {clk}) begin {} end\n    wire p{i}_tick = p{i} == {width}'d{top};\n",
                guard(&body),
                w1 = width - 1
            );
            let bit = if by_bit { format!("p{i}[{k}]") } else { format!("p{i}_tick") };
            let shape = if held == Held::Alternating {
                Shape::Unknown("its terminal count alternates every clock")
            } else {
                counter(width, Some(top), by_bit.then_some(k))
            };
            (
                verilog,
                bit,
                widen(&format!("p{i}"), width),
                shape,
                format!(
                    "wrap counter to {top} ({width} bits{}), shows {}",
                    match held {
                        Held::No => "",
                        Held::Constant => ", the count held in a register",
                        Held::Alternating => ", the count alternating every clock with another",
                    },
                    if by_bit { format!("bit {k}") } else { "its tick".into() }
                ),
            )
        }
        1 => {
            // A free-running counter, one of its bits shown.
            let width = r.range(3, 32) as u32;
            let k = if short {
                r.range(0, (width - 1).min(5) as u64) as u32
            } else {
                r.range((width - 1).min(16) as u64, (width - 1) as u64) as u32
            };
            let body = format!("p{i} <= p{i} + {width}'d1;");
            let verilog = format!(
                "    reg [{w1}:0] p{i} = {width}'d0;\n    always @(posedge {clk}) begin {} end\n",
                guard(&body),
                w1 = width - 1
            );
            let shape = counter(width, None, Some(k));
            fast = k <= 1;
            (
                verilog,
                format!("p{i}[{k}]"),
                widen(&format!("p{i}"), width),
                shape,
                format!("free counter ({width} bits), shows bit {k}"),
            )
        }
        2 => {
            // A divider: a wrap counter and a toggle that flips at its tick.
            let top = count(r);
            let width = (64 - top.leading_zeros()).min(32);
            // Held: `c + 1 >= top + 1` (the sum one bit wider), the same turn.
            let held = if held == Held::No { Held::No } else { Held::Constant };
            let (limit, hold) = held_limit(i, &clk, width + 1, top + 1, held);
            let turn = if held != Held::No {
                format!("{{1'b0, c{i}}} + {w}'d1 >= {limit}", w = width + 1)
            } else {
                format!("c{i} == {width}'d{top}")
            };
            let body =
                format!("if ({turn}) begin c{i} <= {width}'d0; p{i} <= ~p{i}; end else c{i} <= c{i} + {width}'d1;");
            let verilog = format!(
                "{hold}    reg [{w1}:0] c{i} = {width}'d0;\n    reg p{i} = 1'b0;\n    always @(posedge {clk}) begin {} end\n",
                guard(&body).replace(&format!("p{i} <= 0;"), &format!("p{i} <= 1'b0; c{i} <= {width}'d0;")),
                w1 = width - 1
            );
            // Short, a toggle every top + 1; long, the counter's low 4 bits (read with the
            // toggle by the port mux) repeat every 16 and the toggle flips at its wrap.
            let shape = if 2 * (top + 1) <= 64 {
                periodic(2 * (top + 1))
            } else if top + 1 >= 50_000 {
                Shape::Known { period: 16, boundary: Some(top + 1) }
            } else {
                Shape::Unknown("a count between short and long")
            };
            (
                verilog,
                format!("p{i}"),
                format!("{{c{i}[3:0], p{i}}}"),
                shape,
                format!(
                    "divider by {} (toggle{})",
                    2 * (top + 1),
                    if held == Held::No { "" } else { ", `c + 1 >= limit` with the limit held in a register" }
                ),
            )
        }
        3 => {
            // A rotating shift register (a ring), its last bit shown.
            let width = if tame { *r.pick(&[2u32, 3, 4, 6, 8, 12, 16]) } else { r.range(2, 16) as u32 };
            let body = format!("p{i} <= {{p{i}[{}:0], p{i}[{}]}};", width - 2, width - 1);
            let init = format!("{width}'d{}", 1 + r.range(0, (1 << (width - 1)) - 1));
            let verilog = format!(
                "    reg [{w1}:0] p{i} = {init};\n    always @(posedge {clk}) begin {} end\n",
                guard(&body).replace(&format!("p{i} <= 0;"), &format!("p{i} <= {init};")),
                w1 = width - 1
            );
            (
                verilog,
                format!("p{i}[{}]", width - 1),
                widen(&format!("p{i}"), width),
                periodic(width as u64),
                format!("ring of {width} bits"),
            )
        }
        4 => {
            // A PWM: a counter's low byte compared with a switch byte; the counter may be wider.
            let width = if r.chance(50) { 8 } else { r.range(9, 32) as u32 };
            let body = format!("p{i} <= p{i} + {width}'d1;");
            let byte = if r.chance(50) { "db_sw[15:8]" } else { "db_sw[7:0]" };
            let verilog = format!(
                "    reg [{w1}:0] p{i} = {width}'d0;\n    always @(posedge {clk}) begin {} end\n    wire p{i}_pwm = p{i}[7:0] < {byte};\n",
                guard(&body),
                w1 = width - 1
            );
            (
                verilog,
                format!("p{i}_pwm"),
                widen(&format!("p{i}"), width),
                periodic(256),
                format!("PWM: the low byte of a {width}-bit counter below {byte}"),
            )
        }
        5 => {
            // An LFSR (a game's random source): short ones repeat, long ones never within a run.
            let (width, taps): (u32, &[u32]) = *r.pick(&LFSRS[..if tame { 1 } else { LFSRS.len() }]);
            let fb: Vec<String> = taps.iter().map(|t| format!("p{i}[{t}]")).collect();
            let body = format!("p{i} <= {{p{i}[{}:0], {}}};", width - 2, fb.join(" ^ "));
            let verilog = format!(
                "    reg [{w1}:0] p{i} = {width}'d1;\n    always @(posedge {clk}) begin {} end\n",
                guard(&body).replace(&format!("p{i} <= 0;"), &format!("p{i} <= {width}'d1;")),
                w1 = width - 1
            );
            let shape = if width <= 7 { periodic((1 << width) - 1) } else { Shape::Unknown("a long LFSR") };
            (verilog, format!("p{i}[0]"), widen(&format!("p{i}"), width), shape, format!("LFSR of {width} bits"))
        }
        _ => {
            // A toggle.
            let body = format!("p{i} <= ~p{i};");
            let verilog = format!(
                "    reg p{i} = 1'b0;\n    always @(posedge {clk}) begin {} end\n",
                guard(&body).replace(&format!("p{i} <= 0;"), &format!("p{i} <= 1'b0;"))
            );
            (verilog, format!("p{i}"), format!("{{4'd0, p{i}}}"), periodic(2), "toggle".to_string())
        }
    };
    // An enabled part moves once per period of its enable: its period (in its clock) grows
    // by that much; enabled by a counter's tick, it changes only at the counter's boundary.
    let shape = match (shape, enable.map(|p| p.shape)) {
        (s, None) => s,
        (Shape::Known { period, boundary }, Some(Shape::Known { period: q, boundary: None })) => {
            Shape::Known { period: period * q, boundary: boundary.map(|b| b.saturating_mul(q)) }
        }
        (Shape::Unknown(w), _) | (_, Some(Shape::Unknown(w))) => Shape::Unknown(w),
        (_, Some(Shape::Known { .. })) => Shape::Unknown("moved by a counter's bit (not only at its boundaries)"),
    };
    let text = format!(
        "{text}{}{}",
        if reset { ", reset" } else { "" },
        enable.map_or(String::new(), |p| format!(", enabled by {}", p.bit))
    );
    Part { verilog, bit, value, shape, clock, text, fast, module: String::new(), resets: None, program: None }
}

/// Part `i`: a debouncer of the team's own, shaped as the Nexys3 release's (board.md §2.1) and
/// written as students write it, with the variations drawn from `r`: a wrap counter whose
/// terminal count is a `localparam` ternary on a lower-case `simulate` (left 0, or set 1 by
/// the instance), a `wire` given a constant, or a literal; cleared with `1'b0`, `0` or a sized
/// zero, sometimes by `reset || count == N`; its comparison tested again in a second always
/// block that shifts the buttons and switches into registers of 4 or 5 bits, each output set
/// by a `case` against 4-bit constants.
fn team_debouncer(r: &mut Rng, i: usize, clock: usize, tame: bool) -> Part {
    let clk = format!("@CLK{clock}@");
    let long = if tame { *r.pick(&[99_999u64, 199_999, 399_999]) } else { r.range(60_000, 4_000_000) };
    let short = if tame { *r.pick(&[2u64, 5, 11]) } else { r.range(1, 30) };
    let set_simulate = r.chance(30);
    let top = if set_simulate { short } else { long };
    let width = (64 - long.leading_zeros()).max(8) + r.range(0, 3) as u32;
    let w1 = width - 1;
    let clear = r.pick(&["1'b0".to_string(), "0".to_string(), format!("{width}'d0")]).clone();
    let one = *r.pick(&["1'b1", "1"]);
    let with_reset = r.chance(35);
    let sh = *r.pick(&[4u32, 5]);
    let (pbs, sws) = (r.range(1, 5) as usize, r.range(1, 8) as usize);
    let (count_decl, cmp) = match r.range(0, 2) {
        0 => (
            format!(
                "    parameter simulate = 0;
    localparam debounce_cnt = simulate ? {width}'d{short}
                                       : {width}'d{long};
"
            ),
            "debounce_cnt".to_string(),
        ),
        1 => (
            format!(
                "    parameter simulate = 0;
    wire [{w1}:0] top_cnt = simulate ? {short} : {long};
"
            ),
            "top_cnt".to_string(),
        ),
        _ => (String::new(), format!("{width}'d{top}")),
    };
    let cmp = if cmp.contains('\'') && set_simulate { format!("{width}'d{short}") } else { cmp };
    let counter = if with_reset {
        format!(
            "        if (reset || db_count == {cmp})
            db_count <= {clear};
        else
            db_count <= db_count + {one};
"
        )
    } else {
        format!(
            "        if (db_count == {cmp})
            db_count <= {clear};
        else
            db_count <= db_count + {one};
"
        )
    };
    let mut regs = String::new();
    let mut shifts = String::new();
    let mut cases = String::new();
    for (name, ins, n, out) in [("pb", "pbtn_in", pbs, "pbtn_db"), ("sw", "switch_in", sws, "swtch_db")] {
        for k in 0..n {
            writeln!(regs, "    reg [{}:0] shift_{name}{k} = {sh}'h0;", sh - 1).unwrap();
            writeln!(shifts, "            shift_{name}{k} <= (shift_{name}{k} << 1) | {ins}[{k}];").unwrap();
            writeln!(
                cases,
                "        case (shift_{name}{k}) 4'b0000: {out}[{k}] <= 0; 4'b1111: {out}[{k}] <= 1; endcase"
            )
            .unwrap();
        }
    }
    let module = format!(
        "
// A team's own debouncer (the Nexys3 release's shape, written as students write it).
module team_db{i} (
    input clk,{reset_port}
    input [4:0] pbtn_in,
    input [7:0] switch_in,
    output reg [4:0] pbtn_db = 5'h0,
    output reg [7:0] swtch_db = 8'h0
);
{count_decl}    reg [{w1}:0] db_count = {width}'h0;
{regs}
    always @(posedge clk)
    begin
{counter}    end

    always @(posedge clk)
    begin
        if (db_count == {cmp}) begin
{shifts}        end
{cases}    end
endmodule
",
        reset_port = if with_reset {
            "
    input reset,"
        } else {
            ""
        },
    );
    let params = if set_simulate && !count_decl.is_empty() { " #(.simulate(1))" } else { "" };
    let verilog = format!(
        "    wire [4:0] tdb{i}_pb;
    wire [7:0] tdb{i}_sw;
    team_db{i}{params} TDB{i} (.clk({clk}),{} .pbtn_in({{btnC, btnL, btnU, btnR, btnD}}), .switch_in(sw[7:0]),
        .pbtn_db(tdb{i}_pb), .swtch_db(tdb{i}_sw));
",
        if with_reset { " .reset(sysreset)," } else { "" }
    );
    // Between ticks nothing of it changes; its registers move only at a tick, and settle
    // (0000, 1111, 11111 held) while the inputs hold.
    let cycle = top + 1;
    let shape = if cycle <= 64 {
        periodic(cycle)
    } else if cycle < 50_000 {
        Shape::Unknown("a count between short and long")
    } else {
        Shape::Known { period: 1, boundary: Some(cycle) }
    };
    Part {
        verilog,
        bit: format!("tdb{i}_sw[0]"),
        value: format!("{{tdb{i}_sw[2:0], tdb{i}_pb[1:0]}}"),
        shape,
        clock,
        text: format!(
            "a team debouncer (Nexys3 shape): ticks every {cycle} clocks{}{}, {pbs} buttons and {sws} switches in {sh}-bit registers",
            if set_simulate { " (simulate = 1)" } else { "" },
            if with_reset { ", cleared by reset || count == N" } else { "" }
        ),
        fast: false,
        module,
        resets: (clock == 0).then(|| format!("tdb{i}_pb[0]")),
        program: None,
    }
}

/// A watchdog (the shapes design's WATCHDOG=1): a count that a heartbeat clears while armed,
/// its alarm (`count >= limit`) the part's bit. The heartbeat is an LFSR's state, a wrap
/// counter's zero or a ring's bit; armed always or by a free counter's high bit; disarmed,
/// the count is held at 0 or counts on; written with `if`s or a `?:`, the alarm a wire or a
/// register. The heartbeat clears the count in the middle of the board's period, so a
/// period that saw its first clear moved the count by what looks like a drift no later
/// period repeats (the fast-forward then needs a second period's proof). Not claimed within
/// reach.
/// A game's logic as final projects write it, on the board clock: a frame tick whose
/// terminal count the game's state chooses (two limits, compared with `<=` in one always
/// block and `==` in the next), which interrupts the team CPU; a raster scanned on the clock;
/// an obstacle an LFSR places at every tick; the sprite's place, which the firmware writes at
/// every tick ([`Program::Game`]); a collision flag when the raster is at both, a score
/// counted at each collision (the state flipping with it), the raster's comparison itself:
/// all read by the firmware through the game's port.
fn game_part(r: &mut Rng, i: usize) -> Part {
    let n = format!("gm{i}");
    let port = 0x20 + i;
    let (slow, fast) = (r.range(300, 3000), r.range(60, 299));
    let (h, v) = (r.range(8, 40), r.range(6, 30));
    let (width, taps): (u32, [u32; 2]) = *r.pick(&[(5, [4, 2]), (7, [6, 5]), (9, [8, 4])]);
    let reset = r.chance(40);
    let reset_if = if reset {
        format!("        if (sysreset) begin {n}_score <= 8'd0; {n}_state <= 1'b0; {n}_hit <= 1'b0; end else\n")
    } else {
        String::new()
    };
    let verilog = format!(
        "    // A game: its frame tick ({fast} or {slow} clocks, by its state), a {h} x {v} raster, an obstacle
    // from a {width}-bit LFSR, the sprite the firmware places, a collision flag and a score.
    reg        {n}_state = 1'b0;
    reg [11:0] {n}_cnt = 12'd0;
    reg        {n}_tick = 1'b0;
    always @(posedge clk) begin
        if ({n}_cnt <= ({n}_state ? 12'd{slow} : 12'd{fast})) {n}_cnt <= {n}_cnt + 12'd1;
        else {n}_cnt <= 12'd0;
    end
    always @(posedge clk) {n}_tick <= {n}_cnt == ({n}_state ? 12'd{slow} : 12'd{fast});
    always @(posedge clk) begin
        if (interrupt_ack | sysreset) interrupt <= 1'b0;
        else if ({n}_tick) interrupt <= 1'b1;
    end
    reg [5:0] {n}_h = 6'd0;
    reg [4:0] {n}_v = 5'd0;
    always @(posedge clk) begin
        if ({n}_h == 6'd{h1}) begin
            {n}_h <= 6'd0;
            {n}_v <= ({n}_v == 5'd{v1}) ? 5'd0 : {n}_v + 5'd1;
        end else {n}_h <= {n}_h + 6'd1;
    end
    reg [5:0] {n}_x = 6'd4;
    always @(posedge clk) if (write_strobe && port_id == 8'h{port:02X}) {n}_x <= out_port[5:0];
    reg [{w1}:0] {n}_lfsr = {{{width}{{1'b1}}}};
    reg [7:0] {n}_score = 8'd0;
    reg       {n}_hit = 1'b0;
    wire      {n}_at = ({n}_h == {n}_x) && ({n}_v == {n}_lfsr[4:0]);
    always @(posedge clk) begin
{reset_if}        if ({n}_tick) begin
            {n}_lfsr <= {{{n}_lfsr[{w2}:0], {n}_lfsr[{t0}] ^ {n}_lfsr[{t1}]}};
            {n}_hit <= 1'b0;
        end else if ({n}_at && !{n}_hit) begin
            {n}_hit <= 1'b1;
            {n}_score <= {n}_score + 8'd1;
            {n}_state <= ~{n}_state;
        end
    end
",
        h1 = h - 1,
        v1 = v - 1,
        w1 = width - 1,
        w2 = width - 2,
        t0 = taps[0],
        t1 = taps[1],
    );
    Part {
        verilog,
        bit: format!("{n}_hit"),
        value: format!("{{{n}_score[4:0], {n}_at, {n}_state, {n}_hit}}"),
        shape: Shape::Unknown("a game: its score, obstacle and sprite change at every frame tick"),
        clock: 0,
        text: format!(
            "a game: a frame tick every {fast} or {slow} clocks by its state (interrupting the CPU), a {h} x {v} raster, an obstacle from a {width}-bit LFSR, the sprite the firmware moves by btnL, a collision flag and a score{}",
            if reset { ", reset" } else { "" }
        ),
        fast: false,
        module: String::new(),
        resets: None,
        program: None,
    }
}

fn watchdog(r: &mut Rng, i: usize, clock: usize) -> Part {
    let clk = format!("@CLK{clock}@");
    let n = format!("wd{i}");
    // The heartbeat, and whether it repeats within reach by the generator's rules for its
    // kind (an LFSR of 7 bits or fewer, a ring, a counter of 64 or fewer).
    let (beat_decl, beat_step, beat, every, how, short) = match r.range(0, 2) {
        0 => {
            let (width, taps): (u32, [u32; 2]) = *r.pick(&[(5, [4, 2]), (7, [6, 5]), (9, [8, 4]), (10, [9, 6])]);
            (
                format!("    reg [{}:0] {n}_lfsr = {{{width}{{1'b1}}}};\n", width - 1),
                format!(
                    "        {n}_lfsr <= {{{n}_lfsr[{}:0], {n}_lfsr[{}] ^ {n}_lfsr[{}]}};\n",
                    width - 2,
                    taps[0],
                    taps[1]
                ),
                format!("{n}_lfsr == {width}'d1"),
                (1u64 << width) - 1,
                format!("an LFSR of {width} bits"),
                width <= 7,
            )
        }
        1 => {
            let every = r.range(20, 2000);
            (
                format!("    reg [10:0] {n}_hb = 11'd0;\n"),
                format!("        {n}_hb <= {n}_hb == 11'd{} ? 11'd0 : {n}_hb + 11'd1;\n", every - 1),
                format!("{n}_hb == 11'd0"),
                every,
                format!("a counter to {every}"),
                every <= 64,
            )
        }
        _ => {
            let every = r.range(8, 64);
            (
                format!("    reg [{}:0] {n}_ring = {every}'d1;\n", every - 1),
                format!("        {n}_ring <= {{{n}_ring[{}:0], {n}_ring[{}]}};\n", every - 2, every - 1),
                format!("{n}_ring[0]"),
                every,
                format!("a ring of {every} bits"),
                true,
            )
        }
    };
    let arm_bit = r.chance(70).then(|| r.range(12, 19));
    let (arm_decl, arm_step, armed) = if let Some(bit) = arm_bit {
        (
            format!("    reg [{bit}:0] {n}_arm = {}'d0;\n", bit + 1),
            format!("        {n}_arm <= {n}_arm + 1'b1;\n"),
            format!("{n}_arm[{bit}]"),
        )
    } else {
        (String::new(), String::new(), "1'b1".to_string())
    };
    let width = r.range(10, 16) as u32;
    let limit = r.range(every / 2 + 1, 3 * every).min((1 << width) - 1);
    let held = r.chance(50);
    let clear = if held { format!("!{armed} || ({beat})") } else { format!("{armed} && ({beat})") };
    let count = if r.chance(50) {
        format!("        if ({clear}) {n}_count <= {width}'d0;\n        else {n}_count <= {n}_count + 1'b1;\n")
    } else {
        format!("        {n}_count <= ({clear}) ? 0 : {n}_count + 1;\n")
    };
    let registered = r.chance(40);
    let alarm = if registered {
        format!(
            "    reg {n}_alarm = 1'b0;\n    always @(posedge {clk}) {n}_alarm <= {n}_count > {width}'d{};\n",
            limit - 1
        )
    } else {
        format!("    wire {n}_alarm = {n}_count >= {width}'d{limit};\n")
    };
    let verilog = format!(
        "    // A watchdog: its count cleared by a heartbeat ({how}).
{beat_decl}{arm_decl}    reg [{w1}:0] {n}_count = {width}'d0;
    always @(posedge {clk}) begin
{beat_step}{arm_step}{count}    end
{alarm}",
        w1 = width - 1
    );
    // Armed, the count repeats with the heartbeat; disarmed and held, it is 0; the arming
    // counter's bit is a boundary. Counting on while disarmed, or a heartbeat not within
    // reach, is not claimed.
    let shape = match (short, arm_bit) {
        (false, _) => Shape::Unknown("a watchdog's heartbeat between short and long"),
        (true, None) => periodic(every),
        (true, Some(bit)) if held && bit >= 16 => Shape::Known { period: every, boundary: Some(1 << bit) },
        (true, Some(_)) => Shape::Unknown("a watchdog armed at times between short and long, or counting on"),
    };
    Part {
        verilog,
        bit: format!("{n}_alarm"),
        value: format!("{{{n}_count[{}:{}], {n}_alarm}}", width - 1, width - 4),
        shape,
        clock,
        text: format!(
            "a watchdog: a {width}-bit count cleared by a heartbeat ({how}) every {every} cycles{}, {} disarmed, its alarm at {limit}{}",
            if armed == "1'b1" { ", always armed".to_string() } else { format!(", armed by {armed}") },
            if held { "held at 0" } else { "counting on" },
            if registered { " (registered)" } else { "" }
        ),
        fast: false,
        module: String::new(),
        resets: None,
        program: None,
    }
}

/// A part that runs apart from everything observed, as a UART's baud rate divider does beside
/// an idle transmitter (ddle_rojobotworld's `uart_tx6`, built of LUTs): a free-running source
/// (an LFSR stepped every cycle, or at the tick of a wrap counter, or a divider counting the
/// ticks) whose bit only a register reads: one that takes it while a switch is on, or an idle
/// transmitter's line, which shows it only while sending (a switch and a button together
/// start a send; the switches and buttons are random). While the switch is off or nothing is
/// sent, the board repeats with the rest's period only with the source's cycle. Not claimed
/// within reach.
fn free_part(r: &mut Rng, i: usize, clock: usize) -> Part {
    let clk = format!("@CLK{clock}@");
    let n = format!("fp{i}");
    let (width, taps): (u32, [u32; 2]) = *r.pick(&[(7, [6, 5]), (9, [8, 4]), (10, [9, 6])]);
    let lfsr_step = format!("{{{n}_src[{}:0], {n}_src[{}] ^ {n}_src[{}]}}", width - 2, taps[0], taps[1]);
    let baud = r.chance(60).then(|| r.range(20, 100));
    let (decl, step, bit, how) = match (baud, r.chance(50)) {
        (None, _) => (
            format!("    reg [{}:0] {n}_src = {width}'d1;\n", width - 1),
            format!("        {n}_src <= {lfsr_step};\n"),
            format!("{n}_src[0]"),
            format!("an LFSR of {width} bits"),
        ),
        (Some(b), lfsr) => {
            let counters = format!("    reg [6:0] {n}_baud = 7'd0;\n    reg {n}_tick = 1'b0;\n");
            let tick = format!(
                "        if ({n}_baud == 7'd{}) begin\n            {n}_baud <= 7'd0;\n            {n}_tick <= 1'b1;\n        end else begin\n            {n}_baud <= {n}_baud + 7'd1;\n            {n}_tick <= 1'b0;\n        end\n",
                b - 1
            );
            if lfsr {
                (
                    format!("{counters}    reg [{}:0] {n}_src = {width}'d1;\n", width - 1),
                    format!("{tick}        if ({n}_tick) {n}_src <= {lfsr_step};\n"),
                    format!("{n}_src[0]"),
                    format!("an LFSR of {width} bits stepped every {b} cycles"),
                )
            } else {
                (
                    format!("{counters}    reg [3:0] {n}_src = 4'd0;\n"),
                    format!("{tick}        {n}_src <= {n}_tick ? {n}_src + 4'd1 : {n}_src;\n"),
                    format!("{n}_tick && {n}_src == 4'd15"),
                    format!("a divider of 16 ticks every {b} cycles"),
                )
            }
        }
    };
    let sw = r.range(8, 13);
    let (taker, what) = if r.chance(50) {
        (
            format!("    reg {n}_out = 1'b0;\n    always @(posedge {clk}) {n}_out <= db_sw[{sw}] & ({bit});\n"),
            format!("taken while switch {sw} is on"),
        )
    } else {
        let btn = r.range(0, 4);
        (
            format!(
                "    reg {n}_busy = 1'b0;\n    reg [3:0] {n}_bits = 4'd0;\n    reg {n}_out = 1'b1;\n    always @(posedge {clk}) begin\n        if (!{n}_busy) begin\n            {n}_out <= 1'b1;\n            if (db_sw[{sw}] && db_btns[{btn}]) {n}_busy <= 1'b1;\n        end else if ({bit}) begin\n            {n}_out <= {n}_bits[0];\n            {n}_bits <= {n}_bits + 4'd1;\n            if ({n}_bits == 4'd9) {n}_busy <= 1'b0;\n        end\n    end\n"
            ),
            format!("an idle transmitter's line, sending while switch {sw} and button {btn} are on"),
        )
    };
    Part {
        verilog: format!(
            "    // A free part: {how}, {what}.\n{decl}    always @(posedge {clk}) begin\n{step}    end\n{taker}"
        ),
        bit: format!("{n}_out"),
        value: format!("{{4'd0, {n}_out}}"),
        shape: Shape::Unknown("a free part"),
        clock,
        text: format!("a free part: {how}, {what}"),
        fast: false,
        module: String::new(),
        resets: None,
        program: None,
    }
}

/// A second KCPSM6, as a team's own BotSim 3.1 bot has one beside the team's CPU: its program
/// waits in nested delays called as subroutines (BotSim's shape, two to four levels of random
/// counts), then reads a port and shows it and a toggle; its read mux registered as the
/// course's world_if31 writes it (a `case` on port_id's low bits that leaves items out, no
/// default) or with a default, on all of port_id or its low bits; its INPUT of a constant
/// port, or sometimes of a register's port (`INPUT sX, (sY)`), or of a port the mux leaves
/// out: then the core reads a value the mux kept, which a core apart must not have skipped.
fn own_core(r: &mut Rng, i: usize, clock: usize) -> Part {
    let clk = format!("@CLK{clock}@");
    let n = format!("oc{i}");
    let module = format!("owncore{i}");
    // The read mux: on port_id[3:0] or all of it, some items left out (never the port read).
    let low = r.chance(60);
    let port = r.range(0, 15);
    let default = r.chance(35);
    // Sometimes the port read is one left out (world_if31's "shouldn't be read" ports): the
    // core reads what the mux last took, which the run before the read decides.
    let read_left_out = !default && r.chance(35);
    let mut items = String::new();
    for v in 0..16u64 {
        if (v != port && r.chance(25)) || (v == port && read_left_out) {
            continue; // left out: keeps its value there
        }
        let value = match v % 4 {
            0 => "db_sw[7:0]".to_string(),
            1 => "db_sw[15:8]".to_string(),
            2 => format!("{{3'd0, db_btns}} ^ 8'h{:02X}", r.range(0, 255)),
            _ => format!("8'h{:02X}", r.range(0, 255)),
        };
        let item = if low { format!("4'h{v:X}") } else { format!("8'h{v:02X}") };
        writeln!(items, "            {item}: {n}_in_port <= {value};").unwrap();
    }
    if default {
        items.push_str(&format!("            default: {n}_in_port <= 8'h00;\n"));
    }
    let select = if low { format!("{n}_port_id[3:0]") } else { format!("{n}_port_id") };
    let register_port = r.chance(20);
    let levels = r.range(2, 4) as usize;
    let counts: Vec<u64> = (0..levels).map(|_| r.range(2, 60)).collect();
    // The program: main, then the delay levels (level 0 the innermost countdown).
    let mut psm = format!(
        "; {module}.psm: a second core's program (tests/common/random_design.rs).\n\
         main:       LOAD    s1, 00\n\
         loop:       CALL    wait{top}\n",
        top = levels - 1
    );
    if register_port {
        psm += &format!("            LOAD    s8, {port:02X}\n            INPUT   s0, (s8)\n");
    } else {
        psm += &format!("            INPUT   s0, {port:02X}\n");
    }
    psm += "            OUTPUT  s0, 01\n            XOR     s1, 01\n            OUTPUT  s1, 02\n            JUMP    loop\n";
    for (l, c) in counts.iter().enumerate() {
        let reg = 4 + l;
        if l == 0 {
            psm += &format!("wait0:      LOAD    s{reg:X}, {c:02X}\nspin0:      SUB     s{reg:X}, 01\n            JUMP    NZ, spin0\n            RETURN\n");
        } else {
            psm += &format!(
                "wait{l}:      LOAD    s{reg:X}, {c:02X}\nspin{l}:      CALL    wait{}\n            SUB     s{reg:X}, 01\n            JUMP    NZ, spin{l}\n            RETURN\n",
                l - 1
            );
        }
    }
    let verilog = format!(
        "    // A second KCPSM6 in nested delays (its own program, {module}.psm).
    wire [11:0] {n}_address;
    wire [17:0] {n}_instruction;
    wire        {n}_bram_enable, {n}_rdl, {n}_write_strobe, {n}_k_write_strobe, {n}_read_strobe;
    wire [ 7:0] {n}_port_id, {n}_out_port;
    reg  [ 7:0] {n}_in_port = 8'd0;
    kcpsm6 #(.interrupt_vector(12'h3FF), .scratch_pad_memory_size(64), .hwbuild(8'h00)) {n}_cpu (
        .address({n}_address), .instruction({n}_instruction), .bram_enable({n}_bram_enable),
        .port_id({n}_port_id), .write_strobe({n}_write_strobe), .k_write_strobe({n}_k_write_strobe),
        .out_port({n}_out_port), .read_strobe({n}_read_strobe), .in_port({n}_in_port),
        .interrupt(1'b0), .interrupt_ack(), .sleep(1'b0), .reset(sysreset | {n}_rdl), .clk({clk}));
    {module} {n}_pgm (.enable({n}_bram_enable), .address({n}_address), .instruction({n}_instruction),
        .rdl({n}_rdl), .clk({clk}));
    always @(posedge {clk}) begin
        case ({select})
{items}        endcase
    end
    reg [7:0] {n}_shown = 8'd0;
    reg       {n}_toggle = 1'b0;
    always @(posedge {clk}) begin
        if ({n}_write_strobe) begin
            if ({n}_port_id == 8'h01) {n}_shown <= {n}_out_port;
            if ({n}_port_id == 8'h02) {n}_toggle <= {n}_out_port[0];
        end
    end
"
    );
    let text = format!(
        "a second KCPSM6 in {levels} nested delays ({counts:?}), reading port {port:02X}{}{} through a mux on {}{}",
        if register_port { " by a register" } else { "" },
        if read_left_out { " (left out of the mux)" } else { "" },
        if low { "port_id[3:0]" } else { "port_id" },
        if default { " with a default" } else { " without a default" }
    );
    Part {
        verilog,
        bit: format!("{n}_toggle"),
        value: format!("{n}_shown"),
        shape: Shape::Unknown("a second core"),
        clock,
        text,
        fast: false,
        module: String::new(),
        resets: None,
        program: Some((module, psm)),
    }
}

/// LFSRs: width and taps (maximal length: 2^width - 1).
const LFSRS: [(u32, &[u32]); 5] =
    [(4, &[3, 2]), (5, &[4, 2]), (7, &[6, 5]), (16, &[15, 14, 12, 3]), (32, &[31, 21, 1, 0])];

/// At least five bits of `name` (a `width`-bit register), for a digit.
fn widen(name: &str, width: u32) -> String {
    if width >= 5 {
        name.to_string()
    } else {
        format!("{{{}'d0, {name}}}", 8 - width)
    }
}

/// A sprite on the VGA raster (pdxrayw_p2video's icon): a 16 x 16 window whose top left is the
/// bot's place (its LocY and LocX, times 4, less 7, as that team's) or a constant, its pixel a
/// function of its row and column within the window, shown on an LED. Teams keep the window's
/// edges in registers or compare with the sums directly, test the four comparisons in one
/// `if` or nested ones, and take the row within the window as a difference in the `if` or as
/// a `?:`.
#[derive(Debug)]
struct Sprite {
    /// The window's edges follow the bot (registers set from its LocX/LocY), or are constants.
    follows_bot: bool,
    /// The four comparisons in nested `if`s (rows, then columns), not one `&&`.
    nested: bool,
    /// The row and column within the window as `?:`s of the comparisons, not in the `if`.
    choice: bool,
    /// The window's top and left when constant.
    top: u64,
    left: u64,
}

impl Sprite {
    fn draw(r: &mut Rng) -> Sprite {
        Sprite {
            follows_bot: r.chance(60),
            nested: r.chance(40),
            choice: r.chance(30),
            top: r.range(0, 470),
            left: r.range(0, 630),
        }
    }

    /// Its Verilog on the pixel clock `net`; it drives `sprite_px`.
    fn verilog(&self, net: &str) -> String {
        let edges = if self.follows_bot {
            "        top <= {1'b0, locy, 2'b00} - 11'd7;
        bottom <= {1'b0, locy, 2'b00} + 11'd8;
        left <= {1'b0, locx, 2'b00} - 11'd7;
        right <= {1'b0, locx, 2'b00} + 11'd8;
"
            .to_string()
        } else {
            format!(
                "        top <= 11'd{t};\n        bottom <= 11'd{b};\n        left <= 11'd{l};\n        right <= 11'd{r};\n",
                t = self.top,
                b = self.top + 15,
                l = self.left,
                r = self.left + 15
            )
        };
        let inside_rows = "pixel_row >= top && pixel_row <= bottom";
        let inside_cols = "pixel_column >= left && pixel_column <= right";
        let (at, within) = if self.choice {
            (
                "",
                "    wire [3:0] spr_row = (pixel_row >= top) ? pixel_row - top : 4'd0;
    wire [3:0] spr_col = (pixel_column >= left) ? pixel_column - left : 4'd0;
",
            )
        } else {
            (
                "                spr_row <= pixel_row - top;
                spr_col <= pixel_column - left;
",
                "    reg [3:0] spr_row = 4'd0, spr_col = 4'd0;\n",
            )
        };
        let body =
            format!("{at}                sprite_px <= spr_row[3] ^ spr_col[3] ^ (spr_row[1:0] == spr_col[1:0]);\n");
        let test = if self.nested {
            format!(
                "        if ({inside_rows}) begin
            if ({inside_cols}) begin
{body}            end else sprite_px <= 1'b0;
        end else sprite_px <= 1'b0;
"
            )
        } else {
            format!(
                "        if (({inside_rows}) && ({inside_cols})) begin
{b}        end else sprite_px <= 1'b0;
",
                b = body.replace("                ", "            ")
            )
        };
        format!(
            "    // A sprite on the raster, its pixel on LED 14.
    reg [10:0] top = 11'd0, bottom = 11'd0, left = 11'd0, right = 11'd0;
    reg sprite_px = 1'b0;
{within}    always @(posedge {net}) begin
{edges}{test}    end
"
        )
    }
}

/// Whether the design repeats within reach, and with which period (100 MHz clocks).
fn reach(
    parts: &[Part],
    clocks: &[Clock],
    simulate: bool,
    kind: Program,
    vga_observed: Option<&str>,
) -> Result<u64, String> {
    if let Some(why) = vga_observed {
        return Err(why.into());
    }
    let osc = clocks[0].period;
    // The course's modules: 6-clock wrap counters with SIMULATE = 1 (a display of 8 digits
    // every 48), long counters with 0.
    let mut period = osc.times(if simulate { 48 } else { 1 });
    let mut shortest = u64::MAX;
    if !simulate {
        shortest = 200_000;
    }
    period = period.lcm(osc.times(program_period(kind)));
    if let Program::Delay(d) = kind {
        if let Some(why) = d.unskippable() {
            return Err(why);
        }
        // The delay's end is a boundary, as a counter's.
        shortest = shortest.min(d.trip() * d.turns());
    }
    let mut used = vec![false; clocks.len()];
    used[0] = true;
    for p in parts {
        used[p.clock] = true;
        let c = clocks[p.clock].period;
        match p.shape {
            Shape::Known { period: k, boundary } => {
                period = period.lcm(c.times(k));
                if let Some(b) = boundary {
                    shortest = shortest.min(c.times(b).clocks());
                }
            }
            Shape::Unknown(why) => return Err(why.into()),
        }
    }
    for (i, c) in clocks.iter().enumerate() {
        if used[i] {
            period = period.lcm(c.period);
        }
    }
    let clocks_in_period = period.clocks();
    // A skip needs the period proved twice and a settle after each counter boundary: with
    // boundaries 50 x that far apart, under 5 % of the time is simulated.
    if clocks_in_period > 16_384 {
        return Err(format!("its period is {clocks_in_period} clocks"));
    }
    if shortest < 50 * (256 + 3 * clocks_in_period) {
        return Err(format!("a counter's boundaries are {shortest} clocks apart, its period {clocks_in_period}"));
    }
    Ok(clocks_in_period)
}

/// A team's own display timing generator for 640 x 480, written as many teams write theirs:
/// it counts its totals inclusively (`== 800` wraps after 801 pixels, `>= 525` after 526
/// lines) and ends its syncs with `<=` (97 pixels, 3 lines); a monitor shows it all the same.
const TEAM_DTG: &str = "
module team_dtg (
    input  wire        clock,
    input  wire        rst,
    output reg         horiz_sync = 1'b1,
    output reg         vert_sync = 1'b1,
    output reg         video_on = 1'b0,
    output reg  [10:0] pixel_row = 11'd0,
    output reg  [10:0] pixel_column = 11'd0
);
    always @(posedge clock) begin
        if (rst) begin
            pixel_column <= 11'd0;
            pixel_row <= 11'd0;
        end else begin
            if (pixel_column == 11'd800) pixel_column <= 11'd0;
            else pixel_column <= pixel_column + 11'd1;
            if (pixel_row >= 11'd525 && pixel_column >= 11'd800) pixel_row <= 11'd0;
            else if (pixel_column == 11'd800) pixel_row <= pixel_row + 11'd1;
        end
        horiz_sync <= ~(pixel_column >= 11'd656 && pixel_column <= 11'd752);
        vert_sync <= ~(pixel_row >= 11'd490 && pixel_row <= 11'd492);
        video_on <= pixel_column < 11'd640 && pixel_row < 11'd480;
    end
endmodule
";
