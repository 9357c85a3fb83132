//! The clock of the benches' own tables (`engine`, `dynamics`): the CPU time of the running
//! thread where the platform gives it, else the wall time. On a loaded machine a run of a few
//! milliseconds is preempted for whole time slices (4 ms on the shared machine), so its wall time
//! comes in steps of that size, which no minimum over repetitions removes; its CPU time does not.

use std::time::{Duration, Instant};

/// The CPU time of this thread (Linux: `clock_gettime(CLOCK_THREAD_CPUTIME_ID)` of the C library
/// that std links), or `None` elsewhere.
#[cfg(all(target_os = "linux", target_pointer_width = "64"))]
pub fn thread_cpu() -> Option<Duration> {
    #[repr(C)]
    struct Timespec {
        sec: i64,
        nsec: i64,
    }
    extern "C" {
        fn clock_gettime(clock: i32, tp: *mut Timespec) -> i32;
    }
    const CLOCK_THREAD_CPUTIME_ID: i32 = 3;
    let mut t = Timespec { sec: 0, nsec: 0 };
    // SAFETY: `t` is a valid `struct timespec` of this target (two 64-bit fields).
    let rc = unsafe { clock_gettime(CLOCK_THREAD_CPUTIME_ID, &mut t) };
    (rc == 0).then(|| Duration::new(t.sec as u64, t.nsec as u32))
}

#[cfg(not(all(target_os = "linux", target_pointer_width = "64")))]
pub fn thread_cpu() -> Option<Duration> {
    None
}

/// What `f` returns, and the time it takes by this clock.
pub fn timed<T>(f: impl FnOnce() -> T) -> (T, Duration) {
    let (t, cpu) = (Instant::now(), thread_cpu());
    let out = f();
    let took = match (cpu, thread_cpu()) {
        (Some(a), Some(z)) => z.saturating_sub(a),
        _ => t.elapsed(),
    };
    (out, took)
}

/// What the tables' times are.
pub fn name() -> &'static str {
    if thread_cpu().is_some() {
        "CPU time of the thread"
    } else {
        "wall time"
    }
}
