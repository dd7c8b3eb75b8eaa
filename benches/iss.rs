//! The instruction-set simulator (criterion); throughput in cycles ("elem/s").
//!
//! - `backend_sample`: the ISS backend over one `hw` sample (5.3 M cycles, busy-waits
//!   fast-forwarded), as `botsim bench` measures it;
//! - `cpu_tick`: the cycle-level [`Cpu::tick`] on the firmware, the path the lock-step uses;
//! - `cpu_run_fast`: whole instructions at a time, without the busy-wait fast-forward
//!   (a program with no countdown loop);
//! - `nested_delay_run_fast` / `nested_delay_run_with`: one turn of a main loop that waits in
//!   the course firmware's shape of delay (four nested levels, about 5 M cycles), without and
//!   with the replay of subroutines that only compute ([`Routines`]).

use botsim::kcpsm6::iss::{Config, Cpu, NullBus, Pins, Routines};
use botsim::IssBot;
use botsim::{Firmware, MotCtl, World};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};

fn iss(c: &mut Criterion) {
    let mut g = c.benchmark_group("iss");
    let image = Firmware::default().assemble().unwrap();
    let mut bot = IssBot::new(&image, World::builtin()).unwrap();
    bot.set_motors(MotCtl::FORWARD);
    // Samples 0 and 1 come right after start-up; from then on a sample is a full period.
    bot.wait_update_within(20_000_000).unwrap();
    bot.wait_update_within(20_000_000).unwrap();
    let c0 = bot.cycle();
    bot.wait_update_within(20_000_000).unwrap();
    g.throughput(Throughput::Elements(bot.cycle() - c0));
    g.bench_function("backend_sample", |b| b.iter(|| bot.wait_update_within(20_000_000).unwrap()));

    let mut cpu = Cpu::new(Config::default(), &image.words[..1024]);
    let mut bus = NullBus::default();
    g.throughput(Throughput::Elements(100_000));
    g.bench_function("cpu_tick", |b| {
        b.iter(|| {
            for _ in 0..100_000 {
                cpu.tick(Pins::default(), &mut bus);
            }
        })
    });

    // ADD/XOR/JUMP: no busy-wait idiom to fast-forward.
    let p = botsim::kcpsm6::asm::assemble_str("start: ADD s0, 01\nXOR s1, s0\nJUMP start\n").unwrap();
    let mut cpu = Cpu::new(Config::default(), &p.image.words[..1024]);
    g.bench_function("cpu_run_fast", |b| {
        b.iter(|| {
            let end = cpu.cycle() + 100_000;
            cpu.run_fast(&mut bus, end, |_| false)
        })
    });

    let p = botsim::kcpsm6::asm::assemble_str(
        "main: OUTPUT s5, 01\nCALL wait4\nADD s5, 01\nJUMP main\n\
         wait1: LOAD s0, 18\nspin: SUB s0, 01\nJUMP NZ, spin\nRETURN\n\
         wait2: LOAD s1, 28\nturn2: CALL wait1\nSUB s1, 01\nJUMP NZ, turn2\nRETURN\n\
         wait3: LOAD s2, 19\nturn3: CALL wait2\nSUB s2, 01\nJUMP NZ, turn3\nRETURN\n\
         wait4: LOAD s3, 32\nturn4: CALL wait3\nSUB s3, 01\nJUMP NZ, turn4\nRETURN\n",
    )
    .unwrap();
    let turn = |cpu: &mut Cpu, bus: &mut NullBus, routines: Option<&mut Routines>| {
        let end = cpu.cycle() + 5_000_000;
        match routines {
            Some(r) => cpu.run_with(bus, end, |_| false, r),
            None => cpu.run_fast(bus, end, |_| false),
        }
    };
    g.throughput(Throughput::Elements(5_000_000));
    let mut cpu = Cpu::new(Config::default(), &p.image.words[..1024]);
    g.bench_function("nested_delay_run_fast", |b| b.iter(|| turn(&mut cpu, &mut bus, None)));
    let mut cpu = Cpu::new(Config::default(), &p.image.words[..1024]);
    let mut routines = Routines::default();
    g.bench_function("nested_delay_run_with", |b| b.iter(|| turn(&mut cpu, &mut bus, Some(&mut routines))));
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = iss
}
criterion_main!(benches);
