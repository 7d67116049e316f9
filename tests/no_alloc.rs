//! Propagation allocates nothing: a counting global allocator sees no allocation while the
//! analytic method runs 1000 forcing periods of the paper preset (events, samples, Poincaré).
//! Only the test's own thread is counted (the test harness's thread may allocate meanwhile).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

use rotor_rub::{Options, Preset, Propagate, Propagator, advance_to, poincare};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    /// Whether this thread's allocations are counted.
    static COUNTED: Cell<bool> = const { Cell::new(false) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTED.try_with(Cell::get).unwrap_or(false) {
            ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        }
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn propagation_over_1000_periods_allocates_nothing() {
    let problem = Preset::Paper.problem();
    let period = problem.params.forcing_period();
    COUNTED.with(|c| c.set(true));
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    let mut p = Propagator::new(&problem, &Options::default()).expect("valid preset");
    let mut switches = 0usize;
    for k in 1..=1000 {
        advance_to(&mut p, k as f64 * period, |_| switches += 1).expect("propagates");
    }
    let mut strobe = 0usize;
    for s in poincare(&mut p, problem.params.speed_ratio, 10) {
        s.expect("propagates");
        strobe += 1;
    }
    let after = ALLOCATIONS.load(Ordering::SeqCst);
    COUNTED.with(|c| c.set(false));
    assert_eq!(
        after,
        before,
        "propagation allocated {} times",
        after - before
    );
    assert!(
        switches > 1000,
        "the paper preset rubs every period: {switches} switches"
    );
    assert_eq!(strobe, 10);
    assert!(p.time() > 1000.0 * period);
}
