//! The benchmarks' clocks: a thread's wall time, time on a core and time waiting for one, a
//! control workload whose time on a core is the machine's noise floor, and percentiles.

use std::time::Instant;

/// The control: the same work every frame (two passes of integer arithmetic over half a
/// megabyte, read and written), near the terrain systems' median time on a core here. It does
/// not change from frame to frame, so what its time on a core does is what the machine does to
/// the thread (interrupts handled on its core, the pool threads' cache and memory traffic): the
/// noise floor of the terrain's figures beside it.
pub fn control(scratch: &mut Vec<u64>) -> u64 {
    const WORDS: usize = 1 << 16;
    const PASSES: usize = 2;
    if scratch.len() != WORDS {
        *scratch = (0..WORDS as u64).collect();
    }
    let mut acc = 0x9e37_79b9_7f4a_7c15_u64;
    for _ in 0..PASSES {
        for word in scratch.iter_mut() {
            acc = (acc ^ *word).wrapping_mul(0x2545_f491_4f6c_dd1d).rotate_left(17);
            *word = word.wrapping_add(acc >> 60);
        }
    }
    acc
}

/// The calling thread's clocks at one instant: wall time; time on a core, in ns
/// (`CLOCK_THREAD_CPUTIME_ID`: the kernel brings the running thread's figure up to date when
/// asked, so it is exact); and time waiting for a core, in ns (the second field of
/// `/proc/thread-self/schedstat`: the kernel adds a wait when the thread gets a core back, so an
/// interval's is exact). Where a clock is missing (not Linux) it reads 0, and an interval's
/// wall time counts as time on a core.
#[derive(Clone, Copy)]
pub struct Clocks {
    wall: Instant,
    cpu: Option<u64>,
    waiting: u64,
}

impl Clocks {
    pub fn now() -> Self {
        let waiting = waiting_ns();
        #[cfg(unix)]
        let cpu = {
            let t = rustix::time::clock_gettime(rustix::time::ClockId::ThreadCPUTime);
            u64::try_from(t.tv_sec).ok().zip(u64::try_from(t.tv_nsec).ok()).map(|(s, n)| s * 1_000_000_000 + n)
        };
        #[cfg(not(unix))]
        let cpu = None;
        Self { wall: Instant::now(), cpu, waiting }
    }

    /// Wall time from `earlier` to `self`, and of it the time on a core, waiting for a core and
    /// asleep in the kernel, in ms.
    pub fn since(self, earlier: Self) -> [f64; 4] {
        let wall = (self.wall - earlier.wall).as_secs_f64() * 1e3;
        let waiting = self.waiting.saturating_sub(earlier.waiting) as f64 * 1e-6;
        let cpu = match (self.cpu, earlier.cpu) {
            (Some(b), Some(a)) => b.saturating_sub(a) as f64 * 1e-6,
            _ => (wall - waiting).max(0.0),
        };
        [wall, cpu, waiting, (wall - cpu - waiting).max(0.0)]
    }
}

/// The calling thread's total time waiting for a core, in ns: the second field of its
/// `/proc/thread-self/schedstat`, opened once per thread and read again from its start (a read
/// costs a microsecond or two, where opening the file by its path costs several), 0 where there
/// is no such file.
fn waiting_ns() -> u64 {
    thread_local! {
        static FILE: Option<std::fs::File> = std::fs::File::open("/proc/thread-self/schedstat").ok();
    }
    FILE.with(|file| {
        let Some(file) = file else { return 0 };
        let mut buf = [0u8; 128];
        #[cfg(unix)]
        let read = std::os::unix::fs::FileExt::read_at(file, &mut buf, 0).unwrap_or(0);
        #[cfg(not(unix))]
        let read = 0;
        let text = std::str::from_utf8(&buf[..read]).unwrap_or_default();
        text.split_whitespace().nth(1).and_then(|f| f.parse().ok()).unwrap_or(0)
    })
}

pub fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}
