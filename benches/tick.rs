//! The RTL's clock loop under Verilator (criterion). Throughput is in cycles: criterion's
//! "elem/s" reads as cycles per second. `botsim bench` prints the same figures as a table.
//!
//! - `run`: the batched C++ loop (one FFI call for all the cycles), tracing compiled in, off;
//! - `wait_update`: the same loop stopping at upd_sysregs (one `fast`-timing sample);
//! - `tick`: one FFI call per cycle with the outputs returned, for comparison.

use botsim::{Firmware, MotCtl, RtlBot, Timing};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};

fn rtl(c: &mut Criterion) {
    let mut g = c.benchmark_group("rtl");
    let mut bot = RtlBot::builder().motors(MotCtl::FORWARD).build().unwrap();
    const CYCLES: u64 = 1_000_000;
    g.throughput(Throughput::Elements(CYCLES));
    g.bench_function("run", |b| b.iter(|| bot.run(CYCLES).unwrap()));

    let fw = Firmware { timing: Timing::Fast, ..Firmware::default() };
    let mut fast = RtlBot::builder().firmware(fw).motors(MotCtl::FORWARD).build().unwrap();
    fast.wait_update().unwrap();
    fast.wait_update().unwrap(); // samples 0 and 1 come right after start-up
    let per_sample = {
        let c0 = fast.cycle();
        fast.wait_update().unwrap();
        fast.cycle() - c0
    };
    g.throughput(Throughput::Elements(per_sample));
    g.bench_function("wait_update", |b| b.iter(|| fast.wait_update().unwrap()));

    g.throughput(Throughput::Elements(10_000));
    g.bench_function("tick", |b| {
        b.iter(|| {
            for _ in 0..10_000 {
                bot.tick().unwrap();
            }
        })
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = rtl
}
criterion_main!(benches);
