//! Nothing in `linalg` allocates: a counting global allocator (per thread, so the other tests
//! of this binary running in parallel do not count) sees no allocation while a rotor's modal
//! form is built, projected, evaluated and bounded, and the harmonic response solved.

use super::common::*;
use rotor_rub::linalg::{
    Complex, HarmonicResponse, ModalExponential, ProjectedMotion, eigenvalues,
};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // `try_with`: the thread-local may be gone while a thread shuts down.
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn building_evaluating_and_bounding_allocate_nothing() {
    let rotor = two_disk_rotor();
    let force = [Complex::new(0.2, 0.0); 8];
    let y0 = [0.1; 16];
    let (bx, by) = (
        [
            0.0, 0.0, 1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
        ],
        {
            let mut b = [0.0; 16];
            b[3] = 1.0;
            b[7] = -1.0;
            b
        },
    );
    let before = ALLOCATIONS.with(Cell::get);
    let a = rotor.second_order().first_order(0.7).unwrap();
    let modal = ModalExponential::new(&a).unwrap();
    let mut motion = ProjectedMotion::new(&modal, &bx, &by).unwrap();
    motion.set_state(&modal, &y0).unwrap();
    let mut total = 0.0;
    for k in 0..100 {
        let s = 0.37 * k as f64;
        let p = motion.at(&modal, s);
        let b = motion.bound(&modal, s, s + 0.37);
        total += p.value[0] + b.acceleration;
    }
    let c = modal.modal_coordinates(&y0).unwrap();
    let mut y = [0.0; 16];
    modal.state(&c, 12.0, &mut y);
    let h = HarmonicResponse::new(&rotor.second_order(), 0.7, &force, &[]).unwrap();
    h.state(1.0, &mut y);
    let mut ev = [Complex::ZERO; 16];
    eigenvalues(&a, &mut ev).unwrap();
    let after = ALLOCATIONS.with(Cell::get);
    assert_eq!(after, before, "linalg allocated {} times", after - before);
    assert!(total.is_finite());
}
