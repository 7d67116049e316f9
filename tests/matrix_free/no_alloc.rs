//! The solver allocates nothing: a counting global allocator sees no allocation on the test's
//! thread while a ring model is decomposed and searched for 100 forcing periods.

use rotor_rub::driver::SegmentStart;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

use rotor_rub::driver::SegmentSolver;
use rotor_rub::matrix::ExactFree;
use rotor_rub::propagate::Regime;

use super::common::*;

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
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
fn decomposition_and_search_allocate_nothing() {
    let case = Case::load("ring_nonsymmetric");
    let model = case.model();
    let start = case.start();
    let period = 2.0 * std::f64::consts::PI / case.speed;
    COUNTED.with(|c| c.set(true));
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    let mut free = ExactFree::new(&model).unwrap();
    free.start(SegmentStart {
        regime: Regime::Free,
        slip: 0.0,
        time: case.t0,
        state: start,
    })
    .unwrap();
    let mut reached = 0;
    for k in 1..=100 {
        if let rotor_rub::driver::Located::Reached(_) =
            run_to(&mut free, case.t0 + k as f64 * period)
        {
            reached += 1;
        }
    }
    let after = ALLOCATIONS.load(Ordering::SeqCst);
    COUNTED.with(|c| c.set(false));
    assert_eq!(after, before, "allocated {} times", after - before);
    assert_eq!(reached, 100);
}
