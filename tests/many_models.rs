//! Many models at once: 16+ RtlBot models across 8 threads, with and without VCD, created and
//! dropped in random orders; each gets exactly the result it gets alone (no crosstalk through
//! Verilator's global state, no hang at teardown: spec/verilator.md H1-H3).

use std::sync::{mpsc, Arc, Barrier};
use std::time::Duration;

use botsim::regs::Registers;
use botsim::{Error, MotCtl, RtlBot, Timing};

/// Every snapshot of a run: (cycle, registers).
type Trace = Vec<(u64, Registers)>;

/// A scenario: a motor command, a threshold and a sample count; the result is every snapshot.
#[derive(Clone, Copy)]
struct Job {
    motors: u8,
    threshold: u8,
    samples: usize,
    vcd: bool,
}

fn run(job: Job, dir: &std::path::Path, id: usize) -> Trace {
    let mut b = RtlBot::builder().timing(Timing::Fast).threshold(job.threshold).motors(MotCtl(job.motors));
    if job.vcd {
        b = b.vcd(dir.join(format!("m{id}.vcd")));
    }
    let mut bot = b.build().unwrap();
    (0..job.samples).map(|_| bot.wait_update().map(|s| (s.cycle, s.regs)).unwrap()).collect()
}

fn jobs() -> Vec<Job> {
    (0..24)
        .map(|i| Job {
            motors: [0x33, 0x22, 0x30, 0x03, 0x23, 0x32, 0x00, 0x20][i % 8],
            threshold: 1 + (i % 5) as u8,
            samples: 20 + (i * 7) % 30,
            vcd: i % 3 == 0,
        })
        .collect()
}

/// Run `f` on its own thread; fail (instead of hanging the test run) if it takes too long.
fn within(limit: Duration, f: impl FnOnce() + Send + 'static) {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        f();
        let _ = tx.send(());
    });
    match rx.recv_timeout(limit) {
        Ok(()) => {}
        Err(mpsc::RecvTimeoutError::Timeout) => panic!("hung: not finished within {limit:?}"),
        Err(mpsc::RecvTimeoutError::Disconnected) => panic!("the test body panicked (see above)"),
    }
}

#[test]
fn models_in_parallel_threads_match_their_solo_runs() {
    within(Duration::from_secs(120), parallel_threads);
}

fn parallel_threads() {
    let dir = tempfile::tempdir().unwrap();
    let jobs = jobs();
    // Alone, one after the other, on this thread.
    let solo: Vec<_> = jobs.iter().enumerate().map(|(i, &j)| run(j, dir.path(), 100 + i)).collect();
    // Together: 8 threads, 3 models each, all alive at once, stepped in an interleaved order
    // and dropped in a thread-specific order.
    let barrier = Arc::new(Barrier::new(8));
    let handles: Vec<_> = (0..8)
        .map(|t| {
            let barrier = barrier.clone();
            let dir = dir.path().to_path_buf();
            let mine: Vec<(usize, Job)> = (0..3).map(|k| (t * 3 + k, jobs[t * 3 + k])).collect();
            std::thread::spawn(move || {
                let mut bots: Vec<(usize, RtlBot, Trace)> = mine
                    .iter()
                    .map(|&(i, j)| {
                        let mut b =
                            RtlBot::builder().timing(Timing::Fast).threshold(j.threshold).motors(MotCtl(j.motors));
                        if j.vcd {
                            b = b.vcd(dir.join(format!("p{i}.vcd")));
                        }
                        (i, b.build().unwrap(), vec![])
                    })
                    .collect();
                barrier.wait();
                let longest = mine.iter().map(|(_, j)| j.samples).max().unwrap();
                for step in 0..longest {
                    for (i, bot, out) in bots.iter_mut() {
                        if step < jobs_samples(&mine, *i) {
                            let s = bot.wait_update().unwrap();
                            out.push((s.cycle, s.regs));
                        }
                    }
                }
                // Drop out of creation order (the H1 hazard).
                let order: Vec<usize> = match t % 3 {
                    0 => vec![1, 0, 2],
                    1 => vec![2, 1, 0],
                    _ => vec![0, 2, 1],
                };
                let mut results = vec![];
                let mut slots: Vec<Option<_>> = bots.into_iter().map(Some).collect();
                for k in order {
                    let (i, bot, out) = slots[k].take().unwrap();
                    drop(bot);
                    results.push((i, out));
                }
                results
            })
        })
        .collect();
    let mut together = vec![vec![]; jobs.len()];
    for h in handles {
        for (i, out) in h.join().expect("a model thread panicked") {
            together[i] = out;
        }
    }
    for (i, (a, b)) in solo.iter().zip(&together).enumerate() {
        assert_eq!(a, b, "model {i} differs when run beside others");
    }
    // Every requested waveform was written and is complete.
    for (i, j) in jobs.iter().enumerate() {
        if j.vcd {
            let text = std::fs::read_to_string(dir.path().join(format!("p{i}.vcd"))).unwrap();
            assert!(text.contains("$enddefinitions") && text.lines().count() > 1000, "p{i}.vcd");
        }
    }
}

fn jobs_samples(mine: &[(usize, Job)], i: usize) -> usize {
    mine.iter().find(|(k, _)| *k == i).map(|(_, j)| j.samples).unwrap()
}

#[test]
fn models_created_and_dropped_in_random_orders_on_one_thread() {
    within(Duration::from_secs(120), random_orders);
}

fn random_orders() {
    // Several contexts on one thread, freed out of LIFO order: 5.006 deadlocked here without
    // the teardown order of the shim (H1).
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut live: Vec<RtlBot> = vec![];
    for round in 0..60 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        if live.len() < 2 || (x % 3 != 0 && live.len() < 12) {
            let mut b = RtlBot::builder().timing(Timing::Fast).build().unwrap();
            b.wait_update().unwrap();
            live.push(b);
        } else {
            let k = (x as usize >> 8) % live.len();
            live.remove(k);
        }
        if round % 10 == 0 {
            for b in live.iter_mut() {
                assert_eq!(b.wait_update().unwrap().regs.loc_x, 0x40);
            }
        }
    }
}

#[test]
fn a_fatal_error_belongs_to_the_model_it_stopped() {
    // A VCD on a full device: Verilator's write fails, a fatal runtime error, kept for the model
    // it stopped. The message used to be kept per thread: a model dropped with its error
    // unread left it to the next model on the thread, whose next call then failed with it.
    if !std::path::Path::new("/dev/full").exists() {
        eprintln!("note: no /dev/full here; skipping");
        return;
    }
    let fast = || RtlBot::builder().timing(Timing::Fast);
    let mut a = fast().vcd("/dev/full").build().unwrap();
    match a.run(200_000) {
        Err(Error::Waveform(why)) => assert!(why.contains("No space left"), "{why}"),
        other => panic!("expected a waveform error, got {other:?}"),
    }
    let mut b = fast().build().unwrap();
    b.wait_update().unwrap();
    assert!(b.close_vcd().is_ok(), "another model's error is not this one's");
    // Dropped with its error unread, the failed model leaves nothing behind either.
    let c = fast().vcd("/dev/full").build().unwrap();
    drop(c);
    let mut d = fast().build().unwrap();
    assert!(d.close_vcd().is_ok());
    assert_eq!(d.wait_update().unwrap().sample, 0);
}
