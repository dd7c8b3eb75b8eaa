//! The fast-forward: how a board run skips board time it does not need to simulate edge by
//! edge, and the proofs that let it.
//!
//! # The promise
//!
//! A run that fast-forwards records **exactly what the same run with every edge simulated
//! records**: the same display, LED, VGA, UART, audio and bot events at the same picoseconds,
//! the same bot samples, the same `--pins` file, edge for edge, under any stimulus. Nothing
//! is approximated; a design the analyses cannot prove safe runs every edge and the run says
//! why (`fast_forward.off_because`, `kept_busy_by`).
//!
//! # The mechanisms
//!
//! The skip itself is the harness's (`src/board/harness.cpp`, `ff_step`): it marks the board
//! (the bytes of Verilator's root object and the CPU models), finds a period after which the
//! board is back at its mark, and repeats that period's records as many times as fit before
//! the next input, putting the state back as it was. Each mechanism below widens what counts
//! as "back at its mark"; each comes with the obligation it must meet and the test that
//! proves it.
//!
//! | mechanism | what it lets the skip ignore or move | proof obligation | proved by |
//! |---|---|---|---|
//! | [`checks`] | nothing: it decides whether the root object *is* the board's whole state (no `$time`, `$random`, files, prints, DPI of the user's, timing outside the root) | a skip from equal bytes changes nothing a run records | tests/boards/hostile.rs; `checks` unit tests |
//! | [`observed`] | variables nothing recorded reads (a VGA design's raster when no frames are asked for) and the clocks that drive only them (parked) | every variable a record reads, through any chain of assignments and conditions, is compared | `observed` unit tests; tests/boards/shapes.rs (VGA shapes); tests/boards/random_designs.rs |
//! | [`counters`] (with [`demand`]) | free-running counters, moved on by arithmetic across a skip when the rest sees only bits or comparisons the skip does not change | each read of a counter needs only bits constant over the skip, or a comparison with a constant not crossed | `counters`, `demand` unit tests; tests/boards/shapes.rs (2^18, 2^20, 32-bit counters) |
//! | [`strobes`] | what a KCPSM6 shows on `out_port` between OUTPUTs, where the design reads it only under a write strobe | every read of `out_port` sits under a condition true only with a strobe | `strobes` unit tests; tests/boards/shapes.rs |
//! | `counts` | a core's count in a software delay: the period counts, and the board skips as many periods as the count allows | [`kcpsm6::counting`]'s proof that the period only counts, and how far | `counts` unit tests; tests/cpu_lockstep.rs; tests/boards/random_designs.rs (delay programs) |
//! | [`apart`] (with [`solo`]) | a core whose firmware keeps to itself runs on its own up to its next port access while the board skips | the design reads the core's outputs only under a strobe or into its followers (its ROM and read mux) | `apart`, `solo` unit tests; tests/boards/shapes.rs (second core in nested delays) |
//!
//! [`cpp`] reads the C++ Verilator generates and [`dialect`] brings later Verilators' C++ to
//! 5.006's, for these analyses only. Every analysis runs once, when the design is built
//! (`crate::board::build`), and its verdicts are kept beside the model; the harness reads
//! them at run time.
//!
//! The checks that guard the promise end to end: tests/boards/random_designs.rs (random
//! designs, fast against every edge, record for record), tests/boards/differential.rs and
//! `botsim board --check` (the fast board against the all-RTL board), tests/boards/shapes.rs
//! (the course's shapes skip nearly all their time and equal every edge).

pub mod apart;
pub mod checks;
pub mod counters;
pub(crate) mod counts;
pub mod cpp;
pub mod demand;
pub mod dialect;
pub mod observed;
pub mod solo;
pub mod strobes;
