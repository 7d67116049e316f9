//! Every method on a rotor from matrices allocates nothing: a counting global allocator sees no
//! allocation on the test's thread while `MatrixPropagator` is built and runs the ring's heavy
//! rub with friction (contact, reversal, rolling) for 10 forcing periods, events and samples.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

use rotor_rub::matrix::{MatrixPropagator, ring_model, ring_start};
use rotor_rub::method::{Method, Options};
use rotor_rub::{Parameter, Preset, Propagate};

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
fn every_method_runs_without_allocating() {
    let mut problem = Preset::Paper.problem();
    for (p, v) in [
        (Parameter::KXx, 100.0),
        (Parameter::KXy, 0.0),
        (Parameter::KYx, 0.0),
        (Parameter::KYy, 100.0),
        (Parameter::FrictionCoefficient, 0.6),
        (Parameter::RadiusRatio, 1.0),
        (Parameter::StatorMassRatio, 0.2),
        (Parameter::ContactStiffness, 300.0),
        (Parameter::StatorDamping, 0.5),
    ] {
        p.set(&mut problem, v);
    }
    let model = Box::new(ring_model(&problem.params).expect("the ring states"));
    let end = 10.0 * problem.params.forcing_period();
    for method in [
        Method::Dop853,
        Method::Rk45,
        Method::Hybrid,
        Method::Taylor,
        Method::Analytic,
    ] {
        let options = Options::with_method(method);
        COUNTED.with(|c| c.set(true));
        let before = ALLOCATIONS.load(Ordering::SeqCst);
        let mut p = Box::new(
            MatrixPropagator::new(&*model, 0.0, ring_start(&problem), &options)
                .expect("the method starts"),
        );
        let (mut events, mut t) = (0, 0.0);
        while t < end {
            t = (t + 0.05).min(end);
            while p.advance(t).expect("the run goes on").is_some() {
                events += 1;
            }
        }
        let after = ALLOCATIONS.load(Ordering::SeqCst);
        COUNTED.with(|c| c.set(false));
        // The one Box holding the propagator is the test's.
        assert_eq!(
            after - before,
            1,
            "{method:?} allocated {} times",
            after - before - 1
        );
        assert!(events > 100, "{method:?}: {events} events");
    }
}
